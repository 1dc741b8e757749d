#include "pipeline/process_groups.h"

#include "common/error.h"
#include "pipeline/spawn.h"
#include "pipeline/task_runner.h"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>

namespace clearjoint::pipeline
{
  namespace
  {
    std::array<std::atomic<pid_t>, max_process_groups> groups{};

    void register_group(const pid_t pgid)
    {
      for (auto &slot : groups)
      {
        pid_t empty = 0;
        if (slot.compare_exchange_strong(empty, pgid))
          return;
      }
      // Cannot happen with jobs <= max_jobs; never run a stage that an interrupt cannot reach.
      ::kill(-pgid, SIGKILL);
      throw NumericalError("run_pipeline: more than " + std::to_string(max_process_groups) +
                           " stages at once");
    }
  } // namespace

  pid_t spawn_in_own_group(const std::vector<std::string> &words, const std::string &log_path)
  {
    pid_t pid = 0;
    // Block the signals while the group is started and registered, so that a handler never
    // misses a group that exists.
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigprocmask(SIG_BLOCK, &block, &old);
    // The stage starts with our mask as it was (not the block above) and with SIGINT and
    // SIGTERM at their defaults, even if run_pipeline was started with them ignored (nohup).
    SpawnOptions options;
    options.append_to = log_path;
    options.mask = &old;
    options.defaults = &block;
    const int rc = spawn_in_new_group(words, options, pid);
    if (rc == 0)
      try
      {
        register_group(pid);
      }
      catch (...)
      {
        sigprocmask(SIG_SETMASK, &old, nullptr);
        throw;
      }
    sigprocmask(SIG_SETMASK, &old, nullptr);
    if (rc != 0)
      throw NumericalError("cannot start '" + words[0] + "': " + std::strerror(rc));
    if (interrupt_requested())
      ::kill(-pid, SIGTERM);
    return pid;
  }

  bool end_group(const pid_t pgid)
  {
    // The leader is reaped but its group id stays in use (and is not reused as a pid) while
    // any member lives, so this reaches only what the stage left behind.
    const bool left = ::kill(-pgid, SIGKILL) == 0;
    for (auto &slot : groups)
    {
      pid_t expected = pgid;
      if (slot.compare_exchange_strong(expected, 0))
        break;
    }
    return left;
  }

  void signal_groups(const int sig)
  {
    for (auto &slot : groups)
      if (const pid_t g = slot.load(); g > 0)
        ::kill(-g, sig);
  }

  int n_groups()
  {
    int n = 0;
    for (const auto &slot : groups)
      n += slot.load() > 0 ? 1 : 0;
    return n;
  }
} // namespace clearjoint::pipeline
