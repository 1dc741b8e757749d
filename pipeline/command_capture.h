// Runs a short command (sbatch, squeue, scancel, sacct) and captures its output, with a time
// limit: a Slurm controller that does not answer must not hang run_pipeline.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct CommandResult
  {
    int exit_code = -1;       ///< -1: did not exit normally, timed out or could not start
    bool timed_out = false;
    std::string output;       ///< stdout and stderr together (at most 1 MiB kept)
    std::string start_error;  ///< why it could not start, else empty
  };

  /// Runs `words` (argv[0] looked up on PATH) in a process group of its own; after
  /// `timeout_s` seconds the group is killed and timed_out set. Never throws for the
  /// command's own failure.
  CommandResult run_capture(const std::vector<std::string> &words, double timeout_s);

  /// The absolute path of `name` found on $PATH, if any.
  std::optional<std::string> find_on_path(const std::string &name);
} // namespace clearjoint::pipeline
