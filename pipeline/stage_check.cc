#include "pipeline/stage_check.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "pipeline/process_groups.h"
#include "pipeline/task_runner.h"

#include <algorithm>
#include <cerrno>

#include <signal.h>

#include <sys/wait.h>

namespace clearjoint::pipeline
{
  namespace
  {
    /// "clearance_joints[0].normal" → "clearance_joints.0.normal": the pipeline's spelling.
    std::string dotted(const std::string &path)
    {
      std::string out;
      for (const char c : path)
        if (c == '[')
          out += '.';
        else if (c != ']')
          out += c;
      return out;
    }

    bool related(const std::string &a, const std::string &b)
    {
      return a == b || a.rfind(b + ".", 0) == 0 || b.rfind(a + ".", 0) == 0;
    }

    /// The key path an InputError message names ("... key 'a.b' has value ..."), or "".
    std::string failing_key(const std::string &message)
    {
      const auto p = message.find("key '");
      if (p == std::string::npos)
        return "";
      const auto q = message.find('\'', p + 5);
      return q == std::string::npos ? "" : message.substr(p + 5, q - p - 5);
    }

    /// The stage's error message: from "input error" to the end of that line.
    std::string error_line(const std::string &log)
    {
      const auto p = log.find("input error");
      if (p == std::string::npos)
        return log.substr(log.size() > 1000 ? log.size() - 1000 : 0);
      const auto e = log.find('\n', p);
      return log.substr(p, e == std::string::npos ? std::string::npos : e - p);
    }

    /// Throws the error a failed check is reported as (the class comment in stage_check.h).
    [[noreturn]] void report_failure(const StageCheck &check, const int status,
                                     const std::string &log_path,
                                     const std::vector<Origin> &origins,
                                     const std::string &base_key, const std::string &what)
    {
      const std::string &stage = check.stage, &src = check.source;
      std::string log;
      try
        {
          log = read_file(log_path);
        }
      catch (...)
        {}
      if (!WIFEXITED(status) || WEXITSTATUS(status) != exit_input_error)
        throw NumericalError(
          stage + " --check failed on the generated scene of " + what + " (exit status " +
          std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "): " + error_line(log));
      const std::string scene_key = dotted(failing_key(error_line(log)));
      // The last override applied to that key (or to a key above or below it) made it.
      for (auto it = origins.rbegin(); it != origins.rend(); ++it)
        if (!scene_key.empty() && related(dotted(it->scene_key), scene_key))
          throw InputError(src, it->pipeline_key, json_excerpt(it->value),
                           "a value " + stage + " accepts",
                           what + ": " + stage + " reports: " + error_line(log));
      throw InputError(src, base_key, what,
                       (stage == "fit_stage" ? "a command " : "a scene ") + stage + " accepts",
                       stage + " reports: " + error_line(log));
    }
  } // namespace

  StageChecks::StageChecks(const int at_once)
    : at_once_(static_cast<std::size_t>(std::max(1, at_once)))
  {}

  StageChecks::~StageChecks()
  {
    for (Pending &p : checks_)
      if (p.running)
        {
          ::kill(p.pid, SIGKILL);
          wait_for(p);
        }
  }

  void StageChecks::wait_for(Pending &p)
  {
    while (::waitpid(p.pid, &p.status, 0) < 0)
      if (errno != EINTR)
        {
          // not ours to reap (cannot happen unless something else waited for it): a failure
          // with the shell's "cannot run" status, never a pass
          p.status = 127 << 8;
          break;
        }
    end_group(p.pid);
    p.running = false;
  }

  void StageChecks::add(const StageCheck &check, std::vector<std::string> args,
                        const std::string &log_path, const std::vector<Origin> &origins,
                        const std::string &base_key, const std::string &what)
  {
    if (interrupt_requested())
      throw NumericalError("interrupted while checking the scenes; nothing was written");
    // The oldest first: the checks take about as long as each other.
    while (checks_.size() - oldest_running_ >= at_once_)
      wait_for(checks_[oldest_running_++]);
    args.insert(args.begin(), check.executable);
    args.push_back("--check");
    args.push_back("-q");
    Pending p{check, log_path, origins, base_key, what};
    p.pid = spawn_in_own_group(args, log_path);
    p.running = true;
    checks_.push_back(std::move(p));
  }

  void StageChecks::finish()
  {
    while (oldest_running_ < checks_.size())
      wait_for(checks_[oldest_running_++]);
    if (interrupt_requested())
      throw NumericalError("interrupted while checking the scenes; nothing was written");
    for (const Pending &p : checks_)
      if (!WIFEXITED(p.status) || WEXITSTATUS(p.status) != 0)
        report_failure(p.check, p.status, p.log_path, p.origins, p.base_key, p.what);
  }
} // namespace clearjoint::pipeline
