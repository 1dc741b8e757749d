// run_pipeline end to end with stand-in FE and MBD stages (tests/data/fake_stages) and the real
// fit_stage: reuse, re-running only what changed, interrupts, failing stages, bad input.
#include "common/strict_reader.h"
#include "laws/law_file.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <thread>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  /// A build directory whose fe_stage and mbd_stage are the stand-ins.
  struct FakeBuild
  {
    explicit FakeBuild(const test_support::ScratchDir &dir)
      : root(dir.file("build"))
    {
      const fs::path fakes = fs::path(CLEARJOINT_TEST_DATA_DIR) / "fake_stages";
      for (const auto &[stage, target] :
           {std::pair<std::string, fs::path>{"fe_stage", fakes / "fake_fe_stage.py"},
            {"mbd_stage", fakes / "fake_mbd_stage.py"},
            {"fit_stage", FIT_STAGE_EXE}})
      {
        fs::create_directories(fs::path(root) / stage);
        fs::create_symlink(target, fs::path(root) / stage / stage);
      }
    }
    std::string root;
  };

  std::string pipeline_yaml(const std::string &dir, const std::string &values,
                            const std::string &extra_fe = "")
  {
    test_support::write_text(dir + "/fe.yaml",
                             "{\"geometry\": {\"t_B\": 0.004}" + extra_fe + "}\n");
    test_support::write_text(dir + "/mbd.yaml",
                             "{\"joint\": {\"law_file\": \"none\"}, \"extra_file\": \"law.json\"}\n");
    test_support::write_text(dir + "/law.json", test_support::read_text(
                                                  std::string(CLEARJOINT_SOURCE_DIR) +
                                                  "/laws/paper_tB4.json"));
    return "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " + dir + "/out\npreset: fast\n" +
           "presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}, "
           "accurate: {fe: null, mbd: null}}\n"
           "fe_studies:\n  - name: thickness\n    scene: " + dir + "/fe.yaml\n"
           "    parameter: {name: t_B, unit: m, key: geometry.t_B}\n    values: " + values + "\n"
           "fit: {weighting: absolute}\n"
           "mbd_runs:\n"
           "  - {name: fitted, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, study: thickness, value: 0.002}], band: true}\n"
           "  - {name: family, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, study: thickness}]}\n"
           "  - {name: paper, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, file: " + dir + "/law.json}]}\n"
           "report: false\n";
  }

  struct Outcome
  {
    int exit_code;
    std::string log;
    std::map<std::string, std::string> tasks;  // name → ran | reused
  };

  Outcome run(const test_support::ScratchDir &dir, const FakeBuild &build,
              const std::string &extra_args = "", const std::string &env = "")
  {
    const int rc = test_support::run_command(env + " " + RUN_PIPELINE_EXE + " " +
                                               dir.file("p.yaml") + " --no-plots --build-dir " +
                                               build.root + " " + extra_args,
                                             dir.file("log.txt"));
    Outcome o{rc, test_support::read_text(dir.file("log.txt")), {}};
    const std::string summary = dir.file("out/r/pipeline_summary.json");
    const nlohmann::json j = rc == 0 && fs::exists(summary) ? read_json_file(summary) : nlohmann::json();
    if (j.is_object())
      for (const auto &t : j["tasks"])
        o.tasks[t["name"].get<std::string>()] = t["outcome"].get<std::string>();
    return o;
  }

  std::set<std::string> with(const Outcome &o, const std::string &what)
  {
    std::set<std::string> s;
    for (const auto &[name, outcome] : o.tasks)
      if (outcome == what)
        s.insert(name);
    return s;
  }
} // namespace

TEST(RunPipeline, SecondRunReusesEverything)
{
  test_support::ScratchDir dir("pipeline_reuse");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  const Outcome first = run(dir, build);
  ASSERT_EQ(first.exit_code, 0) << first.log;
  EXPECT_EQ(with(first, "ran").size(), 12u) << "2 FE, 2 fits, 1 family, 3 MBD, 4 band\n" << first.log;
  const Outcome second = run(dir, build);
  ASSERT_EQ(second.exit_code, 0) << second.log;
  EXPECT_TRUE(with(second, "ran").empty()) << second.log;
  EXPECT_EQ(with(second, "reused").size(), 12u);
  // The MBD scene got the fitted law's path.
  const auto used = read_json_file(dir.file("out/r/mbd/fitted/scene_used.json"));
  EXPECT_EQ(used["joint"]["law_file"], dir.file("out/r/fit/thickness/t_B=0.002/law.json"));
  EXPECT_EQ(used["extra_file"], fs::canonical(dir.file("law.json")).string())
    << "relative paths of the base scene are made absolute in the generated scene";
  const Outcome forced = run(dir, build, "--force");
  EXPECT_EQ(with(forced, "ran").size(), 12u);
  // The band runs got the variants of the fitted law, not the law itself.
  const auto band = read_json_file(dir.file("out/r/mbd/fitted_band/n_high/scene_used.json"));
  const std::string band_law = band["joint"]["law_file"];
  EXPECT_EQ(laws::read_law_file(band_law).source_kind, "confidence_band");
}

TEST(RunPipeline, ChangingOneParameterRerunsOnlyWhatDependsOnIt)
{
  test_support::ScratchDir dir("pipeline_change");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  ASSERT_EQ(run(dir, build).exit_code, 0);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.006]"));
  const Outcome o = run(dir, build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  const std::set<std::string> expected = {"fe/thickness/t_B=0.006", "fit/thickness/t_B=0.006",
                                          "fit/thickness/family", "mbd/family"};
  EXPECT_EQ(with(o, "ran"), expected) << o.log;
  EXPECT_TRUE(with(o, "reused").count("fe/thickness/t_B=0.002"));
  EXPECT_TRUE(with(o, "reused").count("mbd/paper")) << "a law file given directly needs no FE";
}

TEST(RunPipeline, InterruptLeavesNothingCompleteAndTheNextRunFinishesTheJob)
{
  test_support::ScratchDir dir("pipeline_interrupt");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  const std::string cmd = std::string("CLEARJOINT_FAKE_SLEEP=30 ") + RUN_PIPELINE_EXE + " " +
                          dir.file("p.yaml") + " --no-plots --build-dir " + build.root + " > " +
                          dir.file("log.txt") + " 2>&1";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0)
  {
    execl("/bin/sh", "sh", "-c", ("exec env " + cmd).c_str(), nullptr);
    _exit(127);
  }
  // Wait until the first FE task is running, then interrupt the pipeline.
  const fs::path partial = dir.file("out/r/fe/thickness/t_B=0.002.partial");
  const fs::path started = dir.file("out/r/fe/thickness/t_B=0.002.command.txt");
  for (int i = 0; i < 200 && !fs::exists(started); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2) << test_support::read_text(dir.file("log.txt"));
  EXPECT_NE(test_support::read_text(dir.file("log.txt")).find("interrupted"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("out/r/fe/thickness/t_B=0.002"))) << "nothing looks complete";
  EXPECT_FALSE(fs::exists(dir.file("out/r/pipeline_summary.json")));
  EXPECT_EQ(read_json_file(dir.file("out/r/manifest.json"))["status"], "incomplete");

  const Outcome again = run(dir, build);
  ASSERT_EQ(again.exit_code, 0) << again.log;
  EXPECT_EQ(with(again, "ran").size(), 12u);
  EXPECT_FALSE(fs::exists(partial)) << "the partial output was replaced";
  EXPECT_TRUE(fs::exists(dir.file("out/r/fe/thickness/t_B=0.002/stage.log")));
  EXPECT_TRUE(fs::exists(dir.file("out/r/mbd/paper/command.txt")));
}

TEST(RunPipeline, AFailingStageStopsThePipelineWithItsMessage)
{
  test_support::ScratchDir dir("pipeline_fail");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"),
                           pipeline_yaml(dir.path(), "[0.002, 0.004]", ", \"fail\": true"));
  const Outcome o = run(dir, build);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.log.find("increment 3 did not converge"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(dir.file("out/r/fit")));
}

TEST(RunPipeline, OnlyNeedsUpToDateUpstream)
{
  test_support::ScratchDir dir("pipeline_only");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  const Outcome early = run(dir, build, "--only mbd");
  EXPECT_EQ(early.exit_code, 1);
  EXPECT_NE(early.log.find("run without --only"), std::string::npos) << early.log;
  ASSERT_EQ(run(dir, build).exit_code, 0);
  const Outcome o = run(dir, build, "--only mbd --force");
  ASSERT_EQ(o.exit_code, 0) << o.log;
  EXPECT_EQ(with(o, "ran"),
            (std::set<std::string>{"mbd/fitted", "mbd/family", "mbd/paper", "mbd/fitted/band/n_low",
                                   "mbd/fitted/band/n_high", "mbd/fitted/band/K_low",
                                   "mbd/fitted/band/K_high"}));
}

TEST(RunPipeline, BadPipelineFile)
{
  test_support::ScratchDir dir("pipeline_bad");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"),
                           pipeline_yaml(dir.path(), "[0.002, 0.004]") + "colour: blue\n");
  const Outcome o = run(dir, build);
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.log.find("'colour'"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(dir.file("out")));
}
