// The scheduler (pipeline/scheduler.h) with an executor that runs nothing: which tasks start
// when, how many slots they take, what a failure stops, and tasks added by a finished one.
#include "common/error.h"
#include "pipeline/scheduler.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <deque>
#include <fstream>
#include <set>

using namespace clearjoint;
using namespace clearjoint::pipeline;
namespace fs = std::filesystem;

namespace
{
  /// Starts nothing: a started task "runs" until wait_any() ends the oldest one. Records the
  /// order of events and the most slots in use at once.
  class ScriptedExecutor : public Executor
  {
  public:
    explicit ScriptedExecutor(int capacity, std::set<std::string> failing = {})
      : capacity_(capacity), failing_(std::move(failing))
    {}
    std::string kind() const override { return "local"; }
    int capacity() const override { return capacity_; }
    int slots_for(int ranks) const override { return std::clamp(ranks, 1, capacity_); }
    std::vector<std::string> launcher(int) const override { return {}; }
    void start(const Launch &l) override
    {
      std::ofstream(l.log_path) << "ran " << l.name << "\n";
      running_.push_back(l);
      used_ += slots_for(l.ranks);
      peak_ = std::max(peak_, used_);
      events.push_back("start " + l.name);
    }
    std::vector<Ended> wait_any() override
    {
      const Launch l = running_.front();
      running_.pop_front();
      used_ -= slots_for(l.ranks);
      events.push_back("end " + l.name);
      const bool fails = failing_.count(l.name) > 0;
      return {Ended{l.node, !fails, fails ? "exit status 2" : "exit status 0", nullptr}};
    }
    std::vector<int> stop_all() override { return {}; }
    int n_running() const override { return int(running_.size()); }
    int peak() const { return peak_; }
    std::vector<std::string> events;

  private:
    int capacity_, used_ = 0, peak_ = 0;
    std::set<std::string> failing_;
    std::deque<Launch> running_;
  };

  Task task(const test_support::ScratchDir &dir, const std::string &name)
  {
    Task t;
    t.name = name;
    t.stage = "fake";
    t.executable = "/bin/true";
    t.args = {name};
    t.output_dir = dir.file(name);
    return t;
  }

  GraphNode node(const Task &t, std::vector<int> after = {}, int ranks = 1)
  {
    GraphNode n;
    n.task = t;
    n.group = "fe";
    n.after = std::move(after);
    n.ranks = ranks;
    return n;
  }

  std::size_t index_of(const std::vector<std::string> &events, const std::string &e)
  {
    return std::size_t(std::find(events.begin(), events.end(), e) - events.begin());
  }
} // namespace

TEST(Scheduler, ReadyTasksShareTheSlotsAndATaskWaitsForItsUpstream)
{
  test_support::ScratchDir dir("scheduler_slots");
  TaskGraph g;
  std::vector<int> fe;
  for (const std::string n : {"a", "b", "c", "d"})
    fe.push_back(g.add(node(task(dir, n))));
  g.add(node(task(dir, "family"), fe));
  ScriptedExecutor ex(2);
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  EXPECT_EQ(ex.peak(), 2) << "two slots, four ready tasks: two at a time";
  const auto &ev = ex.events;
  EXPECT_LT(index_of(ev, "start b"), index_of(ev, "end a")) << "a and b ran at once";
  for (const std::string n : {"a", "b", "c", "d"})
    EXPECT_LT(index_of(ev, "end " + n), index_of(ev, "start family")) << n;
  for (int id = 0; id < g.size(); ++id)
    EXPECT_EQ(s.status(id).state, NodeState::done);
  EXPECT_TRUE(fs::exists(dir.file("family/.task.json")));
  EXPECT_EQ(s.status(4).task.depends_on.size(), 4u) << "the upstream identities, in order";
  EXPECT_EQ(s.status(4).task.depends_on[2], s.status(2).identity);
}

TEST(Scheduler, ATaskOnTwoRanksTakesTwoSlots)
{
  test_support::ScratchDir dir("scheduler_ranks");
  TaskGraph g;
  g.add(node(task(dir, "mpi"), {}, 2));
  g.add(node(task(dir, "x")));
  g.add(node(task(dir, "y")));
  g.add(node(task(dir, "huge"), {}, 64));  // more ranks than slots: runs alone
  ScriptedExecutor ex(3);
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  EXPECT_EQ(ex.peak(), 3);
  const auto &ev = ex.events;
  EXPECT_LT(index_of(ev, "start x"), index_of(ev, "end mpi"));
  EXPECT_GT(index_of(ev, "start y"), index_of(ev, "end mpi")) << "2 + 1 slots were taken";
  EXPECT_GT(index_of(ev, "start huge"), index_of(ev, "end y"));
}

TEST(Scheduler, AFailureStartsNothingNewLetsTheRunningEndAndIsThrown)
{
  test_support::ScratchDir dir("scheduler_fail");
  TaskGraph g;
  const int bad = g.add(node(task(dir, "bad")));
  const int good = g.add(node(task(dir, "good")));
  g.add(node(task(dir, "after_bad"), {bad}));
  g.add(node(task(dir, "later")));
  ScriptedExecutor ex(2, {"bad"});
  Scheduler s(g, ex, {}, nullptr, nullptr);
  try
  {
    s.run();
    FAIL() << "the failure is thrown";
  }
  catch (const NumericalError &e)
  {
    EXPECT_NE(std::string(e.what()).find("fake failed in task bad (exit status 2)"),
              std::string::npos) << e.what();
  }
  EXPECT_EQ(s.status(good).state, NodeState::done) << "the running task ended and was kept";
  EXPECT_TRUE(fs::exists(dir.file("good/.task.json")));
  EXPECT_TRUE(fs::exists(dir.file("bad.partial")));
  EXPECT_FALSE(fs::exists(dir.file("bad")));
  EXPECT_EQ(index_of(ex.events, "start later"), ex.events.size()) << "nothing new started";
  EXPECT_EQ(index_of(ex.events, "start after_bad"), ex.events.size());
}

TEST(Scheduler, AToleratedFailureSkipsOnlyWhatFollowsIt)
{
  test_support::ScratchDir dir("scheduler_tolerated");
  TaskGraph g;
  GraphNode rolling = node(task(dir, "rolling"));
  std::string message;
  rolling.on_failure = [&](const std::string &m) { message = m; };
  const int r = g.add(rolling);
  g.add(node(task(dir, "after_rolling"), {r}));
  const int other = g.add(node(task(dir, "other")));
  ScriptedExecutor ex(1, {"rolling"});
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  EXPECT_NE(message.find("failed in task rolling"), std::string::npos) << message;
  EXPECT_EQ(s.status(r + 1).state, NodeState::skipped);
  EXPECT_EQ(s.status(other).state, NodeState::done);
}

TEST(Scheduler, AFinishedTaskAddsTasksAndASecondRunReusesAll)
{
  test_support::ScratchDir dir("scheduler_grow");
  const auto build = [&](TaskGraph &g) {
    GraphNode fit = node(task(dir, "fit"));
    fit.on_done.push_back([&](TaskGraph &graph, const TaskResult &) {
      for (const std::string v : {"n_low", "n_high"})
        graph.add(node(task(dir, "band_" + v), {0}));
    });
    g.add(fit);
  };
  TaskGraph g1;
  build(g1);
  ScriptedExecutor ex1(4);
  Scheduler s1(g1, ex1, {}, nullptr, nullptr);
  s1.run();
  ASSERT_EQ(g1.size(), 3);
  EXPECT_EQ(s1.status(2).state, NodeState::done);
  EXPECT_EQ(s1.status(2).result.outcome, TaskOutcome::ran);
  TaskGraph g2;
  build(g2);
  ScriptedExecutor ex2(4);
  Scheduler s2(g2, ex2, {}, nullptr, nullptr);
  s2.run();
  EXPECT_TRUE(ex2.events.empty()) << "every stamp matches: nothing starts";
  ASSERT_EQ(g2.size(), 3);
  EXPECT_EQ(s2.status(2).result.outcome, TaskOutcome::reused);
}

namespace
{
  /// A node with the preset's measured time of its task (nullopt: none).
  GraphNode timed(const Task &t, std::optional<double> figure_seconds, std::vector<int> after = {})
  {
    GraphNode n = node(t, std::move(after));
    n.figure_seconds = figure_seconds;
    return n;
  }

  /// The tasks' names in the order they started.
  std::vector<std::string> starts(const std::vector<std::string> &events)
  {
    std::vector<std::string> names;
    for (const auto &e : events)
      if (e.rfind("start ", 0) == 0)
        names.push_back(e.substr(6));
    return names;
  }
} // namespace

TEST(Scheduler, TheLongestChainStartsFirst)
{
  // The standard pipeline's shape (issue 32 item 5): short FE cases added first, the impact
  // study (the critical path), the rolling study and a mesh before a long FE task.
  test_support::ScratchDir dir("scheduler_longest");
  TaskGraph g;
  std::vector<int> fe;
  for (const std::string n : {"thick_0", "thick_1", "thick_2", "thick_3"})
    fe.push_back(g.add(timed(task(dir, n), 10.0)));
  g.add(timed(task(dir, "family"), std::nullopt, fe));
  const int impact = g.add(timed(task(dir, "impact"), 150.0));
  g.add(timed(task(dir, "compare"), std::nullopt, {impact}));
  g.add(timed(task(dir, "rolling"), 97.0));
  const int mesh = g.add(timed(task(dir, "mesh"), std::nullopt));  // ~1 s, but 80 s follow it
  g.add(timed(task(dir, "deformable"), 80.0, {mesh}));
  ScriptedExecutor ex(2);
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  const auto started = starts(ex.events);
  ASSERT_EQ(started.size(), std::size_t(g.size()));
  EXPECT_EQ(std::vector<std::string>(started.begin(), started.begin() + 3),
            (std::vector<std::string>{"impact", "rolling", "mesh"}))
    << "by the longest path to the end: 151, 97, 81 s against the FE cases' 11 s";
  EXPECT_LT(index_of(started, "deformable"), index_of(started, "thick_1"))
    << "once the mesh is done, before the FE cases still waiting";
  EXPECT_LT(index_of(started, "thick_0"), index_of(started, "compare"))
    << "11 s of chain (the case and its family) before the 1 s of the comparison";
  EXPECT_EQ(ex.peak(), 2);
  for (int id = 0; id < g.size(); ++id)
    EXPECT_EQ(s.status(id).state, NodeState::done);
  EXPECT_EQ(s.status(impact + 1).task.depends_on.front(), s.status(impact).identity);
}

TEST(Scheduler, EqualChainsStartInTheOrderTheyWereAdded)
{
  test_support::ScratchDir dir("scheduler_ties");
  TaskGraph g;
  g.add(timed(task(dir, "a"), 20.0));
  const int b = g.add(timed(task(dir, "b"), 10.0));
  g.add(timed(task(dir, "c"), 10.0, {b}));  // b's chain: 10 + 10 = 20 s, as a's
  g.add(timed(task(dir, "d"), 20.0));
  g.add(timed(task(dir, "e"), 20.0));
  ScriptedExecutor ex(2);
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  // a and b start; a ends (the executor ends the oldest first): d, then e once b ends, and c
  // (10 s to go) after e.
  EXPECT_EQ(starts(ex.events), (std::vector<std::string>{"a", "b", "d", "e", "c"}));
  ScriptedExecutor again(2);  // the same graph run again (--force): the same order
  Scheduler s2(g, again, {true, std::nullopt}, nullptr, nullptr);
  s2.run();
  EXPECT_EQ(again.events, ex.events);
}

TEST(Scheduler, ATaskWithoutFigureTakesItsStagesTimeElseOneSecond)
{
  test_support::ScratchDir dir("scheduler_unknown");
  TaskGraph g;
  g.add(timed(task(dir, "short"), 0.5));
  g.add(timed(task(dir, "unknown"), std::nullopt));  // stage fake: no time, so 1 s
  Task slow = task(dir, "by_stage");
  slow.stage = "slow";
  g.add(timed(slow, std::nullopt));  // the stage's 60 s
  Task measured = task(dir, "measured");
  measured.stage = "slow";
  g.add(timed(measured, 30.0));  // its own figure comes before the stage's time
  ScriptedExecutor ex(2);
  Scheduler s(g, ex, {}, nullptr, [](const std::string &stage) {
    return stage == "slow" ? 60.0 : 0.0;  // 0: not measured (RunEta::expected_seconds)
  });
  s.run();
  EXPECT_EQ(starts(ex.events),
            (std::vector<std::string>{"by_stage", "measured", "unknown", "short"}));
}

TEST(Scheduler, TasksAddedByAFinishedTaskTakeTheirPlaceInTheOrder)
{
  test_support::ScratchDir dir("scheduler_added");
  TaskGraph g;
  GraphNode fit = timed(task(dir, "fit"), 10.0);
  fit.on_done.push_back(
    [&](TaskGraph &graph, const TaskResult &) { graph.add(timed(task(dir, "band"), 50.0, {0})); });
  g.add(fit);
  for (const std::string n : {"x", "y", "z"})
    g.add(timed(task(dir, n), 5.0));
  ScriptedExecutor ex(2);
  Scheduler s(g, ex, {}, nullptr, nullptr);
  s.run();
  ASSERT_EQ(g.size(), 5);
  EXPECT_EQ(starts(ex.events), (std::vector<std::string>{"fit", "x", "band", "y", "z"}))
    << "the band run (50 s) goes before the waiting 5 s tasks";
  EXPECT_EQ(s.status(4).state, NodeState::done);
}
