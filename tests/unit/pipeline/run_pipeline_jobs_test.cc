// run_pipeline --jobs (issue 33): tasks at once on this machine with the stand-in stages —
// the same files as one at a time, runs that overlap, an interrupt that stops every running
// stage and its children, a killed stage's children ended, and bad values of jobs/executor.
#include "fake_pipeline.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

using namespace fake_pipeline;

namespace
{
  struct TraceLine
  {
    std::string event, folder;
    pid_t pid;
    double time;
  };

  /// The stand-in FE stage's trace (CLEARJOINT_FAKE_TRACE).
  std::vector<TraceLine> read_trace(const std::string &path)
  {
    std::vector<TraceLine> lines;
    std::ifstream in(path);
    TraceLine l;
    while (in >> l.event >> l.folder >> l.pid >> l.time)
      lines.push_back(l);
    return lines;
  }

  /// Most FE runs alive at one time, from their start and end lines.
  int most_at_once(const std::vector<TraceLine> &trace)
  {
    std::vector<std::pair<double, int>> events;
    for (const auto &l : trace)
      if (l.event == "start" || l.event == "end")
        events.emplace_back(l.time, l.event == "start" ? 1 : -1);
    std::sort(events.begin(), events.end());
    int now = 0, most = 0;
    for (const auto &[t, d] : events)
      most = std::max(most, now += d);
    return most;
  }

  /// Waits (at most 20 s) until the trace has `n` lines of `event`.
  std::vector<TraceLine> wait_for(const std::string &trace, const std::string &event, std::size_t n)
  {
    for (int i = 0; i < 400; ++i)
    {
      auto lines = read_trace(trace);
      std::vector<TraceLine> matching;
      for (const auto &l : lines)
        if (l.event == event)
          matching.push_back(l);
      if (matching.size() >= n)
        return matching;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return {};
  }

  bool alive(const pid_t pid)
  {
    // Give init a moment to reap an orphan that was killed (a zombie still answers kill 0).
    for (int i = 0; i < 100; ++i)
    {
      if (::kill(pid, 0) != 0)
        return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return true;
  }

} // namespace

TEST(RunPipelineJobs, TasksAtOnceGiveTheSameFilesAsOneAtATime)
{
  test_support::ScratchDir dir("jobs_same");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"),
                           pipeline_yaml(dir.path(), "[0.002, 0.003, 0.004, 0.005]"));
  std::map<int, std::map<std::string, std::string>> hashes;
  for (const int jobs : {1, 3})
  {
    const std::string root = dir.file("out" + std::to_string(jobs));
    const std::string trace = dir.file("trace" + std::to_string(jobs));
    const std::string log = dir.file("log" + std::to_string(jobs));
    const int rc = test_support::run_command(
      "CLEARJOINT_FAKE_SLEEP=0.7 CLEARJOINT_FAKE_TRACE=" + trace + " " + RUN_PIPELINE_EXE + " " +
        dir.file("p.yaml") + " --no-plots --build-dir " + build.root + " --output-root " + root +
        " --jobs " + std::to_string(jobs),
      log);
    ASSERT_EQ(rc, 0) << test_support::read_text(log);
    const auto t = read_trace(trace);
    ASSERT_EQ(t.size(), 8u) << "4 FE runs, a start and an end each";
    // 0.7 s runs started together overlap; one slot never does.
    EXPECT_EQ(most_at_once(t), jobs == 1 ? 1 : 3) << test_support::read_text(log);
    if (jobs == 3)
      EXPECT_NE(test_support::read_text(log).find(" running), "), std::string::npos)
        << "the progress line counts the running tasks\n" << test_support::read_text(log);
    hashes[jobs] = result_hashes(root + "/r");
    const auto summary = read_json_file(root + "/r/pipeline_summary.json");
    EXPECT_EQ(summary["tasks"].size(), 16u) << "4 FE, 4 fits, family, 3 MBD, 4 band";
  }
  // CSVs, laws, families, generated scenes, band laws, the MBD outputs: byte for byte, once
  // the output root's own path is taken out.
  EXPECT_GE(hashes[1].size(), 30u);
  EXPECT_EQ(hashes[1], hashes[3]);
}

TEST(RunPipelineJobs, AnInterruptStopsEveryRunningStageAndTheNextRunFinishes)
{
  test_support::ScratchDir dir("jobs_interrupt");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  const std::string trace = dir.file("trace");
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir.file("p.yaml"), "--no-plots", "--build-dir", build.root, "--jobs", "2"},
    dir.file("log.txt"),
    {"CLEARJOINT_FAKE_SLEEP=60", "CLEARJOINT_FAKE_CHILD=1", "CLEARJOINT_FAKE_TRACE=" + trace});
  ASSERT_GE(pid, 0);
  const auto children = wait_for(trace, "child", 2);
  ASSERT_EQ(children.size(), 2u) << "both FE cases run at once\n"
                                 << test_support::read_text(dir.file("log.txt"));
  const auto signalled = std::chrono::steady_clock::now();
  kill(pid, SIGTERM);
  ASSERT_EQ(test_support::wait_exit_code(pid), 143) << test_support::read_text(dir.file("log.txt"));
  // The stages sleep 60 s: ending within 10 s means they were stopped, not waited for.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count(),
            10.0);
  const std::string log = test_support::read_text(dir.file("log.txt"));
  EXPECT_NE(log.find("interrupted during fe/thickness/t_B=0.002, fe/thickness/t_B=0.004"),
            std::string::npos) << log;
  for (const auto &c : children)
    EXPECT_FALSE(alive(c.pid)) << "the child of " << c.folder << " was stopped with its stage";
  for (const auto &l : read_trace(trace))
    if (l.event == "start")
      EXPECT_FALSE(alive(l.pid));
  for (const std::string v : {"0.002", "0.004"})
  {
    EXPECT_FALSE(fs::exists(dir.file("out/r/fe/thickness/t_B=" + v))) << "nothing looks complete";
    EXPECT_TRUE(fs::exists(dir.file("out/r/fe/thickness/t_B=" + v + ".partial")));
  }
  EXPECT_EQ(read_json_file(dir.file("out/r/manifest.json"))["status"], "incomplete");

  const Outcome again = run(dir, build, "--jobs 2");
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_EQ(with(again, "ran").size(), 12u);
  EXPECT_FALSE(fs::exists(dir.file("out/r/fe/thickness/t_B=0.002.partial")));
}

TEST(RunPipelineJobs, AStageKilledWithSigkillDoesNotLeaveItsChildRunning)
{
  test_support::ScratchDir dir("jobs_sigkill");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  const std::string trace = dir.file("trace");
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir.file("p.yaml"), "--no-plots", "--build-dir", build.root, "--jobs", "1"},
    dir.file("log.txt"),
    {"CLEARJOINT_FAKE_SLEEP=60", "CLEARJOINT_FAKE_CHILD=1", "CLEARJOINT_FAKE_TRACE=" + trace});
  ASSERT_GE(pid, 0);
  const auto children = wait_for(trace, "child", 1);
  ASSERT_EQ(children.size(), 1u) << test_support::read_text(dir.file("log.txt"));
  const auto stages = wait_for(trace, "start", 1);
  ASSERT_EQ(stages.size(), 1u);
  kill(stages[0].pid, SIGKILL);  // the stage alone, as the OOM killer would
  EXPECT_EQ(test_support::wait_exit_code(pid), 2);
  const std::string log = test_support::read_text(dir.file("log.txt"));
  EXPECT_NE(log.find("error: fe_stage in task fe/thickness/t_B=0.002: killed by signal 9 (Killed); "
                     "its log: "),
            std::string::npos) << log;
  EXPECT_NE(log.find("left processes in its group"), std::string::npos) << log;
  EXPECT_FALSE(alive(children[0].pid)) << "the orphaned child was ended with the group";
  EXPECT_FALSE(fs::exists(dir.file("out/r/fe/thickness/t_B=0.002")));
}

TEST(RunPipelineJobs, BadJobsAndExecutorValuesNameTheKeyAndWriteNothing)
{
  test_support::ScratchDir dir("jobs_bad");
  FakeBuild build(dir);
  const std::string good = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  const auto check = [&](const std::string &yaml_extra, const std::string &args,
                         const std::string &expected, const std::string &env = "") {
    test_support::write_text(dir.file("p.yaml"), good + yaml_extra);
    const Outcome o = run(dir, build, args, env);
    EXPECT_EQ(o.exit_code, 1) << yaml_extra << args << "\n" << o.log;
    EXPECT_NE(o.log.find(expected), std::string::npos) << o.log;
    EXPECT_FALSE(fs::exists(dir.file("out"))) << "nothing written: " << yaml_extra << args;
  };
  check("", "--jobs 0", "key '--jobs' has value '0'; allowed: an integer in [1, 1000]");
  check("", "--jobs -2", "key '--jobs' has value '-2'; allowed: an integer in [1, 1000]");
  check("jobs: 0\n", "", "key 'jobs' has value '0'; allowed: an integer in [1, 1000]");
  check("jobs: 2.5\n", "", "key 'jobs' has value '2.5'");
  check("executor: {kind: pbs}\n", "", "key 'executor.kind' has value 'pbs'; allowed: one of");
  check("executor: {kind: local, partition: short}\n", "", "executor.partition");
  check("executor: {kind: slurm, partiton: short}\n", "", "executor.partiton");
  check("executor: {kind: slurm, time_margin: 0.5}\n", "", "key 'executor.time_margin' has value '0.5'");
  check("executor: {kind: slurm, poll_interval: 0.1}\n", "", "key 'executor.poll_interval'");
  check("executor: {kind: slurm, sbatch_args: [mem=4G]}\n", "", "key 'executor.sbatch_args'");
  // No Slurm commands on PATH (an empty folder): named before anything is written.
  fs::create_directories(dir.file("empty_bin"));
  check("", "--executor slurm", "'sbatch' is not on PATH",
        "PATH=" + dir.file("empty_bin"));
}
