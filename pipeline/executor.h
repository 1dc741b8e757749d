// Where a prepared task runs: on this machine (local_executor.h) or as a Slurm job
// (slurm_executor.h). The scheduler (scheduler.h) decides what runs when; an executor only
// starts runs, reports the ones that ended, and stops them all on an interrupt.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct Launch
  {
    int node = -1;                       ///< the scheduler's id of the task
    std::string name;                    ///< task name, for messages and job names
    std::vector<std::string> words;      ///< the command: launcher, stage, arguments
    std::string log_path;                ///< stdout and stderr of the run
    std::string work_prefix;             ///< <dir>: executor files go to <dir>.<something>
    int ranks = 1;                       ///< MPI ranks of the stage (1: no launcher)
    double expected_seconds = 0.0;       ///< [s] the preset's measured time; 0 unknown
  };

  struct Ended
  {
    int node = -1;
    bool succeeded = false;
    /// Why it failed, e.g. "exit status 2" or "Slurm job 17 ended TIMEOUT (exit code 0:15)".
    std::string what;
    /// What the task's stamp records about where it ran (null for local runs).
    nlohmann::json record;
    /// The stage's exit status if it exited by itself (3: it could not write its output).
    std::optional<int> exit_status;
    /// Ended from outside (a signal, SIGKILL, the OOM killer; Slurm's time limit, scancel, a
    /// node failure, preemption): its log says nothing about why, so the message is one line.
    bool ended_from_outside = false;
  };

  class Executor
  {
  public:
    virtual ~Executor() = default;
    /// "local" or "slurm".
    virtual std::string kind() const = 0;
    /// Slots (local: CPU slots; slurm: jobs queued at once).
    virtual int capacity() const = 0;
    /// The slots a task on `ranks` MPI ranks takes (at most capacity(), so it can run).
    virtual int slots_for(int ranks) const = 0;
    /// What starts a stage on `ranks` MPI ranks (empty for 1): put before the executable.
    virtual std::vector<std::string> launcher(int ranks) const = 0;
    /// Starts the run; throws NumericalError if it cannot (an sbatch that fails, say).
    virtual void start(const Launch &launch) = 0;
    /// Blocks until at least one run ended or a signal arrived (then it may return nothing).
    virtual std::vector<Ended> wait_any() = 0;
    /// After an interrupt: every run is ended (signalled or cancelled) and waited for; returns
    /// the ids of the tasks that were stopped.
    virtual std::vector<int> stop_all() = 0;
    virtual int n_running() const = 0;
  };
} // namespace clearjoint::pipeline
