#include "pipeline/spawn.h"

#include <fcntl.h>
#include <cerrno>
#include <spawn.h>
#include <unistd.h>

extern char **environ;

namespace clearjoint::pipeline
{
  int spawn_in_new_group(const std::vector<std::string> &words, const SpawnOptions &o, pid_t &pid)
  {
    if (words.empty())
      return EINVAL;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!o.append_to.empty())
    {
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, o.append_to.c_str(),
                                       O_WRONLY | O_CREAT | O_APPEND, 0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    else if (o.output_fd >= 0)
    {
      posix_spawn_file_actions_adddup2(&actions, o.output_fd, STDOUT_FILENO);
      posix_spawn_file_actions_adddup2(&actions, o.output_fd, STDERR_FILENO);
    }
    if (o.stdin_null)
      posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    short flags = POSIX_SPAWN_SETPGROUP;
    posix_spawnattr_setpgroup(&attr, 0);
    if (o.mask)
    {
      flags |= POSIX_SPAWN_SETSIGMASK;
      posix_spawnattr_setsigmask(&attr, o.mask);
    }
    if (o.defaults)
    {
      flags |= POSIX_SPAWN_SETSIGDEF;
      posix_spawnattr_setsigdefault(&attr, o.defaults);
    }
    posix_spawnattr_setflags(&attr, flags);
    std::vector<char *> argv;
    for (const auto &w : words)
      argv.push_back(const_cast<char *>(w.c_str()));
    argv.push_back(nullptr);
    const int rc = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    return rc;
  }
} // namespace clearjoint::pipeline
