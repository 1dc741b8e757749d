// The stages run_pipeline starts, each in a process group of its own (issue 33): a one-rank
// stage and its plot.py child are in its group, so one kill(-group) reaches them all. A stage
// under mpirun is different: Open MPI puts every rank in a process group of its own, so the
// group holds mpirun alone; mpirun passes a SIGINT/SIGTERM on to its ranks (as SIGCONT, then
// SIGTERM 1 s later, then SIGKILL), and a rank's plot.py ends itself when its rank dies
// (PR_SET_PDEATHSIG, scripts/plot.py).
// The groups are kept in a fixed table that the SIGINT/SIGTERM handler walks
// (async-signal-safe: atomics only), so an interrupt reaches every running stage at once.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  /// Most process groups run_pipeline keeps at once (at least max_jobs, executor_config.h).
  inline constexpr int max_process_groups = 1024;

  /// Starts `words` (argv[0] looked up on PATH) as the leader of a new process group with
  /// stdout and stderr appended to `log_path`, and registers the group. If an interrupt was
  /// already requested the group gets SIGTERM at once. Throws NumericalError if it cannot start.
  pid_t spawn_in_own_group(const std::vector<std::string> &words, const std::string &log_path);

  /// Call after the leader was reaped: ends whatever is left of its group with SIGKILL (a
  /// plot.py child of a stage that was killed would otherwise go on writing into the task's
  /// folder) and forgets the group. Returns true if something was left.
  bool end_group(pid_t pgid);

  /// From a signal handler: sends `sig` to every registered group.
  void signal_groups(int sig);

  /// Registered groups now (for tests and messages).
  int n_groups();
} // namespace clearjoint::pipeline
