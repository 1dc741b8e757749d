// The Slurm executor (issue 33) against a real single-node Slurm (local_slurm.h) with the
// stand-in stages: the pipeline as jobs gives the local run's files, an MPI task being one job
// of 2 tasks with mpirun inside; a failing job, a job cancelled from outside, an interrupted
// pipeline, a job left by a killed run; and a controller that does not answer. Skipped (with the reason) without root or
// without the slurm-wlm and munge packages. ctest label `slurm`, one test at a time.
#include "fake_pipeline.h"
#include "local_slurm.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <regex>
#include <thread>

using namespace fake_pipeline;

namespace
{
  const std::string slurm_executor = "executor: {kind: slurm, poll_interval: 1, partition: test}\n";

  /// The pipeline of pipeline_yaml() with the Slurm executor.
  std::string slurm_yaml(const std::string &dir, const std::string &values,
                         const std::string &extra_fe = "", const std::string &extra = "")
  {
    std::string y = pipeline_yaml(dir, values, extra_fe);
    y.replace(y.find("report: false"), 13, slurm_executor + extra + "report: false");
    return y;
  }

  /// Waits (at most 30 s) until `n` of the run's tasks have a Slurm job (<dir>.job.json);
  /// returns their job ids.
  std::vector<std::string> wait_for_jobs(const std::string &run_dir, std::size_t n)
  {
    for (int i = 0; i < 300; ++i)
    {
      std::vector<std::string> ids;
      if (fs::exists(run_dir))
        for (const auto &e : fs::recursive_directory_iterator(run_dir))
          if (e.path().string().size() > 9 &&
              e.path().string().compare(e.path().string().size() - 9, 9, ".job.json") == 0)
            ids.push_back(read_json_file(e.path().string())["job_id"].get<std::string>());
      if (ids.size() >= n)
        return ids;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return {};
  }

  std::string job_state(const std::string &id)
  {
    std::string s = local_slurm::command_output("squeue --noheader --states=all --format=%T --jobs=" + id);
    return s.substr(0, s.find('\n'));
  }

  class SlurmExecutorTest : public ::testing::Test
  {
  protected:
    void SetUp() override
    {
      cluster_ = std::make_unique<local_slurm::Cluster>();
      if (!cluster_->skip_reason.empty())
        GTEST_SKIP() << cluster_->skip_reason;
      ASSERT_TRUE(cluster_->failure.empty()) << cluster_->failure;
    }
    void TearDown() override { cluster_.reset(); }  // before the folder goes
    /// The ends of the controller's and the node's logs, for a failure's message (CI prints
    /// nothing else of the cluster).
    std::string cluster_logs() const
    {
      std::string text;
      for (const std::string daemon : {"slurmctld", "slurmd"})
        {
          const std::string all = test_support::read_text(cluster_->dir() + "/" + daemon + ".log");
          text += "\n--- " + daemon + ".log ends with:\n" +
                  all.substr(all.size() > 3000 ? all.size() - 3000 : 0);
        }
      return text;
    }
    test_support::ScratchDir dir_{"slurm_" + std::string(
      ::testing::UnitTest::GetInstance()->current_test_info()->name())};
    std::unique_ptr<local_slurm::Cluster> cluster_;
  };
} // namespace

TEST_F(SlurmExecutorTest, ThePipelineAsJobsGivesTheLocalFilesAndReusesThem)
{
  FakeBuild build(dir_);
  // FE on 2 MPI ranks: one job of 2 tasks each, mpirun inside (locally mpirun -np 2).
  test_support::write_text(dir_.file("p.yaml"),
                           "mpi_ranks: 2\n" + slurm_yaml(dir_.path(), "[0.002, 0.004]"));
  const Outcome local = run(dir_, build, "--executor local --output-root " + dir_.file("local"));
  ASSERT_EQ(local.exit_code, 0) << local.log;
  const Outcome slurm = run(dir_, build);
  ASSERT_EQ(slurm.exit_code, 0) << slurm.log;
  EXPECT_EQ(with(slurm, "ran").size(), 12u) << slurm.log;
  EXPECT_NE(slurm.log.find("as Slurm job"), std::string::npos) << slurm.log;
  const auto hashes = result_hashes(dir_.file("out/r"));
  EXPECT_GE(hashes.size(), 20u);
  EXPECT_EQ(hashes, result_hashes(dir_.file("local/r")));
  // Each task's stamp and summary entry name its job; nothing of the job is left beside it.
  const auto summary = read_json_file(dir_.file("out/r/pipeline_summary.json"));
  std::set<std::string> ids;
  for (const auto &t : summary["tasks"])
  {
    ASSERT_TRUE(t.contains("executor")) << t.dump();
    EXPECT_EQ(t["executor"]["state"], "COMPLETED");
    ids.insert(t["executor"]["job_id"].get<std::string>());
    const auto stamp = read_json_file(t["output_dir"].get<std::string>() + "/.task.json");
    EXPECT_EQ(stamp["executor"]["job_id"], t["executor"]["job_id"]);
  }
  EXPECT_EQ(ids.size(), 12u) << "one job per task";
  for (const std::string left : {".sbatch", ".exit", ".job.json", ".partial", ".log"})
    EXPECT_FALSE(fs::exists(dir_.file("out/r/fe/thickness/t_B=0.002" + left))) << left;
  // The FE jobs: 2 tasks, both ranks in the same job (Debian's Open MPI mpirun inside the
  // allocation; the stand-in prints its rank and the job's task count).
  EXPECT_NE(slurm.log.find("(2 tasks, time limit 60 min)"), std::string::npos) << slurm.log;
  const std::string log = test_support::read_text(dir_.file("out/r/fe/thickness/t_B=0.004/stage.log"));
  for (const std::string rank : {"0", "1"})
    EXPECT_TRUE(std::regex_search(log, std::regex("rank " + rank + " of 2 \\(Slurm job [0-9]+, 2 tasks\\)")))
      << log;
  EXPECT_NE(test_support::read_text(dir_.file("out/r/fe/thickness/t_B=0.004/command.txt"))
              .find("mpirun --allow-run-as-root -np 2 "),
            std::string::npos);
  const Outcome again = run(dir_, build);
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_EQ(with(again, "reused").size(), 12u);
  EXPECT_EQ(again.log.find("as Slurm job"), std::string::npos) << "nothing submitted";
}

TEST_F(SlurmExecutorTest, AJobLeftByAKilledRunIsCancelledBeforeTheTaskIsSubmittedAgain)
{
  FakeBuild build(dir_);
  test_support::write_text(dir_.file("p.yaml"), slurm_yaml(dir_.path(), "[0.002, 0.004]"));
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir_.file("p.yaml"), "--no-plots", "--build-dir", build.root, "--jobs", "1"},
    dir_.file("log.txt"), {"CLEARJOINT_FAKE_SLEEP=60"});
  const auto ids = wait_for_jobs(dir_.file("out/r/fe"), 1);
  ASSERT_EQ(ids.size(), 1u) << test_support::read_text(dir_.file("log.txt"));
  kill(pid, SIGKILL);  // run_pipeline gone without a word; its job goes on
  test_support::wait_exit_code(pid);
  EXPECT_NE(job_state(ids[0]), "CANCELLED");
  const Outcome again = run(dir_, build);
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_NE(again.log.find("Slurm job " + ids[0] + " of an earlier run is still"),
            std::string::npos) << again.log;
  EXPECT_EQ(job_state(ids[0]), "CANCELLED");
}

TEST_F(SlurmExecutorTest, AFailingJobIsReportedWithItsIdStateAndLog)
{
  FakeBuild build(dir_);
  test_support::write_text(dir_.file("p.yaml"),
                           slurm_yaml(dir_.path(), "[0.002, 0.004]", ", \"fail\": true"));
  const Outcome o = run(dir_, build);
  EXPECT_EQ(o.exit_code, 2) << o.log;
  EXPECT_TRUE(std::regex_search(o.log, std::regex("fe_stage failed in task fe/thickness/t_B=0.00[24] "
                                                  "\\(Slurm job [0-9]+ ended FAILED, exit status 2\\); "
                                                  "its log .*t_B=0.00[24].log ends with:")))
    << o.log;
  EXPECT_NE(o.log.find("increment 3 did not converge"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(dir_.file("out/r/fit")));
  EXPECT_TRUE(fs::exists(dir_.file("out/r/fe/thickness/t_B=0.002.job.json")))
    << "a failed job's id stays beside its log";
}

TEST_F(SlurmExecutorTest, AJobCancelledFromOutsideIsReportedAndTheRerunRedoesIt)
{
  FakeBuild build(dir_);
  test_support::write_text(dir_.file("p.yaml"), slurm_yaml(dir_.path(), "[0.002, 0.004]"));
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE,
    {dir_.file("p.yaml"), "--no-plots", "--build-dir", build.root, "--jobs", "1"},
    dir_.file("log.txt"), {"CLEARJOINT_FAKE_SLEEP=60"});
  const auto ids = wait_for_jobs(dir_.file("out/r"), 1);
  ASSERT_EQ(ids.size(), 1u) << test_support::read_text(dir_.file("log.txt"));
  for (int i = 0; i < 100 && job_state(ids[0]) != "RUNNING"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const std::string state_at_cancel = job_state(ids[0]);
  ASSERT_EQ(std::system(("scancel " + ids[0]).c_str()), 0);
  EXPECT_EQ(test_support::wait_exit_code(pid), 2) << cluster_logs();
  const std::string log = test_support::read_text(dir_.file("log.txt"));
  // one line (its log says nothing about why): the task, the job id, the state, the log; and
  // the exit status when the job's wrapper wrote it before the scheduler's SIGKILL (143 after
  // scancel's SIGTERM: seen under load, 2026-11-28), not otherwise. CI failed here once
  // (stop 51) without saying why; the messages below now carry the job's state when it was
  // cancelled and the daemons' logs.
  EXPECT_TRUE(std::regex_search(
    log, std::regex("error: fe_stage in task fe/thickness/t_B=0.00[24]: Slurm job " + ids[0] +
                    " ended CANCELLED(, exit status 143)? \\(scancel from outside[^\n]*; "
                    "its log: [^\n]*t_B=0.00[24].log\n")))
    << "job state when cancelled: " << state_at_cancel << "\n"
    << log << cluster_logs();
  EXPECT_FALSE(fs::exists(dir_.file("out/r/fe/thickness/t_B=0.002")));
  const Outcome again = run(dir_, build);
  ASSERT_EQ(again.exit_code, 0) << again.log << cluster_logs();
  EXPECT_EQ(with(again, "ran").size(), 12u) << again.log;
}

TEST_F(SlurmExecutorTest, AJobPastItsTimeLimitIsReportedInOneLineAndTheRerunResumes)
{
  FakeBuild build(dir_);
  // A 15 s limit (sbatch_args come after the executor's own --time, so they win), a 300 s task.
  std::string yaml = slurm_yaml(dir_.path(), "[0.002, 0.004]");
  yaml.replace(yaml.find("partition: test}"), 16,
               "partition: test, sbatch_args: [\"--time=0:15\"]}");
  test_support::write_text(dir_.file("p.yaml"), yaml);
  const auto started = std::chrono::steady_clock::now();
  const Outcome o = run(dir_, build, "--jobs 1", "CLEARJOINT_FAKE_SLEEP=300");
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_EQ(o.exit_code, 2) << o.log;
  EXPECT_LT(seconds, 150.0) << "ended by Slurm's limit, not by the 300 s sleep";
  std::smatch m;
  ASSERT_TRUE(std::regex_search(o.log, m, std::regex("error: fe_stage in task fe/thickness/t_B=0.00[24]: "
                                                     "Slurm job ([0-9]+) ended TIMEOUT[^\n]*"
                                                     "its log: [^\n]*t_B=0.00[24].log\n")))
    << o.log;
  EXPECT_EQ(o.log.find("ends with:"), std::string::npos) << "one line, not the log's tail";
  EXPECT_EQ(job_state(m[1]), "TIMEOUT");
  EXPECT_FALSE(fs::exists(dir_.file("out/r/fe/thickness/t_B=0.002")));
  EXPECT_FALSE(fs::exists(dir_.file("out/r/fe/thickness/t_B=0.004")));
  // The rerun (no sleep) redoes the task that was killed and goes on.
  const Outcome again = run(dir_, build);
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_EQ(with(again, "ran").size(), 12u);
}

TEST_F(SlurmExecutorTest, AnInterruptCancelsEveryJobAndTheNextRunResumes)
{
  FakeBuild build(dir_);
  test_support::write_text(dir_.file("p.yaml"), slurm_yaml(dir_.path(), "[0.002, 0.004]"));
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir_.file("p.yaml"), "--no-plots", "--build-dir", build.root},
    dir_.file("log.txt"), {"CLEARJOINT_FAKE_SLEEP=60"});
  // the two FE cases and mbd/paper (a law file given directly) start at once
  const auto ids = wait_for_jobs(dir_.file("out/r"), 3);
  ASSERT_EQ(ids.size(), 3u) << test_support::read_text(dir_.file("log.txt"));
  const auto signalled = std::chrono::steady_clock::now();
  kill(pid, SIGINT);
  ASSERT_EQ(test_support::wait_exit_code(pid), 130) << test_support::read_text(dir_.file("log.txt"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count(),
            30.0) << "the 60 s jobs were cancelled, not waited for";
  const std::string log = test_support::read_text(dir_.file("log.txt"));
  EXPECT_NE(log.find("cancelling Slurm jobs"), std::string::npos) << log;
  for (const auto &id : ids)
  {
    const std::string state = job_state(id);  // mbd/paper may have finished first
    EXPECT_TRUE(state == "CANCELLED" || state == "COMPLETED" || state.empty())
      << "job " << id << ": " << state;
  }
  EXPECT_EQ(read_json_file(dir_.file("out/r/manifest.json"))["status"], "incomplete");
  for (const std::string v : {"0.002", "0.004"})
  {
    EXPECT_FALSE(fs::exists(dir_.file("out/r/fe/thickness/t_B=" + v)));
    EXPECT_TRUE(fs::exists(dir_.file("out/r/fe/thickness/t_B=" + v + ".partial")));
    EXPECT_EQ(job_state(read_json_file(dir_.file("out/r/fe/thickness/t_B=" + v + ".job.json"))
                          ["job_id"].get<std::string>()),
              "CANCELLED") << v;
  }
  const Outcome again = run(dir_, build);
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_GE(with(again, "ran").size(), 11u) << "all but mbd/paper, if it had finished";
  EXPECT_EQ(with(again, "ran").size() + with(again, "reused").size(), 12u);
}

// No cluster needed: a controller nobody answers for is named before anything is written.
TEST(SlurmExecutor, AControllerThatDoesNotAnswerIsAnInputErrorNamingSqueue)
{
  if (!local_slurm::on_path("squeue"))
    GTEST_SKIP() << "squeue not installed (Debian package slurm-client, scripts/setup)";
  test_support::ScratchDir dir("slurm_no_controller");
  FakeBuild build(dir);
  test_support::write_text(dir.file("slurm.conf"),
                           "ClusterName=nobody\nSlurmctldHost=localhost(127.0.0.1)\n"
                           "SlurmctldPort=" + std::to_string(local_slurm::free_port()) + "\n"
                           "AuthType=auth/munge\nNodeName=localhost CPUs=1\n"
                           "PartitionName=p Nodes=localhost Default=YES\n");
  test_support::write_text(
    dir.file("p.yaml"),
    slurm_yaml(dir.path(), "[0.002, 0.004]").replace(
      slurm_yaml(dir.path(), "[0.002, 0.004]").find("poll_interval: 1"), 16,
      "poll_interval: 1, command_timeout: 2"));
  const auto start = std::chrono::steady_clock::now();
  const Outcome o = run(dir, build, "", "SLURM_CONF=" + dir.file("slurm.conf"));
  EXPECT_EQ(o.exit_code, 1) << o.log;
  EXPECT_NE(o.log.find("key 'executor.kind' has value 'slurm'; allowed: a Slurm controller that "
                       "answers ('squeue' "),
            std::string::npos) << o.log;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0)
    << "command_timeout: 2 s, not Slurm's own retries";
  EXPECT_FALSE(fs::exists(dir.file("out")));
}
