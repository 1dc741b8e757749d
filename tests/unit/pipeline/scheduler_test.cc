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
