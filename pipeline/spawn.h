// Starting a child process, the one place run_pipeline calls posix_spawn (stages in
// process_groups.cc, short commands such as sbatch in command_capture.cc): argv[0] looked up on
// PATH, the child leader of a new process group, its stdout and stderr sent to a log file or
// to a pipe.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct SpawnOptions
  {
    std::string append_to;   ///< stdout and stderr appended to this file (if not empty)
    int output_fd = -1;      ///< else, if >= 0: stdout and stderr to this descriptor
    bool stdin_null = false; ///< stdin from /dev/null
    /// The child's signal mask and the signals it starts with at their defaults (nullptr:
    /// inherited as they are).
    const sigset_t *mask = nullptr;
    const sigset_t *defaults = nullptr;
  };

  /// Starts `words` as the leader of a new process group. Returns 0 and sets `pid`, or the
  /// error number (errno) why it could not start.
  int spawn_in_new_group(const std::vector<std::string> &words, const SpawnOptions &options,
                         pid_t &pid);
} // namespace clearjoint::pipeline
