// Runs a TaskGraph on an Executor (issue 33): every task whose upstream tasks are done is
// reused (its stamp matches) or started while the executor has free slots, the longest chain
// of tasks first (start_order() below; issue 32 item 5). After a failure nothing new starts;
// the running tasks end normally (their results are kept) and then the failure is thrown. On
// SIGINT/SIGTERM every running task is stopped (executor.stop_all) and an error naming them
// is thrown; their `<dir>.partial/` folders are redone by the next run.
#pragma once

#include "pipeline/executor.h"
#include "pipeline/run_eta.h"
#include "pipeline/task_graph.h"

#include <chrono>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct ScheduleOptions
  {
    bool force = false;               ///< run every task, stamps or not
    std::optional<std::string> only;  ///< outside this group a task must be done already
  };

  enum class NodeState { waiting, running, done, failed, skipped };

  struct NodeStatus
  {
    NodeState state = NodeState::waiting;
    bool prepared = false;      ///< prepare() ran; `task` and `identity` are final
    Task task;                  ///< as run: depends_on and launcher filled in
    std::string identity;
    TaskResult result{};        ///< when done
    nlohmann::json record;      ///< the executor's record (e.g. the Slurm job id)
    PreparedRun run;            ///< when it ran
    int slots = 0;
    std::chrono::steady_clock::time_point start;
  };

  class Scheduler
  {
  public:
    /// expected_seconds(stage): the preset's measured time of one task of the stage [s], 0
    /// when unknown (for a Slurm job's time limit and the start order).
    Scheduler(TaskGraph &graph, Executor &executor, ScheduleOptions options, RunEta *eta,
              std::function<double(const std::string &)> expected_seconds);
    void run();
    const NodeStatus &status(int id) const { return status_.at(id); }

  private:
    /// A task's expected time [s], for the start order only: its preset figure
    /// (GraphNode::figure_seconds), else expected_seconds(stage), else unknown_task_seconds.
    double expected_task_seconds(int id) const;
    /// Every task's id, the longest chain first: by the sum of expected times along the
    /// longest path from the task to the end of the graph through the tasks after it
    /// (critical-path list scheduling), ties by id. Always a topological order.
    std::vector<int> start_order() const;
    /// Reuses or starts every ready task the free slots allow, in start_order(); true if any
    /// was.
    bool start_ready();
    /// Reuses or starts one ready task; false if it has to wait for slots (or failed).
    bool start(int id);
    void done(int id, const TaskResult &result);
    void ended(const Ended &e);
    void fail(std::exception_ptr error);
    [[noreturn]] void stop_on_interrupt();

    TaskGraph &graph_;
    Executor &executor_;
    ScheduleOptions options_;
    RunEta *eta_;
    std::function<double(const std::string &)> expected_seconds_;
    std::vector<NodeStatus> status_;
    int used_slots_ = 0;
    std::exception_ptr first_error_;
  };
} // namespace clearjoint::pipeline
