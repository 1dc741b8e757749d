#include "pipeline/process_groups.h"

#include "common/error.h"
#include "pipeline/task_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>

extern char **environ;

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
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setpgroup(&attr, 0);
    std::vector<char *> argv;
    for (const auto &w : words)
      argv.push_back(const_cast<char *>(w.c_str()));
    argv.push_back(nullptr);
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
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK |
                                      POSIX_SPAWN_SETSIGDEF);
    posix_spawnattr_setsigmask(&attr, &old);
    posix_spawnattr_setsigdefault(&attr, &block);
    const int rc = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
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
