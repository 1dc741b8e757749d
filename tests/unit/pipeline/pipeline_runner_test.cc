// run_pipeline end to end with stand-in FE and MBD stages (tests/data/fake_stages) and the real
// fit_stage: reuse, re-running only what changed, interrupts, failing stages, bad input.
#include "common/csv.h"
#include "common/strict_reader.h"
#include "common/units.h"
#include "fake_pipeline.h"
#include "geometry/joint_geometry.h"
#include "laws/law_family.h"
#include "laws/law_file.h"
#include "laws/own_error_estimate.h"
#include "pipeline/mesh_task.h"
#include "pipeline/pipeline_config.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <set>
#include <thread>
#include <tuple>

using namespace clearjoint;
namespace fs = std::filesystem;

using namespace fake_pipeline;

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
  const pid_t pid = test_support::start_process(
    RUN_PIPELINE_EXE, {dir.file("p.yaml"), "--no-plots", "--build-dir", build.root},
    dir.file("log.txt"), {"CLEARJOINT_FAKE_SLEEP=30"});
  ASSERT_GE(pid, 0);
  // Wait until the first FE task is running, then interrupt the pipeline.
  const fs::path partial = dir.file("out/r/fe/thickness/t_B=0.002.partial");
  const fs::path started = dir.file("out/r/fe/thickness/t_B=0.002.command.txt");
  for (int i = 0; i < 200 && !fs::exists(started); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  ASSERT_EQ(test_support::wait_exit_code(pid), 130)
    << "128 + SIGINT: " << test_support::read_text(dir.file("log.txt"));
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

namespace
{
  /// A pipeline with a misalignment sweep (θ in deg, theta_max among the values) and an MBD run
  /// that takes its law family; `mbd_scene` and `mbd_overrides` describe that run.
  std::string misalignment_yaml(const std::string &dir, const std::string &mbd_scene,
                                const std::string &mbd_key, const std::string &mbd_overrides)
  {
    test_support::write_text(dir + "/mis.yaml",
                             "schema: clearjoint.fe/1\nstudy: misalignment\n"
                             "misalignment: {theta_deg: 1.0}\nloading: {journal: rigid}\n");
    return "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " + dir + "/out\npreset: fast\n"
           "presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}, "
           "accurate: {fe: null, mbd: null}}\n"
           "fe_sweeps:\n  - name: misalignment\n    scene: " + dir + "/mis.yaml\n"
           "    parameter: {name: theta, unit: deg, key: misalignment.theta_deg}\n"
           "    values: [1.0, 2.0, theta_max]\n"
           "fit: {weighting: absolute, family_out_of_range: clamp}\n"
           "mbd_runs:\n"
           "  - name: tilted\n    scene: " + mbd_scene + "\n"
           "    overrides: " + mbd_overrides + "\n"
           "    laws: [{key: " + mbd_key + ", sweep: misalignment}]\n"
           "  - {name: at_max, scene: " + mbd_scene + ", laws: [{key: " + mbd_key +
           ", sweep: misalignment, value: theta_max}]}\n"
           "report: false\n";
  }

  const double theta_max_deg = geometry::degrees(*geometry::theta_max(geometry::JointGeometry{}));
} // namespace

TEST(RunPipeline, MisalignmentSweepRunsThetaMaxAtFullPrecisionAndItsFamilyInRadians)
{
  test_support::ScratchDir dir("pipeline_misalignment");
  FakeBuild build(dir);
  test_support::write_text(dir.file("mbd.yaml"), "{\"joint\": {\"model\": \"fe_law\", \"law_file\": \"none\"}}\n");
  test_support::write_text(dir.file("p.yaml"),
                           misalignment_yaml(dir.path(), dir.file("mbd.yaml"), "joint.law_file",
                                             "{joint.model: law_family}"));
  const Outcome first = run(dir, build);
  ASSERT_EQ(first.exit_code, 0) << first.log;
  const std::string max_label = "theta=" + pipeline::value_label(theta_max_deg);
  const std::set<std::string> expected = {
    "fe/misalignment/theta=1", "fe/misalignment/theta=2", "fe/misalignment/" + max_label,
    "fit/misalignment/theta=1", "fit/misalignment/theta=2", "fit/misalignment/" + max_label,
    "fit/misalignment/family", "mbd/tilted", "mbd/at_max"};
  EXPECT_EQ(with(first, "ran"), expected) << first.log;

  // The scene got θ_max at full precision (the stand-in, like fe_stage, rejects θ > θ_max, so
  // a value rounded up would have failed the run), and the law file says where it came from.
  const auto scene = read_yaml_file(dir.file("out/r/scenes/fe_misalignment_" + max_label + ".yaml"));
  EXPECT_EQ(scene["misalignment"]["theta_deg"].get<double>(), theta_max_deg);
  const auto law = laws::read_law_file(dir.file("out/r/fit/misalignment/" + max_label + "/law.json"));
  EXPECT_EQ(law.scene["misalignment"]["theta_deg"].get<double>(), theta_max_deg);

  // The family is over θ in rad (mbd_stage evaluates it at the tilt in rad).
  const auto family = laws::read_law_family(dir.file("out/r/fit/misalignment/family/family.json"));
  EXPECT_EQ(family.parameter(), "theta");
  EXPECT_EQ(family.unit(), "rad");
  ASSERT_EQ(family.members().size(), 3u);
  EXPECT_DOUBLE_EQ(family.members()[0].value, units::pi / 180.0);
  EXPECT_DOUBLE_EQ(family.members()[2].value, *geometry::theta_max(geometry::JointGeometry{}));
  EXPECT_EQ(family.parameter_policy(), laws::RangePolicy::clamp);
  // Larger tilt, lower force (what the stand-in does: it checks the order of the members).
  EXPECT_LT(family.members()[2].law.F_ref(), family.members()[0].law.F_ref());

  // The MBD scene got the override and the family; `value: theta_max` picked that law.
  const auto used = read_json_file(dir.file("out/r/mbd/tilted/scene_used.json"));
  EXPECT_EQ(used["joint"]["model"], "law_family");
  EXPECT_EQ(used["joint"]["law_file"], dir.file("out/r/fit/misalignment/family/family.json"));
  const auto at_max = read_json_file(dir.file("out/r/mbd/at_max/scene_used.json"));
  EXPECT_EQ(at_max["joint"]["law_file"], dir.file("out/r/fit/misalignment/" + max_label + "/law.json"));
  EXPECT_EQ(at_max["joint"]["model"], "fe_law") << "overrides belong to their run only";

  const Outcome second = run(dir, build);
  ASSERT_EQ(second.exit_code, 0) << second.log;
  EXPECT_TRUE(with(second, "ran").empty()) << second.log;
  // The summary tells the report the family's unit and each case's keyword.
  const auto summary = read_json_file(dir.file("out/r/pipeline_summary.json"));
  EXPECT_EQ(summary["sweeps"][0]["family_unit"], "rad");
  EXPECT_EQ(summary["sweeps"][0]["cases"][2]["keyword"], "theta_max");
  EXPECT_EQ(summary["presets"].size(), 3u);
}

// Issue 31 item 5: the misalignment sweep on the deformable (core-loaded) journal, whose
// adaptive meshes the sweep sets per preset (fe_sweeps[i].presets) after the preset's own
// uniform level; the law family is fitted from those cases. The global presets here set
// levels the sweep must undo, so a sweep preset applied too early (or not at all) shows.
TEST(RunPipeline, TheMisalignmentFamilyFromTheDeformableJournalOnTheSweepsOwnMeshes)
{
  test_support::ScratchDir dir("pipeline_misalignment_core");
  FakeBuild build(dir);
  test_support::write_text(dir.file("mbd.yaml"), "{\"joint\": {\"model\": \"fe_law\", \"law_file\": \"none\"}}\n");
  std::string text = misalignment_yaml(dir.path(), dir.file("mbd.yaml"), "joint.law_file",
                                       "{joint.model: law_family}");
  const auto replace = [&](const std::string &from, const std::string &to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}",
          "presets: {fast: {fe: {mesh.global_refinements: 1}, mbd: null}, "
          "standard: {fe: {mesh.global_refinements: 2}, mbd: null}");
  replace("    values: [1.0, 2.0, theta_max]\n",
          "    values: [1.0, 2.0, theta_max]\n    overrides: {loading.journal: core}\n"
          "    presets:\n"
          "      fast: {mesh.global_refinements: 0, mesh.adaptive_cycles: 2}\n"
          "      standard: {mesh.global_refinements: 0, mesh.adaptive_cycles: 3}\n"
          "      accurate: null\n");
  test_support::write_text(dir.file("p.yaml"), text);
  const std::string max_label = "theta=" + pipeline::value_label(theta_max_deg);

  for (const auto &[preset, cycles] : std::vector<std::pair<std::string, int>>{{"fast", 2},
                                                                               {"standard", 3}})
  {
    const Outcome o = run(dir, build, "--preset " + preset);
    ASSERT_EQ(o.exit_code, 0) << o.log;
    EXPECT_EQ(with(o, "ran").count("fe/misalignment/" + max_label), 1u)
      << "another preset, another scene: " << o.log;
    for (const std::string label : {"theta=1", "theta=2", max_label.c_str()})
    {
      const auto scene = read_yaml_file(dir.file("out/r/scenes/fe_misalignment_" + label + ".yaml"));
      EXPECT_EQ(scene["loading"]["journal"], "core") << preset << " " << label;
      EXPECT_EQ(scene["mesh"]["global_refinements"], 0) << "the sweep's preset after the preset's";
      EXPECT_EQ(scene["mesh"]["adaptive_cycles"], cycles) << preset << " " << label;
      // The law fitted from it says which journal and mesh it came from.
      const auto law = laws::read_law_file(dir.file("out/r/fit/misalignment/" + label + "/law.json"));
      EXPECT_EQ(law.scene["loading"]["journal"], "core") << label;
      EXPECT_EQ(law.scene["mesh"]["adaptive_cycles"], cycles) << label;
    }
    // The family over θ in rad from those three cases; the stand-in's core journal is 0.7 times
    // its rigid one at every θ (so a rigid case slipped in would stand out) and falls with θ.
    const auto family = laws::read_law_family(dir.file("out/r/fit/misalignment/family/family.json"));
    EXPECT_EQ(family.unit(), "rad");
    ASSERT_EQ(family.members().size(), 3u);
    EXPECT_LT(family.members()[2].law.F_ref(), family.members()[0].law.F_ref());
    const auto used = read_json_file(dir.file("out/r/mbd/tilted/scene_used.json"));
    EXPECT_EQ(used["joint"]["law_file"], dir.file("out/r/fit/misalignment/family/family.json"));
    // The summary lists the sweep's own settings under each preset (the report's table).
    const auto summary = read_json_file(dir.file("out/r/pipeline_summary.json"));
    for (const auto &p : summary["presets"])
      if (p["name"] == "standard")
        EXPECT_EQ(p["sweeps"]["misalignment"]["mesh.adaptive_cycles"], 3) << p.dump();
      else if (p["name"] == "accurate")
        EXPECT_TRUE(p["sweeps"]["misalignment"].empty()) << p.dump();
  }

  // The rigid journal stays an option: without the override the same sweep fits the rigid
  // journal's laws, 1/0.7 times the core journal's at every θ in the stand-in.
  const auto core_family =
    laws::read_law_family(dir.file("out/r/fit/misalignment/family/family.json"));
  replace("    overrides: {loading.journal: core}\n", "    overrides: {loading.journal: rigid}\n");
  test_support::write_text(dir.file("p.yaml"), text);
  const Outcome rigid = run(dir, build, "--preset standard");
  ASSERT_EQ(rigid.exit_code, 0) << rigid.log;
  const auto rigid_family =
    laws::read_law_family(dir.file("out/r/fit/misalignment/family/family.json"));
  for (std::size_t i = 0; i < 3; ++i)
    // The same exponent, K scaled by the stand-in's 0.7: F_ref's ratio is 0.7 to the fit's
    // round-off (1e-9 relative is far above Ceres's converged digits on exact power-law data).
    EXPECT_NEAR(core_family.members()[i].law.F_ref() / rigid_family.members()[i].law.F_ref(),
                0.7, 1e-9) << i;
}

TEST(RunPipeline, TheRealMbdStageRunsTheTiltedSceneOnTheMisalignmentFamily)
{
  // The unit question end to end: the family the pipeline fits is evaluated by the real
  // mbd_stage at the tilt θ ≈ 1° = 0.01745 rad, inside the family's range [1°, θ_max].
  test_support::ScratchDir dir("pipeline_tilted_real_mbd");
  FakeBuild build(dir, true);
  const std::string tilted =
    std::string(CLEARJOINT_SOURCE_DIR) + "/mbd_stage/scenes/slider_crank_tilted_1deg.yaml";
  test_support::write_text(dir.file("p.yaml"),
                           misalignment_yaml(dir.path(), tilted, "clearance_joints.0.normal.law_file",
                                             "{clearance_joints.0.normal.model: law_family, "
                                             "duration: 0.02}"));
  const Outcome o = run(dir, build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  const auto summary = read_json_file(dir.file("out/r/mbd/tilted/summary.json"));
  const auto &normal = summary["clearance_joints"][0]["normal_model"];
  EXPECT_EQ(normal["name"], "law_family");
  EXPECT_EQ(normal["out_of_range"]["n_parameter_out_of_range"], 0)
    << "θ stays at 1° to round-off, at the family's lowest member";
  EXPECT_GT(summary["clearance_joints"][0]["n_impacts"]["radial"].get<int>(), 0)
    << "the family carried contacts";
}

TEST(RunPipeline, ChangingTheMeshFileRerunsFeAndEverythingDownstream)
{
  test_support::ScratchDir dir("pipeline_mesh_identity");
  FakeBuild build(dir);
  // The base scene names its mesh relative to its own folder.
  test_support::write_text(dir.file("a.msh"), "mesh A\n");
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  test_support::write_text(dir.file("fe.yaml"), "{\"geometry\": {\"t_B\": 0.004, \"mesh\": \"a.msh\"}}\n");
  const Outcome first = run(dir, build);
  ASSERT_EQ(first.exit_code, 0) << first.log;
  const auto scene = read_yaml_file(dir.file("out/r/scenes/fe_thickness_t_B=0.002.yaml"));
  EXPECT_EQ(scene["geometry"]["mesh"], fs::canonical(dir.file("a.msh")).string())
    << "a relative mesh path is made absolute like other paths";
  const double K_before = laws::read_law_file(dir.file("out/r/fit/thickness/t_B=0.002/law.json")).law.K;

  EXPECT_TRUE(with(run(dir, build), "ran").empty()) << "same mesh: all reused";
  test_support::write_text(dir.file("a.msh"), "mesh A, refined\n");  // same name, new content
  const Outcome o = run(dir, build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  const std::set<std::string> expected = {
    "fe/thickness/t_B=0.002", "fe/thickness/t_B=0.004", "fit/thickness/t_B=0.002",
    "fit/thickness/t_B=0.004", "fit/thickness/family", "mbd/fitted", "mbd/family",
    "mbd/fitted/band/n_low", "mbd/fitted/band/n_high", "mbd/fitted/band/K_low",
    "mbd/fitted/band/K_high"};
  EXPECT_EQ(with(o, "ran"), expected) << o.log;
  EXPECT_EQ(with(o, "reused"), std::set<std::string>{"mbd/paper"}) << "no FE behind it";
  EXPECT_NE(laws::read_law_file(dir.file("out/r/fit/thickness/t_B=0.002/law.json")).law.K, K_before)
    << "the stand-in's law depends on the mesh content";
}

TEST(RunPipeline, TwoGeometriesKeepTheirLawsApart)
{
  test_support::ScratchDir dir("pipeline_laws_apart");
  FakeBuild build(dir);
  test_support::write_text(dir.file("flanged.msh"), "another bearing\n");
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  const std::string second_sweep =
    "  - name: thickness_flanged\n    scene: " + dir.file("fe.yaml") + "\n"
    "    overrides: {geometry.mesh: " + dir.file("flanged.msh") + "}\n"
    "    parameter: {name: t_B, unit: m, key: geometry.t_B}\n    values: [0.002, 0.004]\n";
  yaml.insert(yaml.find("fit:"), second_sweep);
  yaml.insert(yaml.find("report:"),
              "  - {name: flanged, scene: " + dir.file("mbd.yaml") +
                ", laws: [{key: joint.law_file, sweep: thickness_flanged, value: 0.002}]}\n");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome o = run(dir, build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  const std::string a = dir.file("out/r/fit/thickness/t_B=0.002/law.json");
  const std::string b = dir.file("out/r/fit/thickness_flanged/t_B=0.002/law.json");
  const auto law_a = laws::read_law_file(a), law_b = laws::read_law_file(b);
  EXPECT_NE(law_a.law.K, law_b.law.K) << "different geometry, different law";
  EXPECT_FALSE(law_a.scene["geometry"].contains("mesh"));
  EXPECT_EQ(law_b.scene["geometry"]["mesh"], dir.file("flanged.msh")) << "the law names its mesh";
  EXPECT_EQ(read_json_file(dir.file("out/r/mbd/flanged/scene_used.json"))["joint"]["law_file"], b);
  EXPECT_EQ(read_json_file(dir.file("out/r/mbd/fitted/scene_used.json"))["joint"]["law_file"], a);
  // Same parameter value, two geometries: two families, each from its own sweep's cases.
  EXPECT_TRUE(fs::exists(dir.file("out/r/fit/thickness/family/family.json")));
  EXPECT_TRUE(fs::exists(dir.file("out/r/fit/thickness_flanged/family/family.json")));
}

TEST(RunPipeline, AGeoIsMeshedInItsOwnTaskSharedAndReused)
{
  if (!pipeline::gmsh_on_path())
    GTEST_SKIP() << "gmsh not installed";
  test_support::ScratchDir dir("pipeline_geo");
  FakeBuild build(dir);
  const std::string geo = std::string(CLEARJOINT_SOURCE_DIR) + "/fe_stage/geometries/default_joint.geo";
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.006]");
  const std::string sweep_keys = "    overrides: {geometry.mesh: " + geo + "}\n"
                                 "    mesh_parameters: {h: 0.004}\n";
  yaml.insert(yaml.find("    parameter:"), sweep_keys);
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome first = run(dir, build);
  ASSERT_EQ(first.exit_code, 0) << first.log;
  std::set<std::string> meshes;
  for (const auto &name : with(first, "ran"))
    if (name.rfind("mesh/", 0) == 0)
      meshes.insert(name);
  EXPECT_EQ(meshes.size(), 2u) << "one mesh per t_B (the joint's keys go to gmsh)\n" << first.log;
  const auto scene = read_yaml_file(dir.file("out/r/scenes/fe_thickness_t_B=0.006.yaml"));
  const std::string msh = scene["geometry"]["mesh"];
  EXPECT_EQ(fs::path(msh).filename(), "mesh.msh");
  EXPECT_TRUE(fs::exists(msh)) << msh;
  EXPECT_NE(test_support::read_text(fs::path(msh).parent_path() / "command.txt").find("-setnumber t_B 0.006"),
            std::string::npos);

  const Outcome second = run(dir, build);
  ASSERT_EQ(second.exit_code, 0) << second.log;
  EXPECT_TRUE(with(second, "ran").empty()) << second.log;

  // A finer mesh: re-meshed, and every FE case and what depends on it re-runs.
  yaml.replace(yaml.find("h: 0.004"), 8, "h: 0.003");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome third = run(dir, build);
  ASSERT_EQ(third.exit_code, 0) << third.log;
  const auto ran = with(third, "ran");
  EXPECT_TRUE(ran.count("fe/thickness/t_B=0.002") && ran.count("fe/thickness/t_B=0.006") &&
              ran.count("fit/thickness/family") && ran.count("mbd/family"))
    << third.log;
  EXPECT_EQ(with(third, "reused"), std::set<std::string>{"mbd/paper"});
}

TEST(RunPipeline, AGeoWithoutGmshIsAClearErrorBeforeAnyWork)
{
  test_support::ScratchDir dir("pipeline_no_gmsh");
  FakeBuild build(dir);
  const std::string geo = std::string(CLEARJOINT_SOURCE_DIR) + "/fe_stage/geometries/default_joint.geo";
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.006]");
  yaml.insert(yaml.find("    parameter:"), "    overrides: {geometry.mesh: " + geo + "}\n");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome o = run(dir, build, "", "PATH=" + dir.path().string());
  EXPECT_EQ(o.exit_code, 1) << o.log;
  EXPECT_NE(o.log.find("geometry.mesh"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("gmsh is not on PATH"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(dir.file("out/r/fe"))) << "nothing ran";
}

TEST(RunPipeline, AMissingMeshFileNamesTheKey)
{
  test_support::ScratchDir dir("pipeline_missing_mesh");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"), pipeline_yaml(dir.path(), "[0.002, 0.004]"));
  test_support::write_text(dir.file("fe.yaml"), "{\"geometry\": {\"t_B\": 0.004, \"mesh\": \"nope.msh\"}}\n");
  const Outcome o = run(dir, build);
  EXPECT_EQ(o.exit_code, 1) << o.log;
  EXPECT_NE(o.log.find("geometry.mesh"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("nope.msh"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("fe.yaml"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(dir.file("out/r/fe"))) << "nothing ran";
}

// Issue 15 items 6, 7, 8: the preset's measured error of F reaches the law file and moves the
// band; run_pipeline counts its tasks; stage logs name the final folders.
TEST(RunPipeline, PresetErrorReachesTheLawAndTheBandTasksAreCountedLogsNameFinalFolders)
{
  test_support::ScratchDir dir("pipeline_mesh_error");
  FakeBuild build(dir);
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  const std::string plain = "presets: {fast: {fe: null, mbd: null}, ";
  yaml.replace(yaml.find(plain), plain.size(),
               "presets: {fast: {fe: null, mbd: null, measured: {note: test, fe_dofs: null, "
               "fe_case_time: 1.0, pipeline_time: 10.0, error_F_max: {thickness: {percent: 3.0, "
               "where: made up for the test}}}}, ");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome o = run(dir, build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  const auto law = laws::read_law_file(dir.file("out/r/fit/thickness/t_B=0.002/law.json"));
  ASSERT_TRUE(law.discretisation_error.has_value());
  EXPECT_EQ(law.discretisation_error->F_relative, 0.03);
  EXPECT_NE(law.discretisation_error->description.find("made up for the test"), std::string::npos);
  // 2 FE, 2 fits, 1 family, 3 MBD, 4 regression + 2 mesh band variants
  EXPECT_EQ(with(o, "ran").size(), 14u) << o.log;
  EXPECT_EQ(with(o, "ran").count("mbd/fitted/band/mesh_high"), 1u);
  EXPECT_NE(o.log.find("task 1 of 14, about "), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("task 14 of 14"), std::string::npos) << o.log;
  const auto mesh_high = laws::read_law_file(
    read_json_file(dir.file("out/r/mbd/fitted_band/mesh_high/scene_used.json"))["joint"]["law_file"]);
  EXPECT_NEAR(mesh_high.F_ref() / law.F_ref(), 1.03, 1e-12);  // one multiplication's round-off
  for (const auto &entry : fs::recursive_directory_iterator(dir.file("out/r")))
    if (entry.path().filename() == "stage.log")
    {
      const std::string text = test_support::read_text(entry.path().string());
      const auto note = text.find("[run_pipeline]");
      EXPECT_EQ(text.substr(0, note).find(".partial"), std::string::npos) << entry.path();
    }
}

// Issue 32 item 4: every adaptive FE case's own estimate of the error of F(delta_max) (its
// manifest's extra.adaptive) is logged as the case ends, again per sweep at the end beside the
// preset's figure — here none, so it is named the figure to use —, reused cases too, and kept
// in the summary per case, with whether it is only the last cycle's change (last_change).
TEST(RunPipeline, EachAdaptiveCaseLogsItsOwnErrorEstimate)
{
  test_support::ScratchDir dir("pipeline_own_estimate");
  FakeBuild build(dir);
  test_support::write_text(dir.file("p.yaml"),
                           pipeline_yaml(dir.path(), "[0.002, 0.004]",
                                         ", \"mesh\": {\"adaptive_cycles\": 2}"));
  for (const bool reused : {false, true})
  {
    const Outcome o = run(dir, build);
    ASSERT_EQ(o.exit_code, 0) << o.log;
    // 12 tasks, and the MBD band's two mesh variants: the laws carry the cases' own estimate
    EXPECT_EQ(with(o, reused ? "reused" : "ran").size(), 14u) << o.log;
    EXPECT_NE(o.log.find("mbd/fitted/band/mesh_high"), std::string::npos) << o.log;
    EXPECT_NE(o.log.find("fe/thickness/t_B=0.002: own estimate of the error of F(delta_max) "
                         "0.5 % (extrapolated) on the last of 3 meshes, 4000 DoFs"),
              std::string::npos)
      << o.log;
    EXPECT_NE(o.log.find("FE sweep 'thickness': own estimate of the error of F(delta_max): "
                         "t_B=0.002 0.5 % (extrapolated), t_B=0.004 0.5 % (extrapolated); preset "
                         "fast: not measured for this sweep, so the run's own estimate is the "
                         "figure to use"),
              std::string::npos)
      << o.log;
    const auto summary = read_json_file(dir.file("out/r/pipeline_summary.json"));
    const auto &c = summary["sweeps"][0]["cases"][1];
    EXPECT_EQ(c["value"], 0.004);
    EXPECT_EQ(c["own_error_F_max"]["value"], 0.005);
    EXPECT_EQ(c["own_error_F_max"]["unit"], "1");
    EXPECT_EQ(c["own_error_F_max"]["last_change"], false);
    EXPECT_FALSE(c["own_error_F_max"].contains("lower_bound"));
    EXPECT_FALSE(c["own_error_F_max"].contains("last_change_record")) << "extrapolated";
    // no preset figure: each law carries its case's own estimate as its discretisation error
    // (fit_stage --discretisation-error-from), the family the largest of its cases'
    const auto law = laws::read_law_file(dir.file("out/r/fit/thickness/t_B=0.004/law.json"));
    ASSERT_TRUE(law.discretisation_error.has_value()) << "reused " << reused;
    EXPECT_EQ(law.discretisation_error->F_relative, 0.005);
    EXPECT_NE(law.discretisation_error->description.find("own estimate, 0.5 % (extrapolated)"),
              std::string::npos)
      << law.discretisation_error->description;
    EXPECT_NE(law.discretisation_error->description.find("fe/thickness/t_B=0.004/manifest.json"),
              std::string::npos)
      << law.discretisation_error->description;
    const auto family = laws::read_law_family(dir.file("out/r/fit/thickness/family/family.json"));
    for (const auto &m : family.members())
    {
      ASSERT_TRUE(m.law.discretisation_error.has_value());
      EXPECT_EQ(m.law.discretisation_error->F_relative, 0.005);
      EXPECT_NE(m.law.discretisation_error->description.find("the largest of 2 cases"),
                std::string::npos)
        << m.law.discretisation_error->description;
    }
  }
  // one adaptive cycle (two meshes): the last cycle's change, said so, flagged last_change
  test_support::ScratchDir one("pipeline_own_estimate_one_cycle");
  FakeBuild one_build(one);
  test_support::write_text(one.file("p.yaml"),
                           pipeline_yaml(one.path(), "[0.002, 0.004]",
                                         ", \"mesh\": {\"adaptive_cycles\": 1}"));
  {
    const Outcome o = run(one, one_build);
    ASSERT_EQ(o.exit_code, 0) << o.log;
    EXPECT_NE(o.log.find("fe/thickness/t_B=0.002: own estimate of the error of F(delta_max) "
                         "~1 % (the change in the last cycle, not extrapolated: on the recorded "
                         "sequences it was 0.05-29x the error, median 1.12) on the last of 2 "
                         "meshes, 2000 DoFs"),
              std::string::npos)
      << o.log;
    const auto summary = read_json_file(one.file("out/r/pipeline_summary.json"));
    const auto &c = summary["sweeps"][0]["cases"][1];
    EXPECT_EQ(c["own_error_F_max"]["value"], 0.01);
    EXPECT_EQ(c["own_error_F_max"]["last_change"], true);
    // the words the report quotes, from their one source
    EXPECT_EQ(c["own_error_F_max"]["last_change_record"], laws::last_change_record);
    const auto law = laws::read_law_file(one.file("out/r/fit/thickness/t_B=0.004/law.json"));
    ASSERT_TRUE(law.discretisation_error.has_value());
    EXPECT_EQ(law.discretisation_error->F_relative, 0.01);
    EXPECT_NE(law.discretisation_error->description.find("~1 % (the change in the last cycle"),
              std::string::npos)
      << law.discretisation_error->description;
  }
  // a sweep without adaptive cycles says nothing of it
  test_support::ScratchDir plain("pipeline_own_estimate_none");
  FakeBuild plain_build(plain);
  test_support::write_text(plain.file("p.yaml"), pipeline_yaml(plain.path(), "[0.002, 0.004]"));
  const Outcome o = run(plain, plain_build);
  ASSERT_EQ(o.exit_code, 0) << o.log;
  EXPECT_EQ(o.log.find("own estimate"), std::string::npos) << o.log;
  EXPECT_FALSE(laws::read_law_file(plain.file("out/r/fit/thickness/t_B=0.004/law.json"))
                 .discretisation_error.has_value())
    << "no estimate, no preset figure: the law says null";
}

// Issue 13 item 5: the rolling study is one fe_stage task, fe/rolling, with the preset's `fe`
// overrides (a key only it reads, rolling.n_steps, included) and its own overrides after them,
// its own time in the ETA (rolling_time), reused like any task; nothing depends on it.
TEST(RunPipeline, TheRollingStudyIsOneTaskWithItsOwnTime)
{
  test_support::ScratchDir dir("pipeline_rolling");
  FakeBuild build(dir);
  test_support::write_text(dir.file("rolling.yaml"),
                           "{\"study\": \"rolling\", \"loading\": {\"delta_max\": 5e-5}}\n");
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  const std::string plain = "presets: {fast: {fe: null, mbd: null}, ";
  // fe_case_time 1 s × 2 FE cases, the rolling study its own 50 s, and the 10 other tasks share
  // the rest of the pipeline's 80 s, (80 − 2 − 50)/10 = 2.8 s each: "about 80 s" (without the
  // rolling study's own time the estimate would be a lower bound, "at least").
  yaml.replace(yaml.find(plain), plain.size(),
               "presets: {fast: {fe: {rolling.n_steps: 6, rolling.omega_B: 10.0}, mbd: null, "
               "measured: {note: test, fe_case_time: 1.0, pipeline_time: 80.0, "
               "rolling_time: 50.0, error_F_max: {}}}, ");
  yaml.replace(yaml.find("report: false"), 13,
               "rolling: {scene: " + dir.file("rolling.yaml") +
                 ", overrides: {rolling.omega_B: 12.0}}\nreport: false");
  test_support::write_text(dir.file("p.yaml"), yaml);
  // One task at a time: the whole 80 s (two at once: RunEta.TasksAtOnceShareTheWork).
  const Outcome first = run(dir, build, "--jobs 1");
  ASSERT_EQ(first.exit_code, 0) << first.log;
  EXPECT_EQ(with(first, "ran").size(), 13u) << "12 as before and the rolling task\n" << first.log;
  EXPECT_EQ(with(first, "ran").count("fe/rolling"), 1u) << first.log;
  EXPECT_NE(first.log.find("task 1 of 13, about 1 min 20 s left"), std::string::npos) << first.log;
  const fs::path run_dir = dir.file("out/r");
  const auto summary = read_json_file((run_dir / "pipeline_summary.json").string());
  ASSERT_TRUE(summary.contains("rolling")) << summary.dump(2);
  EXPECT_EQ(summary["rolling"]["status"], "complete");
  EXPECT_EQ(summary["rolling"]["fe_dir"], (run_dir / "fe/rolling").string());
  for (const auto &t : summary["tasks"])
    if (t["name"] == "fe/rolling")
      EXPECT_EQ(t["stage"], "fe_rolling") << "its own stage in the ETA";
  // The stand-in fe_stage wrote one row per step after t = 0: the preset's n_steps reached it,
  // and the rolling block's override came after the preset's.
  const CsvTable history = read_csv((run_dir / "fe/rolling/rolling_history.csv").string());
  EXPECT_EQ(history.rows.size(), 7u);
  const auto used = read_json_file((run_dir / "fe/rolling/manifest.json").string());
  EXPECT_EQ(used["extra"]["scene"]["rolling"]["n_steps"], 6);
  EXPECT_EQ(used["extra"]["scene"]["rolling"]["omega_B"], 12.0);
  EXPECT_TRUE(fs::exists(run_dir / "scenes/fe_rolling.yaml"));
  // Reused like every task; a change to its scene re-runs it alone.
  const Outcome second = run(dir, build);
  ASSERT_EQ(second.exit_code, 0) << second.log;
  EXPECT_TRUE(with(second, "ran").empty()) << second.log;
  test_support::write_text(dir.file("rolling.yaml"),
                           "{\"study\": \"rolling\", \"loading\": {\"delta_max\": 4e-5}}\n");
  const Outcome third = run(dir, build);
  ASSERT_EQ(third.exit_code, 0) << third.log;
  EXPECT_EQ(with(third, "ran"), std::set<std::string>{"fe/rolling"}) << third.log;
}

// rolling.presets: the rolling study's own settings for the preset that runs, set in its scene
// after the preset's `fe` map and after rolling.overrides (the paper's full rolling case needs
// its own mesh and steps per preset). The preset's map, the block's overrides and its presets
// all set rolling.n_steps here, so settings applied too early, not at all, or another preset's
// show in the written scene and in the steps the stand-in ran.
TEST(RunPipeline, TheRollingStudysOwnPresetSettingsComeAfterItsOverrides)
{
  test_support::ScratchDir dir("pipeline_rolling_presets");
  FakeBuild build(dir);
  test_support::write_text(dir.file("rolling.yaml"), "{\"study\": \"rolling\"}\n");
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  const std::string plain = "presets: {fast: {fe: null, mbd: null}, ";
  yaml.replace(yaml.find(plain), plain.size(),
               "presets: {fast: {fe: {rolling.n_steps: 6, mesh.contact_refinements: 2}, "
               "mbd: null}, ");
  yaml.replace(yaml.find("report: false"), 13,
               "rolling:\n  scene: " + dir.file("rolling.yaml") +
                 "\n  overrides: {rolling.n_steps: 12, rolling.omega_B: 12.0}\n"
                 "  presets:\n"
                 "    fast: {rolling.n_steps: 32, mesh.contact_refinements: 0}\n"
                 "    standard: {rolling.n_steps: 64, mesh.contact_refinements: 1}\n"
                 "    accurate: null\n"
                 "report: false");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const fs::path run_dir = dir.file("out/r");
  // accurate: null — its `fe` map sets nothing, so the block's overrides alone.
  for (const auto &[preset, n_steps, refinements] :
       std::vector<std::tuple<std::string, int, nlohmann::json>>{{"fast", 32, 0},
                                                                 {"standard", 64, 1},
                                                                 {"accurate", 12, nullptr}})
    {
      const Outcome o = run(dir, build, "--preset " + preset);
      ASSERT_EQ(o.exit_code, 0) << o.log;
      EXPECT_EQ(with(o, "ran").count("fe/rolling"), 1u)
        << "another preset, another scene: " << o.log;
      const auto scene = read_yaml_file((run_dir / "scenes/fe_rolling.yaml").string());
      EXPECT_EQ(scene["rolling"]["n_steps"], n_steps) << preset << ": " << scene.dump();
      EXPECT_EQ(scene["rolling"]["omega_B"], 12.0) << preset << ": the block's overrides stay";
      const nlohmann::json *cr = find_key_path(scene, "mesh.contact_refinements");
      EXPECT_EQ(cr ? *cr : nlohmann::json(), refinements) << preset << ": " << scene.dump();
      // The stand-in ran those steps: one row per step after t = 0.
      const CsvTable history = read_csv((run_dir / "fe/rolling/rolling_history.csv").string());
      EXPECT_EQ(history.rows.size(), std::size_t(n_steps + 1)) << preset;
      // The summary lists the block's settings under each preset (the report's table).
      const auto summary = read_json_file((run_dir / "pipeline_summary.json").string());
      for (const auto &p : summary["presets"])
        if (p["name"] == "standard")
          EXPECT_EQ(p["rolling"]["rolling.n_steps"], 64) << p.dump();
        else if (p["name"] == "accurate")
          EXPECT_EQ(p["rolling"], nlohmann::json::object()) << p.dump();
    }
}

// A failing rolling study (a first step, docs/fe.md) does not stop the rest: every other task
// runs, the summary records the failure with its message and where the partial output is, and
// run_pipeline exits 2 after the report; --only mbd then does not need it; once the scene is
// fixed the next run does only the rolling task.
TEST(RunPipeline, AFailingRollingStudyDoesNotStopTheRest)
{
  test_support::ScratchDir dir("pipeline_rolling_fail");
  FakeBuild build(dir);
  test_support::write_text(dir.file("rolling.yaml"),
                           "{\"study\": \"rolling\", \"fake_rolling_fail\": true}\n");
  std::string yaml = pipeline_yaml(dir.path(), "[0.002, 0.004]");
  yaml.replace(yaml.find("report: false"), 13,
               "rolling: {scene: " + dir.file("rolling.yaml") + "}\nreport: false");
  test_support::write_text(dir.file("p.yaml"), yaml);
  const Outcome failed = run(dir, build);
  EXPECT_EQ(failed.exit_code, 2) << failed.log;
  EXPECT_NE(failed.log.find("FE rolling study failed"), std::string::npos) << failed.log;
  EXPECT_NE(failed.log.find("did not converge after 10 cuts"), std::string::npos) << failed.log;
  const fs::path run_dir = dir.file("out/r");
  for (const char *done : {"fe/thickness/t_B=0.004", "fit/thickness/family", "mbd/paper",
                           "mbd/fitted_band/n_high"})
    EXPECT_TRUE(fs::exists(run_dir / done / ".task.json")) << done << " ran\n" << failed.log;
  EXPECT_FALSE(fs::exists(run_dir / "fe/rolling"));
  const auto summary = read_json_file((run_dir / "pipeline_summary.json").string());
  EXPECT_EQ(summary["rolling"]["status"], "failed");
  const std::string message = summary["rolling"]["message"];
  EXPECT_NE(message.find("did not converge"), std::string::npos) << message;
  EXPECT_EQ(summary["rolling"]["partial_dir"], (run_dir / "fe/rolling.partial").string());
  const auto partial = read_json_file((run_dir / "fe/rolling.partial/manifest.json").string());
  EXPECT_EQ(partial["status"], "incomplete");
  const auto manifest = read_json_file((run_dir / "manifest.json").string());
  EXPECT_EQ(manifest["status"], "failed");
  EXPECT_NE(manifest["message"].get<std::string>().find("rolling"), std::string::npos);

  const Outcome only = run(dir, build, "--only mbd");
  ASSERT_EQ(only.exit_code, 0) << only.log;
  EXPECT_EQ(read_json_file((run_dir / "pipeline_summary.json").string())["rolling"]["status"],
            "not_run");

  test_support::write_text(dir.file("rolling.yaml"), "{\"study\": \"rolling\"}\n");
  const Outcome fixed = run(dir, build);
  ASSERT_EQ(fixed.exit_code, 0) << fixed.log;
  EXPECT_EQ(with(fixed, "ran"), std::set<std::string>{"fe/rolling"}) << fixed.log;
  EXPECT_FALSE(fs::exists(run_dir / "fe/rolling.partial"));
  EXPECT_EQ(read_json_file((run_dir / "pipeline_summary.json").string())["rolling"]["status"],
            "complete");
}

namespace
{
  /// The report without its figures' and tables' insides: every <details>…</details> removed
  /// (what a reader sees before unfolding anything).
  std::string unfolded_only(std::string html)
  {
    for (auto open = html.find("<details"); open != std::string::npos; open = html.find("<details"))
    {
      const auto close = html.find("</details>", open);
      if (close == std::string::npos)
        break;
      html.erase(open, close + 10 - open);
    }
    return html;
  }

  std::size_t count_of(const std::string &text, const std::string &what)
  {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  }
} // namespace

// Issue 15 items 1-3, 5 (the report's part), 6, 8, 9 without the FE build: the stand-in FE stage
// writes fields (CLEARJOINT_FAKE_FIELDS=1: von Mises above the yield stress near the contact,
// contact fields in Abaqus's meaning), the real fit and MBD stages run on its laws, and the report
// must lead with the answer: summary (what ran, our t_B = 4 mm law beside the paper's, trends
// beside the paper's claims, MBD headline numbers, every warning), contents, one section per FE
// sweep with VTK pictures, the yield check against the yield stress the scene names, contact-field
// checks (fe_stage's old fields — shear and 'stick' without friction, slip off contact — are
// flagged), all models overlaid, the band split into regression and mesh with the dominant part
// named, per-run plots folded away and captioned by what they show; and in headless Chromium
// every image loads and nothing refers to the network.
TEST(RunPipeline, ReportLeadsWithTheAnswerFromStandInStages)
{
  test_support::ScratchDir dir("pipeline_report");
  FakeBuild build(dir, /*real_mbd=*/true);
  const std::string src = CLEARJOINT_SOURCE_DIR;
  const std::string mbd = src + "/mbd_stage/scenes/slider_crank_";
  test_support::write_text(
    dir.file("p.yaml"),
    "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " + dir.file("out") + "\npreset: fast\n"
    "presets:\n"
    "  fast: {fe: null, mbd: null, measured: {note: test, fe_dofs: null, fe_case_time: 1.0,\n"
    "         pipeline_time: 60.0, error_F_max: {thickness: {percent: 4.8, where: made up},\n"
    "         misalignment: {percent: null, where: not measured}}}}\n"
    "  standard: {fe: null, mbd: null}\n  accurate: {fe: null, mbd: null}\n"
    "fe_sweeps:\n"
    "  - name: thickness\n    scene: " + src + "/fe_stage/scenes/radial.yaml\n"
    "    parameter: {name: t_B, unit: m, key: geometry.t_B}\n    values: [0.002, 0.004, 0.006]\n"
    // frictionless, fields as fe_stage wrote them before issue 15, and its own yield stress
    // (above the stand-in's 600 MPa: no yield warning for this sweep)
    "  - name: misalignment\n    scene: " + src + "/fe_stage/scenes/misalignment.yaml\n"
    "    parameter: {name: theta, unit: deg, key: misalignment.theta_deg}\n"
    "    values: [1.0, 2.5, theta_max]\n"
    "    overrides: {contact.mu: 0.0, fake_old_contact_fields: true, material.yield_stress: 1.0e9}\n"
    "fit: {weighting: absolute, family_out_of_range: clamp}\n"
    "mbd_runs:\n"
    "  - {name: fe_law, scene: " + mbd + "fe_law.yaml, laws: [{key: clearance_joints.0.normal.law_file, sweep: thickness, value: 0.004}], band: true}\n"
    "  - {name: paper_law, scene: " + mbd + "fe_law_damped.yaml, laws: [{key: clearance_joints.0.normal.law_file, file: " + src + "/laws/paper_tB4.json}]}\n"
    "  - {name: johnson, scene: " + mbd + "johnson.yaml}\n"
    "  - {name: ideal, scene: " + mbd + "ideal.yaml}\n"
    "  - {name: tilted_1deg, scene: " + mbd + "tilted_1deg.yaml, overrides: {clearance_joints.0.normal.model: law_family}, laws: [{key: clearance_joints.0.normal.law_file, sweep: misalignment}]}\n"
    // issue 13 item 5: the rolling study's own section (the stand-in's outputs: a clean run)
    "rolling: {scene: " + src + "/fe_stage/scenes/rolling.yaml}\n"
    "report: true\n");
  const int rc = test_support::run_command("CLEARJOINT_FAKE_FIELDS=1 " + std::string(RUN_PIPELINE_EXE) +
                                             " " + dir.file("p.yaml") + " --build-dir " + build.root,
                                           dir.file("log.txt"));
  const std::string log = test_support::read_text(dir.file("log.txt"));
  ASSERT_EQ(rc, 0) << log;
  const fs::path run = dir.file("out/r");
  // The band variants draw no plots of their own (the report shows none of them); the runs
  // the report shows do.
  EXPECT_TRUE(fs::exists(run / "mbd/fe_law/plots/energy.png"));
  for (const char *variant : {"n_high", "K_low", "mesh_high"})
    {
      const fs::path band = run / "mbd/fe_law_band" / variant;
      EXPECT_TRUE(fs::exists(band / "timeseries.csv")) << band;
      EXPECT_FALSE(fs::exists(band / "plots")) << band;
      EXPECT_NE(test_support::read_text((band / "command.txt").string()).find("--no-plots"),
                std::string::npos)
        << band;
    }
  const std::string report = test_support::read_text((run / "report.html").string());
  const auto at = [&](const std::string &what) {
    const auto p = report.find(what);
    EXPECT_NE(p, std::string::npos) << "report.html lacks: " << what;
    return p;
  };

  // Item 1: summary, then contents, then one section per FE sweep, then the multibody part.
  const auto summary = at("id='summary'"), contents = at("<nav>"), thickness = at("id='sweep-thickness'"),
             misalignment = at("id='sweep-misalignment'"), rolling = at("id='rolling'"),
             multibody = at("id='mbd'");
  EXPECT_LT(summary, contents);
  EXPECT_LT(contents, thickness);
  EXPECT_LT(thickness, misalignment);
  EXPECT_LT(misalignment, rolling);
  EXPECT_LT(rolling, multibody);
  EXPECT_NE(report.substr(contents, thickness - contents).find("href='#rolling'"), std::string::npos)
    << "the contents list the rolling study";
  const std::string head = report.substr(summary, contents - summary);
  for (const char *part :
       {"Preset <strong>fast</strong>", "μ = 0.1", "frictionless", "4.8 %",  // what ran
        "paper, t_B = 4 mm", "338240", "16344", "this run, t_B = 4 mm",      // law beside the paper's
        "+0.0 % against the paper",  // the stand-in's t_B = 4 mm law is the paper's
        "<strong>the mesh (discretisation) error dominates</strong>",  // item 6: which part dominates
        "grows monotonically over t_B", "as the paper says",   // trends beside the claims
        "mbd-run-fe_law", "mbd-run-johnson", "mbd-run-ideal",  // MBD headline numbers
        "Rolling (<a href='#rolling'>FE rolling study</a>)",    // the rolling study's sentence
        "id='warnings'"})
    EXPECT_NE(head.find(part), std::string::npos) << "summary lacks: " << part;
  // Every warning of the run is in the summary: the thickness cases' stress above the default
  // yield stress, none for the misalignment cases (their scene names 1 GPa), and the old
  // contact fields of the frictionless misalignment run.
  EXPECT_NE(head.find("<strong>FE thickness</strong>: stress above the yield stress 168.2 MPa in 3 of "
                      "3 cases"),
            std::string::npos)
    << head;
  EXPECT_EQ(head.find("<strong>FE misalignment</strong>: stress above"), std::string::npos) << head;
  for (const char *part : {"in a frictionless run", "contact_status = stick at",
                           "contact_slip is non-zero at"})
    EXPECT_NE(head.find(part), std::string::npos) << "summary lacks the field warning: " << part;
  EXPECT_EQ(count_of(head, "<strong>FE fields, t_B"), 0u) << "the thickness fields are consistent";
  EXPECT_EQ(count_of(head, "<strong>FE rolling study</strong>"), 0u) << "the rolling run is clean";
  at("Contact fields: consistent (friction within Coulomb's cone");
  at("against the yield stress 1000 MPa (the scene's material.yield_stress)");

  // Items 2 and 3: the paper's law over our curves, F_ref (not K) over the parameter, the
  // paper's claims beside ours, the fields rendered with VTK for each sweep.
  at("with the paper's t_B = 4 mm law (dashed)");
  at("K is not plotted");
  at("The paper's claims beside ours");
  EXPECT_EQ(count_of(report, "rendered off-screen with VTK"), 4u);  // caption and alt text, twice
  EXPECT_TRUE(fs::exists(run / "pictures" / "thickness_fields.png"));
  EXPECT_TRUE(fs::exists(run / "pictures" / "misalignment_fields.png"));
  // Issue 31 item 5: the paper's Fig. 7 — the radial normal stress beside von Mises in the side
  // cut — for θ = 1° and 2.5° (the stand-in's fields carry the stress tensor).
  EXPECT_TRUE(fs::exists(run / "pictures" / "misalignment_fig7a.png"));
  EXPECT_TRUE(fs::exists(run / "pictures" / "misalignment_fig7b.png"));
  at("The paper's Fig. 7a, θ = 1 °: the radial normal stress σ_rr = n·σ·n");
  at("The paper's Fig. 7b, θ = 2.5 °: the radial normal stress");
  EXPECT_EQ(count_of(head, "Fig. 7"), 0u) << "both rendered: no warning";
  at("Every contact model overlaid");
  at("a zoom on the first 10 ms (the paper's Fig. 17b)");
  at("id='band'");

  // Per-run plots folded away and captioned by what they show, not by their file name. Unfolded:
  // per sweep F–δ, F_ref and n, the fields picture; for the multibody runs the two overlays and
  // the band.
  // ... and the rolling study's three: spin rates (Fig. 10), energy split, strain profile (Fig. 12)
  // ... and the misalignment sweep's Fig. 7a and 7b
  EXPECT_EQ(count_of(unfolded_only(report), "<img"), 3u * 2u + 2u + 1u + 3u + 2u);
  at("the counterpart of the paper's Fig. 10");
  at("the counterpart of the paper's Fig. 12");
  EXPECT_GE(count_of(report, "<details>"), 3u + 3u + 5u);
  at("fe_law: phase portrait: slider velocity over slider position");
  EXPECT_EQ(report.find("phase_portrait.png</figcaption>"), std::string::npos);

  // Item 8: no temporary folder named anywhere in the report.
  EXPECT_EQ(report.find(".partial"), std::string::npos);

  // Item 9: in headless Chromium every image loads and nothing refers to the network.
  EXPECT_EQ(test_support::run_command("/usr/bin/python3 " + src +
                                        "/tests/unit/report/check_report_html.py " +
                                        (run / "report.html").string(),
                                      dir.file("browser.txt")),
            0)
    << test_support::read_text(dir.file("browser.txt"));
}
