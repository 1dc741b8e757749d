// Runs each task as one Slurm batch job (issue 33): `sbatch` with --ntasks = the task's MPI
// ranks, a time limit from the preset's measured time × time_margin, the task's log as the
// job's output (appended, so a requeued job keeps the first attempt's lines). One `squeue`
// call every poll_interval seconds follows all of run_pipeline's jobs; a job's exit status
// comes from a file its script writes (<dir>.exit), its end state from squeue (or sacct once
// squeue has forgotten it). An interrupt cancels every job with one `scancel`.
//
// Why sbatch and not srun inside the caller's allocation: a sweep of hundreds of FE cases is
// the cluster's to schedule (backfill, fair share, other users), one job per task as sites
// expect from Snakemake and Nextflow; run_pipeline itself needs no allocation and can run on
// a login node. The stage executables and the output root must be on a file system the
// compute nodes share.
#pragma once

#include "pipeline/command_capture.h"
#include "pipeline/executor.h"
#include "pipeline/executor_config.h"

#include <chrono>
#include <map>

namespace clearjoint::pipeline
{
  class SlurmExecutor : public Executor
  {
  public:
    SlurmExecutor(SlurmSettings settings, int jobs);
    /// Cancels every job still queued or running (nothing is left behind on any error).
    ~SlurmExecutor() override;

    /// InputError naming `file`'s executor key unless sbatch, squeue and scancel are on PATH
    /// and the controller answers (squeue within command_timeout).
    static void check_available(const SlurmSettings &settings, const std::string &file);

    std::string kind() const override { return "slurm"; }
    int capacity() const override { return jobs_; }
    int slots_for(int) const override { return 1; }  ///< one job, whatever its ranks
    std::vector<std::string> launcher(int ranks) const override;
    void start(const Launch &launch) override;
    std::vector<Ended> wait_any() override;
    std::vector<int> stop_all() override;
    int n_running() const override { return int(jobs_running_.size()); }

    /// The time limit [min] of a task expected to take `expected_seconds` (0: unknown).
    int time_limit_minutes(double expected_seconds) const;

  private:
    struct Job
    {
      int node;
      std::string name, prefix, log_path, exit_file;  ///< prefix: <dir>
      int time_limit_min;
      int polls_missing = 0;  ///< polls in a row that squeue did not list it
    };
    /// One squeue call for every job: job id → state; nullopt if squeue failed.
    std::optional<std::map<std::string, std::string>> query_states();
    /// The end of a job squeue no longer lists: its exit file, or sacct, or unknown.
    Ended forgotten(const std::string &id, const Job &job);
    Ended ended(const std::string &id, const Job &job, const std::string &state);
    CommandResult run(const std::vector<std::string> &words) const;
    /// Cancels (and waits for, at most 60 s) a job that an earlier run_pipeline left running
    /// for this task (<dir>.job.json), so that two jobs never write into one .partial folder.
    void cancel_earlier_job(const std::string &work_prefix);

    SlurmSettings settings_;
    int jobs_;
    std::map<std::string, Job> jobs_running_;  ///< job id → job
    int failed_queries_ = 0;
  };
} // namespace clearjoint::pipeline
