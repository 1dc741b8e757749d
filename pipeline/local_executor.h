// Runs tasks as processes on this machine, up to `jobs` CPU slots at once (a task on R MPI
// ranks under mpirun takes R), each stage in a process group of its own (process_groups.h).
#pragma once

#include "pipeline/executor.h"

#include <sys/types.h>

#include <map>

namespace clearjoint::pipeline
{
  class LocalExecutor : public Executor
  {
  public:
    explicit LocalExecutor(int jobs);
    /// Ends every stage still running (SIGTERM to its group, then waits): nothing outlives
    /// the pipeline, whatever error ended it.
    ~LocalExecutor() override;
    std::string kind() const override { return "local"; }
    int capacity() const override { return jobs_; }
    int slots_for(int ranks) const override;
    std::vector<std::string> launcher(int ranks) const override;
    void start(const Launch &launch) override;
    std::vector<Ended> wait_any() override;
    std::vector<int> stop_all() override;
    int n_running() const override { return int(running_.size()); }

  private:
    /// Reaps `pid` (already waited for) with its wait status.
    Ended reaped(pid_t pid, int status);

    int jobs_;
    struct Running
    {
      int node;
      std::string name;
    };
    std::map<pid_t, Running> running_;  ///< process group leader → its task
  };
} // namespace clearjoint::pipeline
