// Where run_pipeline runs its tasks and how many at once: pipeline.yaml `jobs` and `executor`
// (docs/pipeline.md, "Tasks at once" and "Running on a cluster").
#pragma once

#include "common/strict_reader.h"

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  /// Largest `jobs` accepted: slots on this machine (local) or jobs queued at once (slurm).
  inline constexpr int max_jobs = 1000;
  /// Default `jobs` with the Slurm executor: jobs in the queue at once (the cluster, not this
  /// machine, decides how many run).
  inline constexpr int default_slurm_jobs = 100;

  struct SlurmSettings
  {
    std::optional<std::string> partition, account, qos;  ///< sbatch --partition/--account/--qos
    /// A task's time limit is its preset's measured time [s] × time_margin, in whole minutes,
    /// at least 1 min.
    double time_margin = 3.0;
    /// [min] the time limit of a task whose preset time is not measured.
    double time_unmeasured = 60.0;
    /// [s] how often run_pipeline asks the controller (one squeue call for all its jobs).
    double poll_interval = 10.0;
    /// [s] how long one Slurm command may take before the controller counts as not answering.
    double command_timeout = 60.0;
    /// How an MPI task starts its ranks inside its job: "mpirun" (Open MPI reads the
    /// allocation) or "srun" (srun --mpi=<srun_mpi>).
    std::string mpi_launcher = "mpirun";
    std::string srun_mpi = "pmix";
    std::vector<std::string> sbatch_args;  ///< passed to every sbatch as they are (--mem=4G, ...)
  };

  struct ExecutorConfig
  {
    std::string kind = "local";  ///< local | slurm
    SlurmSettings slurm;
  };

  /// Reads the `executor` mapping (strict: unknown keys are errors naming the key path).
  ExecutorConfig read_executor_config(StrictObject executor);

  /// The machine's cores (std::thread::hardware_concurrency, at least 1).
  int machine_cores();

  /// `--jobs` (or `jobs:`) checked: InputError naming `key` unless 1 <= jobs <= max_jobs.
  int checked_jobs(long jobs, const std::string &file, const std::string &key);
} // namespace clearjoint::pipeline
