#include "pipeline/scheduler.h"

#include "common/error.h"
#include "common/log.h"
#include "pipeline/presets.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  namespace
  {
    /// [s] A task no figure covers (a fit, an MBD run, a mesh; any task of a pipeline without
    /// `measured`): these take about a second or less, so with this they cannot outrank a
    /// measured FE task (seconds to minutes), while among themselves the longer chain still
    /// goes first — with 0 they would add nothing to a chain.
    constexpr double unknown_task_seconds = 1.0;
  } // namespace

  Scheduler::Scheduler(TaskGraph &graph, Executor &executor, ScheduleOptions options,
                       RunEta *eta, std::function<double(const std::string &)> expected_seconds)
    : graph_(graph)
    , executor_(executor)
    , options_(std::move(options))
    , eta_(eta)
    , expected_seconds_(std::move(expected_seconds))
  {}

  void Scheduler::fail(std::exception_ptr error)
  {
    if (!first_error_)
      first_error_ = error;
    if (executor_.n_running() > 0)
      log::info("run_pipeline: no new tasks; waiting for the " +
                std::to_string(executor_.n_running()) + " running to end (Ctrl-C stops them)");
  }

  void Scheduler::done(const int id, const TaskResult &result)
  {
    NodeStatus &s = status_.at(id);
    s.state = NodeState::done;
    s.result = result;
    if (eta_)
      eta_->finished(s.task.stage, result.outcome == TaskOutcome::ran, result.wall_time_s);
    // Callbacks may add nodes: take a copy, the deque keeps the node itself in place.
    const auto callbacks = graph_.node(id).on_done;
    for (const auto &f : callbacks)
      f(graph_, result);
  }

  bool Scheduler::start(const int id)
  {
    GraphNode &node = graph_.node(id);
    NodeStatus &s = status_.at(id);
    if (!s.prepared)
    {
      s.task = node.task;
      s.task.depends_on.clear();
      for (const int a : node.after)
        s.task.depends_on.push_back(status_.at(a).result.identity);
      if (node.prepare)
        node.prepare(s.task);
      s.identity = compute_identity(s.task);
      s.prepared = true;
      const bool outside_only = options_.only && *options_.only != node.group;
      const auto earlier = (outside_only || !options_.force) ? find_completed(s.task, s.identity)
                                                             : std::nullopt;
      if (outside_only && !earlier)
        throw InputError("", "--only " + *options_.only, s.task.name,
                         "upstream tasks already run and up to date",
                         "task '" + s.task.name + "' is missing or out of date: run without --only");
      if (earlier)
      {
        if (eta_)
          log::info(eta_->describe_next(executor_.n_running()) + ": " + s.task.name);
        log::info("  reused  " + s.task.name + "  (inputs unchanged)");
        done(id, *earlier);
        return true;
      }
    }
    const int slots = executor_.slots_for(node.ranks);
    if (used_slots_ + slots > executor_.capacity())
      return false;
    s.task.launcher = executor_.launcher(node.ranks);
    s.run = prepare_run(s.task, s.identity);
    Launch launch;
    launch.node = id;
    launch.name = s.task.name;
    launch.words = s.run.words;
    launch.log_path = s.run.log_path;
    launch.work_prefix = s.task.output_dir;
    launch.ranks = node.ranks;
    launch.expected_seconds = expected_seconds_ ? expected_seconds_(s.task.stage) : 0.0;
    if (eta_)
      log::info(eta_->describe_next(executor_.n_running()) + ": " + s.task.name);
    executor_.start(launch);
    s.slots = slots;
    used_slots_ += slots;
    s.start = std::chrono::steady_clock::now();
    s.state = NodeState::running;
    log::info("  running " + s.task.name + "  (log: " + s.run.log_path + ")");
    return true;
  }

  double Scheduler::expected_task_seconds(const int id) const
  {
    // The figure of this very task is the best guess (an FE case of its own sweep); the
    // stage's time is one guess for every task of the stage (RunEta::expected_seconds: 0 when
    // not measured, and for fits and MBD runs when the FE figures use up the preset's whole
    // pipeline time).
    const GraphNode &node = graph_.node(id);
    if (node.figure_seconds && *node.figure_seconds > 0)
      return *node.figure_seconds;
    if (expected_seconds_)
      if (const double s = expected_seconds_(node.task.stage); s > 0)
        return s;
    return unknown_task_seconds;
  }

  std::vector<int> Scheduler::start_order() const
  {
    // The graph knows each task's predecessors only, all with smaller ids: from the last id
    // down, a task's rank is its own time plus the largest rank among the tasks after it
    // (`tail`, complete once every larger id is seen), which it then offers to its
    // predecessors. Tasks added later by on_done callbacks are ranked on the next call. A
    // predecessor outranks the tasks after it (every time is > 0; equal ranks go by id), so
    // a task reused in a pass makes the tasks after it ready within that pass.
    const int n = graph_.size();
    std::vector<double> tail(n, 0.0), rank(n, 0.0);
    for (int id = n - 1; id >= 0; --id)
    {
      rank[id] = expected_task_seconds(id) + tail[id];
      for (const int a : graph_.node(id).after)
        tail[a] = std::max(tail[a], rank[id]);
    }
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](const int a, const int b) { return rank[a] > rank[b]; });
    return order;
  }

  bool Scheduler::start_ready()
  {
    bool any = false;
    // A reused task can make others ready at once, and its on_done callbacks may add tasks:
    // scan again until nothing changes (bounded: each pass that goes on has reused at least
    // one task).
    for (bool again = true; again && !first_error_;)
    {
      again = false;
      status_.resize(graph_.size());
      for (const int id : start_order())
      {
        if (first_error_)
          break;
        if (status_[id].state != NodeState::waiting)
          continue;
        bool ready = true, blocked = false;
        for (const int a : graph_.node(id).after)
          if (status_[a].state == NodeState::failed || status_[a].state == NodeState::skipped)
            blocked = true;
          else if (status_[a].state != NodeState::done)
            ready = false;
        if (blocked)
        {
          status_[id].state = NodeState::skipped;
          continue;
        }
        if (!ready)
          continue;
        try
        {
          if (start(id))
          {
            any = true;
            again = again || status_[id].state == NodeState::done;
          }
        }
        catch (const WriteError &w)
        {
          status_[id].state = NodeState::failed;
          fail(std::make_exception_ptr(TaskWriteError(
            "run_pipeline in task " + graph_.node(id).task.name + ": " + w.what())));
        }
        catch (...)
        {
          status_[id].state = NodeState::failed;
          fail(std::current_exception());
        }
      }
    }
    return any;
  }

  void Scheduler::ended(const Ended &e)
  {
    NodeStatus &s = status_.at(e.node);
    used_slots_ -= s.slots;
    s.record = e.record;
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - s.start).count();
    if (interrupt_requested())
    {
      s.state = NodeState::failed;  // stopped: the loop reports the interrupt
      return;
    }
    if (e.succeeded)
    {
      try
      {
        const TaskResult r = complete_run(s.task, s.run, seconds, e.record);
        const GraphNode &node = graph_.node(e.node);
        log::info("  done    " + s.task.name + "  in " + log::format_duration(seconds) +
                  (node.figure_seconds ? "  (" +
                                           describe_against_figure(node.figure_preset, seconds,
                                                                   *node.figure_seconds) +
                                           ")" :
                                         ""));
        done(e.node, r);
      }
      catch (const WriteError &w)
      {
        // Its stamp (or a manifest) could not be written: the task is not complete and the
        // next run redoes it.
        s.state = NodeState::failed;
        fail(std::make_exception_ptr(
          TaskWriteError("run_pipeline in task " + s.task.name + ": " + w.what() +
                         "; the task is not marked complete, the next run redoes it")));
      }
      catch (...)
      {
        s.state = NodeState::failed;
        fail(std::current_exception());
      }
      return;
    }
    s.state = NodeState::failed;
    const bool write_error = e.exit_status && *e.exit_status == exit_write_error;
    // A stage that could not write (a full disk) or was ended from outside (a signal, a
    // scheduler's time limit): one line; the log's end says nothing more. Its own failure:
    // the end of its log.
    const std::string message = write_error            ? write_failure_message(s.task, s.run.log_path)
                                : e.ended_from_outside ? ended_message(s.task, s.run.log_path, e.what)
                                                       : failure_message(s.task, s.run.log_path, e.what);
    if (write_error)
    {
      std::error_code ec;
      fs::remove_all(s.run.partial, ec);  // the stage removed its work; nothing in it is kept
    }
    if (const auto &tolerated = graph_.node(e.node).on_failure)
    {
      tolerated(message);
      return;
    }
    // Said now if other tasks go on (the run waits for them), and again as the run's last line.
    if (executor_.n_running() > 0 || first_error_)
      log::error(message);
    if (write_error)
      fail(std::make_exception_ptr(TaskWriteError(message)));
    else
      fail(std::make_exception_ptr(NumericalError(message)));
  }

  void Scheduler::stop_on_interrupt()
  {
    std::vector<int> stopped = executor_.stop_all();
    for (int id = 0; id < int(status_.size()); ++id)
      if (status_[id].state == NodeState::running)
      {
        status_[id].state = NodeState::failed;
        stopped.push_back(id);
      }
    std::string names, partials;
    std::sort(stopped.begin(), stopped.end());
    stopped.erase(std::unique(stopped.begin(), stopped.end()), stopped.end());
    for (const int id : stopped)
    {
      names += (names.empty() ? "" : ", ") + status_[id].task.name;
      partials += (partials.empty() ? "" : ", ") + status_[id].run.partial;
    }
    if (stopped.empty())
      throw NumericalError("interrupted between tasks; the next run goes on from here");
    throw NumericalError("interrupted during " + names + "; the partial output (" + partials +
                         ") will be redone on the next run");
  }

  void Scheduler::run()
  {
    for (long pass = 0;; ++pass)
    {
      // Each pass starts or reuses a task, or sees one end (or a signal, which ends the loop):
      // more passes than that mean a bug, not a long run.
      if (pass > 10L * graph_.size() + 1000)
        throw std::logic_error("scheduler: no progress after " + std::to_string(pass) + " passes");
      if (interrupt_requested())
        stop_on_interrupt();
      start_ready();
      if (interrupt_requested())
        stop_on_interrupt();
      if (executor_.n_running() == 0)
        break;  // nothing runs and nothing more could start: done, failed or blocked
      for (const Ended &e : executor_.wait_any())
        ended(e);
    }
    if (first_error_)
      std::rethrow_exception(first_error_);
    for (const auto &s : status_)
      if (s.state == NodeState::waiting)
        throw std::logic_error("scheduler: task " + s.task.name + " never became ready");
  }
} // namespace clearjoint::pipeline
