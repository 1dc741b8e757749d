// The pipeline's tasks as a dependency graph (issue 33): PipelineRunner adds every task with
// the tasks it needs, and the scheduler (scheduler.h) runs each once those are done, as many
// at once as the executor has slots. A task may add more tasks when it is done (the
// confidence-band MBD runs exist only once the fitted law is known).
#pragma once

#include "pipeline/task_runner.h"

#include <deque>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  class TaskGraph;

  struct GraphNode
  {
    Task task;                ///< depends_on is filled in by the scheduler (below)
    std::string group;        ///< fe | fit | mbd: the stage `--only` names
    /// Ids of the tasks that must be done first (each smaller than this node's id); their
    /// identities become task.depends_on, in this order.
    std::vector<int> after;
    int ranks = 1;            ///< MPI ranks of the stage (slots it takes, ranks of its job)
    /// The chosen preset's measured time of this task [s] (presets.h task_figure), the key of
    /// `measured` it comes from and the preset's name: printed beside the task's time.
    std::optional<double> figure_seconds;
    std::string figure_key, figure_preset;
    /// Called once every `after` task is done, before the identity is computed (e.g. to
    /// write a file the task reads). May throw.
    std::function<void(Task &)> prepare;
    /// Called when the task is done (ran or reused); may add nodes to the graph.
    std::vector<std::function<void(TaskGraph &, const TaskResult &)>> on_done;
    /// If set, a failure of this task does not stop the run: called with the message (the
    /// rolling study, docs/pipeline.md); tasks after it are skipped.
    std::function<void(const std::string &)> on_failure;
  };

  class TaskGraph
  {
  public:
    /// Returns the node's id. Throws std::logic_error if an `after` id is not smaller.
    int add(GraphNode node)
    {
      const int id = int(nodes_.size());
      for (const int a : node.after)
        if (a < 0 || a >= id)
          throw std::logic_error("task graph: " + node.task.name + " after a later task");
      nodes_.push_back(std::move(node));
      return id;
    }
    int size() const { return int(nodes_.size()); }
    GraphNode &node(const int id) { return nodes_.at(id); }
    const GraphNode &node(const int id) const { return nodes_.at(id); }

  private:
    std::deque<GraphNode> nodes_;  ///< a deque: references stay valid while nodes are added
  };
} // namespace clearjoint::pipeline
