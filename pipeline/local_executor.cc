#include "pipeline/local_executor.h"

#include "common/error.h"
#include "common/log.h"
#include "pipeline/process_groups.h"

#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <signal.h>

namespace clearjoint::pipeline
{
  LocalExecutor::LocalExecutor(const int jobs)
    : jobs_(jobs)
  {}

  LocalExecutor::~LocalExecutor()
  {
    for (const auto &[pid, r] : running_)
      ::kill(-pid, SIGTERM);
    for (const auto &[pid, r] : running_)
    {
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
      {
      }
      end_group(pid);
    }
  }

  int LocalExecutor::slots_for(const int ranks) const { return std::clamp(ranks, 1, jobs_); }

  std::vector<std::string> LocalExecutor::launcher(const int ranks) const
  {
    if (ranks <= 1)
      return {};
    return {"mpirun", "--allow-run-as-root", "--oversubscribe", "-np", std::to_string(ranks)};
  }

  void LocalExecutor::start(const Launch &launch)
  {
    const pid_t pid = spawn_in_own_group(launch.words, launch.log_path);
    running_[pid] = {launch.node, launch.name};
  }

  Ended LocalExecutor::reaped(const pid_t pid, const int status)
  {
    Ended e;
    const Running r = running_.at(pid);
    e.node = r.node;
    running_.erase(pid);
    if (end_group(pid))
      log::warning("run_pipeline: the stage of task " + r.name +
                   " left processes in its group (a plot.py child, say); they were killed");
    e.succeeded = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (WIFEXITED(status))
    {
      e.what = "exit status " + std::to_string(WEXITSTATUS(status));
      e.exit_status = WEXITSTATUS(status);
    }
    else if (WIFSIGNALED(status))
    {
      e.what = std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
               strsignal(WTERMSIG(status)) + ")";
      e.ended_from_outside = true;
    }
    else
      e.what = "ended with wait status " + std::to_string(status);
    return e;
  }

  std::vector<Ended> LocalExecutor::wait_any()
  {
    // Only our stages are our children while the scheduler runs; any other child is reaped
    // and ignored. Bounded: each pass reaps one child, or returns on a signal.
    for (std::size_t pass = 0; pass <= running_.size() + 16; ++pass)
    {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, 0);
      if (pid < 0)
      {
        if (errno == EINTR)
          return {};  // a signal: the scheduler looks at the interrupt flag
        throw NumericalError(std::string("run_pipeline: waitpid failed: ") + std::strerror(errno));
      }
      if (running_.count(pid))
        return {reaped(pid, status)};
    }
    return {};
  }

  std::vector<int> LocalExecutor::stop_all()
  {
    // The signal handler has already passed the signal on to every group; wait for them to
    // end (the stages stop at their next safe point and remove their temporary files). A
    // second Ctrl-C ends run_pipeline at once (common/interrupt.h).
    std::vector<int> stopped;
    for (std::size_t pass = 0; !running_.empty() && pass < 1000000; ++pass)
    {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, 0);
      if (pid < 0 && errno != EINTR)
        break;
      if (pid > 0 && running_.count(pid))
        stopped.push_back(reaped(pid, status).node);
    }
    for (const auto &[pid, r] : running_)  // only if waitpid failed: do not leave them
    {
      ::kill(-pid, SIGKILL);
      end_group(pid);
      stopped.push_back(r.node);
    }
    running_.clear();
    return stopped;
  }
} // namespace clearjoint::pipeline
