#include "pipeline/task_runner.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/sha256.h"
#include "pipeline/process_groups.h"

#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>

#include <cerrno>
#include <filesystem>
#include <optional>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  namespace
  {
    void on_signal(const int sig)
    {
      interrupt_requested() = true;
      signal_groups(sig);  // every running stage's group (mpirun and its ranks, plot.py)
    }

    std::string stamp_path(const std::string &dir) { return dir + "/.task.json"; }

    /// The wall time recorded when the task ran, if its stamp carries `identity`.
    std::optional<double> stamp_matches(const std::string &dir, const std::string &identity)
    {
      try
      {
        const auto j = parse_json_string(read_file(stamp_path(dir)), stamp_path(dir));
        if (j.at("identity").get<std::string>() == identity)
          return j.at("wall_time").at("value").get<double>();
      }
      catch (...)
      {
      }
      return std::nullopt;
    }

    /// The stages record output paths in their manifests as they wrote them, inside
    /// "<dir>.partial"; after the rename those paths are "<dir>". Rewrite them so a manifest
    /// never points at a directory that no longer exists.
    void repoint_manifests(const std::string &dir, const std::string &partial)
    {
      for (const auto &entry : fs::recursive_directory_iterator(dir))
      {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() ||
            !(name == "manifest.json" || (name.size() > 14 &&
                                          name.compare(name.size() - 14, 14, ".manifest.json") == 0)))
          continue;
        std::string text = read_file(entry.path().string());
        for (std::size_t p; (p = text.find(partial)) != std::string::npos;)
          text.replace(p, partial.size(), dir);
        write_file_atomically(entry.path().string(), text);
      }
    }

  } // namespace

  std::atomic<bool> &interrupt_requested()
  {
    static std::atomic<bool> flag{false};
    return flag;
  }

  void install_signal_handlers()
  {
    // The common handler (also seen by run_plot_script, which then stops the report's plot.py)
    // with on_signal as its hook: the running stage gets the signal too.
    interrupt::install(on_signal);
  }

  int run_process(const std::vector<std::string> &words, const std::string &log_path)
  {
    const pid_t pid = spawn_in_own_group(words, log_path);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
      if (errno != EINTR)
        break;
    end_group(pid);
    return status;
  }

  std::string compute_identity(const Task &t)
  {
    nlohmann::json j;
    j["stage"] = t.stage;
    j["executable_sha256"] = sha256_file(t.executable);
    j["args"] = t.args;
    j["inputs"] = nlohmann::json::array();
    for (const auto &f : t.input_files)
      j["inputs"].push_back(sha256_file(f));
    j["depends_on"] = t.depends_on;
    return sha256_hex(json_text(j, -1));
  }

  std::optional<TaskResult> find_completed(const Task &t, const std::string &identity)
  {
    if (const auto seconds = stamp_matches(t.output_dir, identity))
      return TaskResult{TaskOutcome::reused, identity, *seconds};
    return std::nullopt;
  }

  std::optional<TaskResult> find_completed(const Task &t)
  {
    return find_completed(t, compute_identity(t));
  }

  PreparedRun prepare_run(const Task &t, const std::string &identity)
  {
    PreparedRun r;
    r.identity = identity;
    r.partial = t.output_dir + ".partial";
    fs::remove_all(r.partial);
    fs::create_directories(r.partial);
    r.words = t.launcher;
    r.words.push_back(t.executable);
    for (auto a : t.args)
    {
      for (std::size_t p; (p = a.find("{out}")) != std::string::npos;)
        a.replace(p, 5, r.partial);
      r.words.push_back(a);
    }
    // The log and the command line sit beside the partial folder while the stage runs (a stage
    // may replace its whole output folder), and move into the result when it succeeds.
    r.log_path = t.output_dir + ".log";
    r.command_path = t.output_dir + ".command.txt";
    fs::remove(r.log_path);
    AtomicFile cmd(r.command_path);
    for (const auto &w : r.words)
      cmd.stream() << w << ' ';
    cmd.stream() << '\n';
    cmd.commit();
    return r;
  }

  std::string failure_message(const Task &t, const std::string &log_path, const std::string &what)
  {
    std::string tail;
    try
    {
      const std::string all = read_file(log_path);
      tail = all.substr(all.size() > 2000 ? all.size() - 2000 : 0);
    }
    catch (...)
    {
      tail = "(no log)";
    }
    return t.stage + " failed in task " + t.name + " (" + what + "); its log " + log_path +
           " ends with:\n" + tail;
  }

  std::string ended_message(const Task &t, const std::string &log_path, const std::string &what)
  {
    return t.stage + " in task " + t.name + ": " + what + "; its log: " + log_path;
  }

  std::string write_failure_message(const Task &t, const std::string &log_path)
  {
    // The stage's last line: "error: <stage>: cannot write '<file>': <reason>; ..."
    std::string line = "could not write its output (exit status 3)";
    try
    {
      const std::string all = read_file(log_path);
      const auto at = all.rfind("cannot write '");
      if (at != std::string::npos)
      {
        line = all.substr(at, all.find('\n', at) - at);
        line = line.substr(0, line.find("; "));  // what the stage removed: said below
      }
    }
    catch (...)
    {
    }
    return t.stage + " in task " + t.name + ": " + line +
           "; nothing of the task kept, the next run redoes it; its log: " + log_path;
  }

  TaskResult complete_run(const Task &t, const PreparedRun &run, const double seconds,
                          const nlohmann::json &executor)
  {
    fs::remove_all(t.output_dir);
    fs::rename(run.partial, t.output_dir);
    fs::rename(run.log_path, t.output_dir + "/stage.log");
    fs::rename(run.command_path, t.output_dir + "/command.txt");
    repoint_manifests(t.output_dir, run.partial);
    nlohmann::json stamp = {{"schema", "clearjoint.task/1"},
                            {"task", t.name},
                            {"identity", run.identity},
                            {"wall_time", {{"value", seconds}, {"unit", "s"}}}};
    if (!executor.is_null())
      stamp["executor"] = executor;
    write_file_atomically(stamp_path(t.output_dir), json_text(stamp) + "\n");
    return {TaskOutcome::ran, run.identity, seconds};
  }
} // namespace clearjoint::pipeline
