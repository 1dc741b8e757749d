// run_pipeline --check and the check every run starts with (issue 16 item 2): a bad value in
// any generated scene is an input error naming the pipeline key that produced it, exit 1, and
// nothing is created under the output root. Stand-in FE stage, the real mbd_stage.
#include "common/document_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <filesystem>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  struct Build
  {
    explicit Build(const test_support::ScratchDir &dir)
      : root(dir.file("build"))
    {
      const fs::path fakes = fs::path(CLEARJOINT_TEST_DATA_DIR) / "fake_stages";
      for (const auto &[link, target] : std::vector<std::pair<fs::path, fs::path>>{
             {"fe_stage/fe_stage", fakes / "fake_fe_stage.py"},
             {"mbd_stage/mbd_stage", MBD_STAGE_EXE},
             {"fit_stage/fit_stage", FIT_STAGE_EXE}})
      {
        fs::create_directories((fs::path(root) / link).parent_path());
        fs::create_symlink(target, fs::path(root) / link);
      }
    }
    std::string root;
  };

  /// A pipeline with one FE sweep and one MBD run of the shipped slider–crank scene using the
  /// law fitted for t_B = 4 mm; `mbd_extra` is added to the MBD run's mapping.
  std::string pipeline(const test_support::ScratchDir &dir, const std::string &mbd_extra = "",
                       const std::string &output_root = "", const std::string &name = "m")
  {
    test_support::write_text(dir.file("fe.yaml"), "{\"geometry\": {\"t_B\": 0.004}}\n");
    const std::string src = CLEARJOINT_SOURCE_DIR;
    const std::string text =
      "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " +
      (output_root.empty() ? dir.file("out") : output_root) + "\npreset: fast\n" +
      "presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}, "
      "accurate: {fe: null, mbd: null}}\n"
      "fe_sweeps:\n  - name: thickness\n    scene: " + dir.file("fe.yaml") + "\n"
      "    parameter: {name: t_B, unit: m, key: geometry.t_B}\n    values: [0.002, 0.004]\n"
      "fit: {weighting: absolute}\n"
      "mbd_runs:\n  - {name: " + name + ", scene: " + src +
      "/mbd_stage/scenes/slider_crank_fe_law.yaml, laws: [{key: "
      "clearance_joints.0.normal.law_file, sweep: thickness, value: 0.004}]" + mbd_extra + "}\n"
      "report: false\n";
    test_support::write_text(dir.file("p.yaml"), text);
    return dir.file("p.yaml");
  }

  int run_pipeline(const test_support::ScratchDir &dir, const Build &b, const std::string &args,
                   std::string &log)
  {
    const int rc = test_support::run_command(std::string(RUN_PIPELINE_EXE) + " " +
                                               dir.file("p.yaml") + " --no-plots --build-dir " +
                                               b.root + " " + args,
                                             dir.file("log.txt"));
    log = test_support::read_text(dir.file("log.txt"));
    return rc;
  }
} // namespace

TEST(PipelineCheck, AValidPipelinePassesAndNothingIsWritten)
{
  test_support::ScratchDir dir("pipeline_check_ok");
  const Build b(dir);
  pipeline(dir);
  std::string log;
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  EXPECT_FALSE(fs::exists(dir.file("out"))) << log;
}

TEST(PipelineCheck, ABadOverrideIsNamedByItsPipelineKeyBeforeAnyTaskRuns)
{
  test_support::ScratchDir dir("pipeline_check_override");
  const Build b(dir);
  // Gravity 1e23 m/s^2 and a journal 2 mm off centre in a 0.5 mm clearance: mbd_stage's own
  // reader rejects both; the message names the pipeline key. Without --check too: the run
  // stops before its first (FE) task.
  for (const auto &[extra, key] : std::vector<std::pair<std::string, std::string>>{
         {", overrides: {gravity: [0, 0, -1e23]}", "mbd_runs[0].overrides.gravity"},
         {", overrides: {clearance_joints.0.journal.center: [0.0, 0.4572, 0.002]}",
          "mbd_runs[0].overrides.clearance_joints.0.journal.center"}})
    for (const std::string args : {"--check", ""})
    {
      pipeline(dir, extra);
      std::string log;
      EXPECT_EQ(run_pipeline(dir, b, args, log), 1) << log;
      EXPECT_NE(log.find("key '" + key + "'"), std::string::npos) << log;
      EXPECT_FALSE(fs::exists(dir.file("out"))) << "nothing under the output root: " << log;
    }
}

// A sweep's own preset settings (fe_sweeps[i].presets, issue 31 item 5) are checked like every
// other key: a value fe_stage rejects is named by its pipeline key — the sweep's preset's, which
// is applied after the sweep's overrides — and only for the preset that runs.
TEST(PipelineCheck, ASweepsOwnPresetSettingIsNamedByItsKey)
{
  test_support::ScratchDir dir("pipeline_check_sweep_presets");
  const Build b(dir);
  test_support::write_text(dir.file("mis.yaml"), "{\"study\": \"misalignment\", "
                                                 "\"misalignment\": {\"theta_deg\": 1.0}}\n");
  const auto write = [&](const std::string &fast) {
    test_support::write_text(
      dir.file("p.yaml"),
      "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " + dir.file("out") + "\npreset: fast\n"
      "presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}, "
      "accurate: {fe: null, mbd: null}}\n"
      "fe_sweeps:\n  - name: misalignment\n    scene: " + dir.file("mis.yaml") + "\n"
      "    parameter: {name: theta, unit: deg, key: misalignment.theta_deg}\n"
      "    values: [1.0, theta_max]\n    overrides: {loading.journal: core}\n"
      "    presets:\n      fast: " + fast + "\n"
      "      standard: {mesh.adaptive_cycles: 3}\n      accurate: null\n"
      "fit: {weighting: absolute}\nmbd_runs: []\nreport: false\n");
  };
  std::string log;
  write("{mesh.adaptive_cycles: 2}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  // The stand-in, like fe_stage, refuses the end_faces journal in the misalignment study.
  write("{mesh.adaptive_cycles: 2, loading.journal: end_faces}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << log;
  EXPECT_NE(log.find("key 'fe_sweeps[0].presets.fast.loading.journal'"), std::string::npos) << log;
  EXPECT_NE(log.find("end_faces"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.file("out"))) << log;
  // Another preset runs: the fast preset's setting is not used, so not checked.
  EXPECT_EQ(run_pipeline(dir, b, "--check --preset standard", log), 0) << log;
}

TEST(PipelineCheck, UnusableOutputRootsAndNamesAreInputErrors)
{
  test_support::ScratchDir dir("pipeline_check_root");
  const Build b(dir);
  std::string log;
  test_support::write_text(dir.file("a_file"), "x");
  pipeline(dir, "", dir.file("a_file"));
  EXPECT_EQ(run_pipeline(dir, b, "", log), 1) << log;
  EXPECT_NE(log.find("key 'output_root'"), std::string::npos) << log;
  EXPECT_EQ(test_support::read_text(dir.file("a_file")), "x");

  pipeline(dir, "", "", std::string(300, 'n'));
  EXPECT_EQ(run_pipeline(dir, b, "", log), 1) << log;
  EXPECT_NE(log.find("mbd_runs[0].name"), std::string::npos) << log;
  EXPECT_NE(log.find("too long"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.file("out")));

  // Two MBD runs with one name would write into the same folder.
  std::string text = test_support::read_text(pipeline(dir));
  text.replace(text.find("report:"), 0,
               "  - {name: m, scene: " + std::string(CLEARJOINT_SOURCE_DIR) +
                 "/mbd_stage/scenes/slider_crank_ideal.yaml}\n");
  test_support::write_text(dir.file("p.yaml"), text);
  EXPECT_EQ(run_pipeline(dir, b, "", log), 1) << log;
  EXPECT_NE(log.find("key 'mbd_runs[1].name'"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

TEST(PipelineInterrupt, SigintDuringTheReportStopsPlotPyAndExits130)
{
  test_support::ScratchDir dir("pipeline_interrupt_report");
  const Build b(dir);
  std::string text = test_support::read_text(pipeline(dir));
  text.replace(text.find("report: false"), 13, "report: true");
  test_support::write_text(dir.file("p.yaml"), text);
  // A stand-in plot.py: instant for the stages' plots, long for the report (records its pid).
  test_support::write_text(dir.file("plot.py"),
                           "import os, sys, time\n"
                           "if sys.argv[1] == 'report':\n"
                           "    open(os.environ['REPORT_PID'], 'w').write(str(os.getpid()))\n"
                           "    time.sleep(60)\n");
  const std::string pid_file = dir.file("report.pid");
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir.file("p.yaml"), "--build-dir", b.root}, dir.file("log.txt"),
    {"CLEARJOINT_PLOT_SCRIPT=" + dir.file("plot.py"), "REPORT_PID=" + pid_file});
  ASSERT_GE(pid, 0);
  for (int i = 0; i < 6000 && test_support::read_text(pid_file).empty(); ++i)
    usleep(20000);
  ASSERT_FALSE(test_support::read_text(pid_file).empty()) << test_support::read_text(dir.file("log.txt"));
  const pid_t report = std::stoi(test_support::read_text(pid_file));
  kill(pid, SIGINT);
  ASSERT_EQ(test_support::wait_exit_code(pid), 130) << test_support::read_text(dir.file("log.txt"));
  const std::string manifest = test_support::read_text(dir.file("out/r/manifest.json"));
  EXPECT_NE(manifest.find("\"status\": \"incomplete\""), std::string::npos) << manifest;
  bool gone = false;
  for (int i = 0; i < 250 && !gone; ++i, usleep(20000))
    gone = kill(report, 0) != 0;
  EXPECT_TRUE(gone) << "the report's plot.py was stopped";
}

// The impact section is checked with the rest: its scene must be an impact study, and a law
// given as a file must read; each is an input error naming the key, nothing written.
TEST(PipelineCheck, TheImpactSectionIsChecked)
{
  test_support::ScratchDir dir("pipeline_check_impact");
  const Build b(dir);
  test_support::write_text(dir.file("impact.yaml"), "{\"study\": \"impact\"}\n");
  test_support::write_text(dir.file("radial.yaml"), "{\"study\": \"radial\"}\n");
  test_support::write_text(dir.file("bad_law.json"), "{\"schema\": \"clearjoint.law/1\"}\n");
  const std::string law_ok = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  for (const auto &[section, key] : std::vector<std::pair<std::string, std::string>>{
         {"impact: {scene: " + dir.file("radial.yaml") + ", law: {file: " + law_ok + "}}\n",
          "impact.scene"},
         {"impact: {scene: " + dir.file("impact.yaml") + ", law: {file: " +
            dir.file("bad_law.json") + "}}\n",
          "impact.law.file"}})
  {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("report: false"), 13, section + "report: false");
    test_support::write_text(dir.file("p.yaml"), text);
    std::string log;
    EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << log;
    EXPECT_NE(log.find("key '" + key + "'"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir.file("out")));
  }
  std::string text = test_support::read_text(pipeline(dir));
  text.replace(text.find("report: false"), 13,
               "impact: {scene: " + dir.file("impact.yaml") + ", law: {file: " + law_ok +
                 "}}\nreport: false");
  test_support::write_text(dir.file("p.yaml"), text);
  std::string log;
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
}

// The rigid journal's impact scene with its own settings (impact.overrides, then
// impact.presets.<preset>): fe_stage checks the scene they make, and a bad value is named by
// the pipeline key that set it — the overrides' when the preset's own settings leave it, the
// preset's own when they set it last; exit 1, nothing written.
TEST(PipelineCheck, TheImpactStudysOwnSettingsAreCheckedAndNamed)
{
  test_support::ScratchDir dir("pipeline_check_impact_own");
  const Build b(dir);
  test_support::write_text(dir.file("impact.yaml"), "{\"study\": \"impact\"}\n");
  const std::string law_ok = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  const auto with = [&](const std::string &own) {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("report: false"), 13,
                 "impact: {scene: " + dir.file("impact.yaml") + ", law: {file: " + law_ok + "}, " +
                   own + "}\nreport: false");
    test_support::write_text(dir.file("p.yaml"), text);
  };
  const std::string presets = "presets: {fast: {impact.steps_per_period: %}, standard: null, "
                              "accurate: null}";
  const auto fast = [&](const std::string &value) {
    std::string p = presets;
    return p.replace(p.find('%'), 1, value);
  };
  for (const auto &[own, key] : std::vector<std::pair<std::string, std::string>>{
         {"overrides: {impact.steps_per_period: 2}", "impact.overrides.impact.steps_per_period"},
         {fast("3"), "impact.presets.fast.impact.steps_per_period"},
         // the preset's own value comes last: it is the one fe_stage sees
         {"overrides: {impact.steps_per_period: 80}, " + fast("5"),
          "impact.presets.fast.impact.steps_per_period"}})
    {
      with(own);
      std::string log;
      EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << own << log;
      EXPECT_NE(log.find("key '" + key + "'"), std::string::npos) << own << log;
      EXPECT_FALSE(fs::exists(dir.file("out"))) << own;
    }
  // a bad overrides value mended by the preset's own setting passes
  with("overrides: {impact.steps_per_period: 2}, " + fast("160"));
  std::string log;
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
}

// The impact section's deformable variant (issue 31 item 2) is checked with the rest: its scene
// must exist, read, be an impact study and have a deformable journal (a rigid one would repeat
// impact.scene's), and fe_stage must accept it; each failure is an input error naming the
// pipeline key, exit 1, nothing written. (A journal-mass key with the deformable journal is
// fe_stage's own error: the end-to-end test checks it with the real stage.)
TEST(PipelineCheck, TheDeformableImpactIsChecked)
{
  test_support::ScratchDir dir("pipeline_check_impact_deformable");
  const Build b(dir);
  const std::string law_ok = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  test_support::write_text(dir.file("impact.yaml"), "{\"study\": \"impact\"}\n");
  test_support::write_text(dir.file("deformable.yaml"),
                           "{\"study\": \"impact\", \"loading\": {\"journal\": \"end_faces\"}}\n");
  test_support::write_text(dir.file("rigid.yaml"),
                           "{\"study\": \"impact\", \"loading\": {\"journal\": \"rigid\"}}\n");
  test_support::write_text(dir.file("radial.yaml"),
                           "{\"loading\": {\"journal\": \"end_faces\"}}\n");
  test_support::write_text(dir.file("broken.yaml"), "{\"study\": [\n");
  const auto with = [&](const std::string &deformable) {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("report: false"), 13,
                 "impact: {scene: " + dir.file("impact.yaml") + ", law: {file: " + law_ok +
                   "}, deformable: " + deformable + "}\nreport: false");
    test_support::write_text(dir.file("p.yaml"), text);
  };
  for (const auto &[deformable, says] : std::vector<std::pair<std::string, std::string>>{
         {"{scene: " + dir.file("missing.yaml") + "}", "no such file"},
         {"{scene: " + dir.file("broken.yaml") + "}", "readable"},
         {"{scene: " + dir.file("radial.yaml") + "}", "study: impact"},
         {"{scene: " + dir.file("impact.yaml") + "}", "deformable journal"},  // default: rigid
         {"{scene: " + dir.file("rigid.yaml") + "}", "deformable journal"},
         // the overrides make it rigid again
         {"{scene: " + dir.file("deformable.yaml") + ", overrides: {loading.journal: rigid}}",
          "deformable journal"}})
  {
    with(deformable);
    std::string log;
    EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << deformable << log;
    EXPECT_NE(log.find("key 'impact.deformable.scene'"), std::string::npos) << deformable << log;
    EXPECT_NE(log.find(says), std::string::npos) << deformable << log;
    EXPECT_FALSE(fs::exists(dir.file("out"))) << deformable;
  }
  with("{scene: " + dir.file("deformable.yaml") + ", overrides: {mesh.global_refinements: 0}}");
  std::string log;
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

// The rolling section is checked with the rest (issue 13 item 5): its scene must exist and be a
// rolling study, and fe_stage must accept it with the preset's and the section's overrides;
// each failure is an input error naming the pipeline key, exit 1, nothing written.
TEST(PipelineCheck, TheRollingSectionIsChecked)
{
  test_support::ScratchDir dir("pipeline_check_rolling");
  const Build b(dir);
  test_support::write_text(dir.file("rolling.yaml"), "{\"study\": \"rolling\"}\n");
  test_support::write_text(dir.file("impact.yaml"), "{\"study\": \"impact\"}\n");
  test_support::write_text(dir.file("none.yaml"), "{\"geometry\": {\"t_B\": 0.004}}\n");
  test_support::write_text(dir.file("broken.yaml"), "{\"study\": [\n");
  const auto with = [&](const std::string &section, const std::string &fast_fe = "null") {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("report: false"), 13, section + "report: false");
    const std::string fast = "fast: {fe: null,";
    text.replace(text.find(fast), fast.size(), "fast: {fe: " + fast_fe + ",");
    test_support::write_text(dir.file("p.yaml"), text);
  };
  for (const auto &[section, fast_fe, key] : std::vector<std::array<std::string, 3>>{
         {"rolling: {scene: " + dir.file("impact.yaml") + "}\n", "null", "rolling.scene"},
         {"rolling: {scene: " + dir.file("none.yaml") + "}\n", "null", "rolling.scene"},
         {"rolling: {scene: " + dir.file("missing.yaml") + "}\n", "null", "rolling.scene"},
         {"rolling: {scene: " + dir.file("broken.yaml") + "}\n", "null", "rolling.scene"},
         // fe_stage rejects fewer than 4 steps: the key that set it is named
         {"rolling: {scene: " + dir.file("rolling.yaml") + "}\n", "{rolling.n_steps: 2}",
          "presets.fast.fe.rolling.n_steps"},
         {"rolling: {scene: " + dir.file("rolling.yaml") + ", overrides: {rolling.n_steps: 3}}\n",
          "{rolling.n_steps: 6}", "rolling.overrides.rolling.n_steps"}})
  {
    with(section, fast_fe);
    std::string log;
    EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << section << log;
    EXPECT_NE(log.find("key '" + key + "'"), std::string::npos) << section << log;
    EXPECT_FALSE(fs::exists(dir.file("out"))) << section;
  }
  // The other study's name is in the message.
  with("rolling: {scene: " + dir.file("impact.yaml") + "}\n");
  std::string log;
  run_pipeline(dir, b, "--check", log);
  EXPECT_NE(log.find("study: rolling"), std::string::npos) << log;
  EXPECT_NE(log.find("\"impact\""), std::string::npos) << log;
  // A valid one passes, with a preset's rolling.n_steps (a key only this study reads).
  with("rolling: {scene: " + dir.file("rolling.yaml") + "}\n", "{rolling.n_steps: 6}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

// The rolling study's own preset settings (rolling.presets) are checked like a sweep's: a value
// fe_stage rejects is named by its pipeline key, rolling.presets.<preset>.<key>, and only the
// preset that runs is checked. Applied after the preset's map and the block's overrides: a
// preset setting replaces a bad override of the same key.
TEST(PipelineCheck, TheRollingStudysOwnPresetSettingIsNamedByItsKey)
{
  test_support::ScratchDir dir("pipeline_check_rolling_presets");
  const Build b(dir);
  test_support::write_text(dir.file("rolling.yaml"), "{\"study\": \"rolling\"}\n");
  const auto with = [&](const std::string &overrides, const std::string &fast) {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("report: false"), 13,
                 "rolling:\n  scene: " + dir.file("rolling.yaml") + "\n  overrides: " + overrides +
                   "\n  presets:\n    fast: " + fast +
                   "\n    standard: {rolling.n_steps: 16}\n    accurate: null\n"
                   "report: false");
    const std::string preset = "fast: {fe: null,";
    text.replace(text.find(preset), preset.size(), "fast: {fe: {rolling.n_steps: 6},");
    test_support::write_text(dir.file("p.yaml"), text);
  };
  std::string log;
  with("{rolling.n_steps: 8}", "{rolling.n_steps: 32, mesh.contact_refinements: 0}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  // fe_stage (and the stand-in) refuse fewer than 4 steps: the preset's own setting is named.
  with("{rolling.n_steps: 8}", "{rolling.n_steps: 2, mesh.contact_refinements: 0}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 1) << log;
  EXPECT_NE(log.find("key 'rolling.presets.fast.rolling.n_steps'"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.file("out"))) << log;
  // Without --check too: the run stops before its first task.
  EXPECT_EQ(run_pipeline(dir, b, "", log), 1) << log;
  EXPECT_NE(log.find("key 'rolling.presets.fast.rolling.n_steps'"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.file("out"))) << log;
  // Another preset runs: the fast preset's setting is not used, so not checked.
  EXPECT_EQ(run_pipeline(dir, b, "--check --preset standard", log), 0) << log;
  // A bad override that the preset's setting replaces is not in the scene fe_stage checks; with
  // a preset that sets nothing it is, and named as the override.
  with("{rolling.n_steps: 2}", "{rolling.n_steps: 32}");
  EXPECT_EQ(run_pipeline(dir, b, "--check", log), 0) << log;
  EXPECT_EQ(run_pipeline(dir, b, "--check --preset accurate", log), 1) << log;
  EXPECT_NE(log.find("key 'rolling.overrides.rolling.n_steps'"), std::string::npos) << log;
}

// SIGINT and SIGTERM while a stage plots: run_pipeline passes the signal on (to the stage's
// process group), the stage stops its plot.py and the run exits 130/143 with the task left as
// '<dir>.partial'. The stand-in plot.py ignores SIGINT, so only the stage's SIGTERM ends it:
// a stage that did not stop its child would leave it running. Two fit tasks may plot at once
// (two CPU slots), so each plot.py records its pid in a file of its own, written whole (a shared
// file truncated by the second one read empty: CI, stop 51).
TEST(PipelineInterrupt, ASignalWhileAStagePlotsStopsItsPlotPy)
{
  for (const auto &[sig, code] : std::vector<std::pair<int, int>>{{SIGINT, 130}, {SIGTERM, 143}})
  {
    test_support::ScratchDir dir("pipeline_interrupt_stage_plot");
    const Build b(dir);
    pipeline(dir);
    // The first stage that plots is fit_stage (the FE stand-in does not plot).
    test_support::write_text(dir.file("plot.py"),
                             "import os, signal, sys, time\n"
                             "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
                             "d, me = os.environ['PLOT_PIDS'], str(os.getpid())\n"
                             "open(os.path.join(d, '.' + me), 'w').write(me)\n"
                             "os.replace(os.path.join(d, '.' + me), os.path.join(d, me))\n"
                             "time.sleep(60)\n");
    const std::string pid_dir = dir.file("plot_pids");
    fs::create_directories(pid_dir);
    const auto plots = [&pid_dir]() {
      std::vector<pid_t> pids;
      for (const auto &e : fs::directory_iterator(pid_dir))
        if (e.path().filename().string().front() != '.')
          pids.push_back(std::stoi(e.path().filename().string()));
      return pids;
    };
    const pid_t pid = test_support::start_process(
      RUN_PIPELINE_EXE, {dir.file("p.yaml"), "--build-dir", b.root}, dir.file("log.txt"),
      {"CLEARJOINT_PLOT_SCRIPT=" + dir.file("plot.py"), "PLOT_PIDS=" + pid_dir});
    ASSERT_GE(pid, 0);
    for (int i = 0; i < 6000 && plots().empty(); ++i)
      usleep(20000);
    ASSERT_FALSE(plots().empty()) << test_support::read_text(dir.file("log.txt"));
    kill(pid, sig);
    ASSERT_EQ(test_support::wait_exit_code(pid), code)
      << test_support::read_text(dir.file("log.txt"));
    // every plot.py that started, the second task's too if it had begun to plot
    for (const pid_t plot : plots())
      {
        bool gone = false;
        for (int i = 0; i < 250 && !gone; ++i, usleep(20000))
          gone = kill(plot, 0) != 0;
        EXPECT_TRUE(gone) << "the stage's plot.py " << plot << " was stopped";
      }
    // The fit task that was plotting is left as '<dir>.partial' (redone by the next run), with
    // no law in it (fit_stage removes its temporaries) and none under a final name.
    bool partial = false;
    for (const auto &e : fs::recursive_directory_iterator(dir.file("out/r/fit")))
    {
      const std::string name = e.path().filename().string();
      if (e.is_directory() && name.size() > 8 && name.substr(name.size() - 8) == ".partial")
        partial = true;
      EXPECT_NE(name, "law.json") << e.path();
      EXPECT_EQ(name.find(".tmp."), std::string::npos) << e.path();
    }
    EXPECT_TRUE(partial) << "the interrupted fit task is marked .partial";
    const std::string manifest = test_support::read_text(dir.file("out/r/manifest.json"));
    EXPECT_NE(manifest.find("\"status\": \"incomplete\""), std::string::npos) << manifest;
  }
}

// The fit commands are checked too (fit_stage --check with the options the run will give):
// a preset's measured discretisation error that fit_stage refuses stops the run before its
// first task, naming the preset key (it used to fail at the first fit, after the FE cases).
TEST(PipelineCheck, TheFitCommandsAreChecked)
{
  test_support::ScratchDir dir("pipeline_check_fit");
  const Build b(dir);
  for (const std::string percent : {"100", "4.8"})
  {
    std::string text = test_support::read_text(pipeline(dir));
    const std::string fast = "fast: {fe: null, mbd: null}";
    text.replace(text.find(fast), fast.size(),
                 "fast: {fe: null, mbd: null, measured: {note: n, error_F_max: {thickness: "
                 "{percent: " + percent + ", where: w}}}}");
    test_support::write_text(dir.file("p.yaml"), text);
    for (const std::string args : {"--check", ""})
    {
      std::string log;
      const int rc = run_pipeline(dir, b, args, log);
      if (percent == "100")
      {
        EXPECT_EQ(rc, 1) << log;
        EXPECT_NE(log.find("key 'presets.fast.measured.error_F_max.thickness.percent'"),
                  std::string::npos)
          << log;
        EXPECT_FALSE(fs::exists(dir.file("out"))) << "nothing under the output root: " << log;
      }
      else
        EXPECT_EQ(rc, 0) << log;
      fs::remove_all(dir.file("out"));
    }
  }
}

// Run from a folder whose name is not UTF-8 (a byte 0xFF): the scene paths made absolute from
// it go into pipeline_summary.json and the stages' manifests as U+FFFD, and the run completes
// (the summary's write used to throw: "a path with a byte 0xFF makes run_pipeline abort").
TEST(PipelineRun, AWorkingFolderThatIsNotUtf8)
{
  test_support::ScratchDir dir("pipeline_not_utf8_cwd");
  const Build b(dir);
  const std::string folder = dir.file("p\xff");
  fs::create_directories(folder);
  pipeline(dir, ", overrides: {duration: 0.002}");
  std::string text = test_support::read_text(dir.file("p.yaml"));
  text.replace(text.find(dir.file("fe.yaml")), dir.file("fe.yaml").size(), "fe.yaml");
  test_support::write_text(folder + "/p.yaml", text);
  test_support::write_text(folder + "/fe.yaml", "{\"geometry\": {\"t_B\": 0.004}}\n");
  const int rc = test_support::run_command("cd '" + folder + "' && " + RUN_PIPELINE_EXE +
                                             " p.yaml --no-plots --build-dir " + b.root,
                                           dir.file("log.txt"));
  ASSERT_EQ(rc, 0) << test_support::read_text(dir.file("log.txt"));
  const std::string summary = test_support::read_text(dir.file("out/r/pipeline_summary.json"));
  EXPECT_NE(summary.find("p\xef\xbf\xbd"), std::string::npos) << summary;
  EXPECT_NO_THROW(read_json_file(dir.file("out/r/pipeline_summary.json")));
}

// A .geo named by an FE scene is parsed by Gmsh in the check (gmsh -0 with the mesh task's
// -setnumber values): one Gmsh cannot read is an input error naming geometry.mesh before any
// task (it used to pass the check and fail as the run's first task); the shipped one passes.
TEST(PipelineCheck, AGeoFileGmshCannotReadIsAnInputError)
{
  if (std::system("command -v gmsh > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "gmsh is not installed";
  test_support::ScratchDir dir("pipeline_check_geo");
  const Build b(dir);
  test_support::write_text(dir.file("bad.geo"), "Point(1) = {0, 0, 0\n");
  const std::string good =
    std::string(CLEARJOINT_SOURCE_DIR) + "/fe_stage/geometries/flanged_bearing.geo";
  for (const std::string &geo : {dir.file("bad.geo"), good})
  {
    std::string text = test_support::read_text(pipeline(dir));
    text.replace(text.find("    parameter:"), 0,
                 "    overrides: {geometry.mesh: " + geo + "}\n");
    test_support::write_text(dir.file("p.yaml"), text);
    std::string log;
    const int rc = run_pipeline(dir, b, "--check", log);
    if (geo == good)
      EXPECT_EQ(rc, 0) << log;
    else
    {
      EXPECT_EQ(rc, 1) << log;
      EXPECT_NE(log.find("key 'geometry.mesh'"), std::string::npos) << log;
      EXPECT_NE(log.find("gmsh -0: Error"), std::string::npos) << log;
    }
    EXPECT_FALSE(fs::exists(dir.file("out"))) << log;
  }
}
