// Scene reading (clearjoint.fe/1): defaults, strictness, and the bad-input errors of issue 3
// item 10 — each names the field and its valid range; fe_stage exits 1 and writes nothing.
#include "common/error.h"
#include "common/strict_reader.h"
#include "fe_stage/presets.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/hht.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <tuple>

using namespace clearjoint;
using namespace clearjoint::fe;

namespace
{
  FeScene parse(const std::string &yaml)
  {
    return scene_from_json(parse_yaml_string(yaml, "test.yaml"), "test.yaml");
  }

  /// Expects an InputError whose message contains every one of `parts`.
  void expect_error(const std::string &yaml, const std::vector<std::string> &parts)
  {
    try
      {
        parse(yaml);
        FAIL() << "no error for:\n" << yaml;
      }
    catch (const InputError &e)
      {
        const std::string msg = e.what();
        for (const auto &p : parts)
          EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' missing in: " << msg;
      }
  }
} // namespace

TEST(FeScene, DefaultsAreTheSpecValues)
{
  const FeScene s = parse("schema: clearjoint.fe/1\n");
  EXPECT_DOUBLE_EQ(s.geometry.R_B, 10e-3);
  EXPECT_DOUBLE_EQ(s.geometry.t_B, 4e-3);
  EXPECT_DOUBLE_EQ(s.geometry.L_B, 20e-3);
  EXPECT_DOUBLE_EQ(s.geometry.R_J(), 9.5e-3);
  EXPECT_DOUBLE_EQ(s.geometry.L_J(), 18e-3);
  EXPECT_DOUBLE_EQ(s.material.E, 207e9);
  EXPECT_DOUBLE_EQ(s.material.nu, 0.3);
  EXPECT_DOUBLE_EQ(s.contact.mu, 0.1);
  EXPECT_DOUBLE_EQ(s.loading.delta_max, 0.05e-3);
  EXPECT_GE(s.loading.n_increments, 10u);
  EXPECT_FALSE(s.full_model);
  EXPECT_EQ(s.loading.journal, JournalLoading::end_faces);
}

TEST(FeScene, PrintedDefaultsParseBackToTheDefaults)
{
  const FeScene s = parse(default_scene_yaml());
  const FeScene d;
  EXPECT_EQ(scene_to_json(s).dump(), scene_to_json(d).dump());
}

TEST(FeScene, SweepIsRead)
{
  const FeScene s = parse("schema: clearjoint.fe/1\nsweep: {t_B: [2.0e-3, 4.0e-3, 6.0e-3]}\n");
  ASSERT_EQ(s.sweep_t_B.size(), 3u);
  EXPECT_DOUBLE_EQ(s.sweep_t_B[2], 6e-3);
}

TEST(FeScene, BadInputNamesFieldAndRange)
{
  expect_error("schema: clearjoint.fe/1\ngeometry: {c_r: 0}\n", {"geometry.c_r", "(0, inf) m"});
  expect_error("schema: clearjoint.fe/1\ngeometry: {c_r: -1e-3}\n", {"geometry.c_r"});
  expect_error("schema: clearjoint.fe/1\ngeometry: {t_B: 0}\n", {"geometry.t_B", "(0, inf) m"});
  expect_error("schema: clearjoint.fe/1\ngeometry: {c_a: 0}\n", {"geometry.c_a"});
  // L_J = L_B − 2 c_a ≤ 0: the journal would be at least as long as... nothing left
  expect_error("schema: clearjoint.fe/1\ngeometry: {c_a: 0.011}\n", {"geometry.c_a", "L_B/2"});
  // journal larger than the bearing: c_r ≥ R_B leaves no journal radius
  expect_error("schema: clearjoint.fe/1\ngeometry: {c_r: 0.011}\n", {"geometry.c_r", "R_B"});
  expect_error("schema: clearjoint.fe/1\nloading: {delta_max: 0}\n",
               {"loading.delta_max", "(0, inf) m"});
  expect_error("schema: clearjoint.fe/1\nloading: {delta_max: -1e-5}\n", {"loading.delta_max"});
  expect_error("schema: clearjoint.fe/1\ngeometry: {R_b: 0.01}\n", {"geometry.R_b"});
  expect_error("schema: clearjoint.fe/1\nbogus: 1\n", {"bogus"});
  expect_error("schema: clearjoint.fe/2\n", {"schema"});
  expect_error("geometry: {t_B: 4e-3}\n", {"schema"});
  expect_error("schema: clearjoint.fe/1\nmaterial: {nu: 0.5}\n", {"material.nu"});
  expect_error("schema: clearjoint.fe/1\nmesh: {n_circumferential: 10}\n",
               {"mesh.n_circumferential", "multiple of 4"});
}

TEST(FeScene, JournalLoadingOptions)
{
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nloading: {journal: axis_line}\n").loading.journal,
            JournalLoading::axis_line);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nloading: {journal: rigid}\n").loading.journal,
            JournalLoading::rigid);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nloading: {journal: core}\n").loading.journal,
            JournalLoading::core);
  expect_error("schema: clearjoint.fe/1\nloading: {journal: spring}\n",
               {"loading.journal", "end_faces", "core"});
  // the tilted journal is rigid or core-loaded: end_faces/axis_line drive the contact rim
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nstudy: misalignment\nloading: {journal: core}\n")
              .loading.journal,
            JournalLoading::core);
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\nloading: {journal: end_faces}\n",
               {"loading.journal", "rigid or core for study misalignment"});
}

// contact.mortar_slave: which joint surface carries the mortar constraints. The journal's
// surface only when no surface node of it is driven (core loading), and the bore cannot be the
// slave under the tilted journal's rim (its faces there are only partly covered).
TEST(FeScene, MortarSlave)
{
  const FeScene s = parse("schema: clearjoint.fe/1\ncontact: {mortar_slave: journal}\n"
                          "loading: {journal: core}\n");
  EXPECT_EQ(s.contact.mortar_slave, Contact::MortarSlave::journal);
  expect_error("schema: clearjoint.fe/1\ncontact: {mortar_slave: journal}\n",
               {"contact.mortar_slave", "journal", "loading.journal core"});
  expect_error("schema: clearjoint.fe/1\ncontact: {mortar_slave: bore}\n"
               "loading: {journal: rigid}\n",
               {"contact.mortar_slave", "bore", "deformable journal"});
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\ncontact: {mortar_slave: bore}\n"
               "loading: {journal: core}\n",
               {"contact.mortar_slave", "journal or automatic for study misalignment"});
  expect_error("schema: clearjoint.fe/1\ncontact: {mortar_slave: left}\n",
               {"contact.mortar_slave", "automatic", "bore", "journal"});
}

// contact.sliding and the axially moved core journal: finite sliding redoes the mortar search,
// so it needs two deformable bodies coupled by mortar; the journal may move axially only with
// core loading and must stay within the bore (|offset|, |offset + slide| ≤ c_a = 1 mm).
TEST(FeScene, SlidingAndAxialMotion)
{
  const FeScene s = parse("schema: clearjoint.fe/1\ncontact: {sliding: finite}\n"
                          "loading: {journal: core, axial_slide: 0.5e-3}\n");
  EXPECT_EQ(s.contact.sliding, Contact::Sliding::finite);
  EXPECT_DOUBLE_EQ(s.loading.axial_slide, 0.5e-3);
  expect_error("schema: clearjoint.fe/1\ncontact: {sliding: finite}\nloading: {journal: rigid}\n",
               {"contact.sliding", "finite", "small unless two deformable bodies"});
  expect_error("schema: clearjoint.fe/1\ncontact: {sliding: large}\n",
               {"contact.sliding", "small", "finite"});
  expect_error("schema: clearjoint.fe/1\nloading: {journal: end_faces, axial_offset: 1e-4}\n",
               {"loading.axial_offset", "study radial with loading.journal core"});
  expect_error("schema: clearjoint.fe/1\nloading: {journal: core, axial_offset: 1.5e-3}\n",
               {"loading.axial_offset", "[-c_a, c_a]"});
  expect_error("schema: clearjoint.fe/1\nloading: {journal: core, axial_offset: 0.6e-3, "
               "axial_slide: 0.6e-3}\n",
               {"loading.axial_slide", "within [-c_a, c_a]"});
  expect_error("schema: clearjoint.fe/1\ncontact: {mortar_slave: bore}\n"
               "loading: {journal: core, axial_slide: 0.5e-3}\n",
               {"loading.axial_slide", "mortar_slave bore"});
}

// contact.pairing couples two deformable bodies: node_to_node (the generated joint's common
// rays) or dual mortar; it means nothing against a rigid journal, and the verification
// blocks' independently meshed indenter has no facing nodes.
TEST(FeScene, ContactPairing)
{
  EXPECT_EQ(parse("schema: clearjoint.fe/1\n").contact.pairing, Contact::Pairing::automatic);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\ncontact: {pairing: mortar}\n").contact.pairing,
            Contact::Pairing::mortar);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\ncontact: {pairing: node_to_node}\n").contact.pairing,
            Contact::Pairing::node_to_node);
  expect_error("schema: clearjoint.fe/1\ncontact: {pairing: nts}\n",
               {"contact.pairing", "mortar"});
  expect_error("schema: clearjoint.fe/1\ncontact: {pairing: mortar}\nloading: {journal: rigid}\n",
               {"contact.pairing", "rigid", "loading.journal"});
  // adaptive refinement breaks the common rays; friction runs on adaptive meshes
  expect_error("schema: clearjoint.fe/1\ncontact: {mu: 0, pairing: node_to_node}\n"
               "mesh: {adaptive_cycles: 2}\n",
               {"contact.pairing", "adaptive_cycles"});
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nmesh: {adaptive_cycles: 2}\n").contact.mu, 0.1);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nmesh: {adaptive_increments: 5}\n")
              .mesh.adaptive_increments,
            5u);
  expect_error("schema: clearjoint.fe/1\nmesh: {adaptive_increments: 0}\n",
               {"mesh.adaptive_increments", "1000"});
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nmesh: {adaptive_cycles: 4, adaptive_target_error: 0.01}\n")
              .mesh.adaptive_target_error,
            0.01);
  expect_error("schema: clearjoint.fe/1\nmesh: {adaptive_cycles: 4, adaptive_target_error: -0.1}\n",
               {"mesh.adaptive_target_error", "0.5"});
  // the estimate extrapolates through three meshes: a target needs two cycles or more
  expect_error("schema: clearjoint.fe/1\nmesh: {adaptive_target_error: 0.01}\n",
               {"mesh.adaptive_cycles", "adaptive_target_error"});
  EXPECT_EQ(parse("schema: clearjoint.fe/1\ncontact: {mu: 0}\nmesh: {adaptive_cycles: 2}\n")
              .mesh.adaptive_cycles,
            2u);
  expect_error("schema: clearjoint.fe/1\nstudy: patch\ncontact: {pairing: node_to_node}\n"
               "verification: {indenter: deformable}\n",
               {"contact.pairing", "node_to_node", "mortar"});
}

TEST(FeStageCli, BadInputExitsOneAndWritesNothing)
{
  const auto dir = std::filesystem::temp_directory_path() / "clearjoint_fe_cli_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto scene = dir / "bad.yaml";
  std::ofstream(scene) << "schema: clearjoint.fe/1\ngeometry: {t_B: -0.004}\n";
  const auto out = dir / "out";
  const std::string cmd = std::string(FE_STAGE_EXE) + " " + scene.string() + " --output " +
                          out.string() + " > " + (dir / "log.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_FALSE(std::filesystem::exists(out)) << "no outputs on bad input";
  std::ifstream log(dir / "log.txt");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("geometry.t_B"), std::string::npos) << text;

  // the same for the impact's new keys (issue 31 item 6): an unknown application, α out of
  // Abaqus's range, α with backward Euler
  for (const std::string &impact : {"{application: moderate}", "{alpha: -0.6}",
                                    "{application: quasi_static, alpha: -0.05}"})
    {
      std::ofstream(scene) << "schema: clearjoint.fe/1\nstudy: impact\nimpact: " << impact << "\n";
      const int st = std::system(cmd.c_str());
      ASSERT_TRUE(WIFEXITED(st));
      EXPECT_EQ(WEXITSTATUS(st), 1) << impact;
      EXPECT_FALSE(std::filesystem::exists(out)) << impact;
      std::ifstream l(dir / "log.txt");
      const std::string t((std::istreambuf_iterator<char>(l)), {});
      EXPECT_NE(t.find("impact."), std::string::npos) << t;
    }
  // and for the journal mass (issue 31 item 3): the key, the value and the range named, nothing
  // written
  for (const auto &[keys, named] : std::vector<std::pair<std::string, std::string>>{
         {"impact: {journal_mass: -1}", "impact.journal_mass"},
         {"sweep: {journal_mass: [0.04, -2]}", "sweep.journal_mass.1"},
         {"loading: {journal: end_faces}\nsweep: {journal_mass: [1.0]}", "sweep.journal_mass"}})
    {
      std::ofstream(scene) << "schema: clearjoint.fe/1\nstudy: impact\n" << keys << "\n";
      const int st = std::system(cmd.c_str());
      ASSERT_TRUE(WIFEXITED(st));
      EXPECT_EQ(WEXITSTATUS(st), 1) << keys;
      EXPECT_FALSE(std::filesystem::exists(out)) << keys;
      std::ifstream l(dir / "log.txt");
      const std::string t((std::istreambuf_iterator<char>(l)), {});
      EXPECT_NE(t.find(named), std::string::npos) << t;
    }

  // --print-defaults exits 0 and prints the schema line
  const std::string cmd2 = std::string(FE_STAGE_EXE) + " --print-defaults > " +
                           (dir / "defaults.yaml").string() + " 2>&1";
  const int status2 = std::system(cmd2.c_str());
  ASSERT_TRUE(WIFEXITED(status2));
  EXPECT_EQ(WEXITSTATUS(status2), 0);
  std::ifstream d(dir / "defaults.yaml");
  const std::string defaults((std::istreambuf_iterator<char>(d)), {});
  EXPECT_NE(defaults.find("schema: clearjoint.fe/1"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// The restart flags (fe_stage --write-restart / --restart-every / --resume): the rolling study
// only, a folder apart from --output (a run replaces that as a whole), at least every step, a
// folder that holds a state. Each an input error naming the flag, exit 1, nothing written.
TEST(FeStageCli, BadRestartFlagsExitOneAndWriteNothing)
{
  const auto dir = std::filesystem::temp_directory_path() / "clearjoint_fe_restart_cli_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto radial = dir / "radial.yaml", rolling = dir / "rolling.yaml";
  std::ofstream(radial) << "schema: clearjoint.fe/1\n";
  std::ofstream(rolling) << "schema: clearjoint.fe/1\nstudy: rolling\n";
  const auto out = dir / "out";
  for (const auto &[scene, flags, named] :
       std::vector<std::tuple<std::filesystem::path, std::string, std::string>>{
         {radial, "--write-restart " + (dir / "r").string(), "--write-restart"},
         {rolling, "--write-restart " + (out / "r").string(), "--write-restart"},
         {rolling, "--resume " + out.string(), "--resume"},
         {rolling, "--write-restart " + (dir / "r").string() + " --restart-every 0",
          "--restart-every"},
         {rolling, "--resume " + (dir / "none").string(), "--resume"}})
    {
      const std::string cmd = std::string(FE_STAGE_EXE) + " " + scene.string() + " --output " +
                              out.string() + " " + flags + " > " + (dir / "log.txt").string() +
                              " 2>&1";
      const int st = std::system(cmd.c_str());
      ASSERT_TRUE(WIFEXITED(st));
      EXPECT_EQ(WEXITSTATUS(st), 1) << flags;
      EXPECT_FALSE(std::filesystem::exists(out)) << flags;
      EXPECT_FALSE(std::filesystem::exists(dir / "r")) << flags;
      std::ifstream l(dir / "log.txt");
      const std::string t((std::istreambuf_iterator<char>(l)), {});
      EXPECT_NE(t.find(named), std::string::npos) << flags << ": " << t;
    }
  std::filesystem::remove_all(dir);
}

// Misalignment study (issue 4 item 1): the journal is rigid by default, θ ≤ θ_max of paper Eq. 3
// (3.284226° for the defaults, docs/geometry.md), the word theta_max resolves to it, and a
// larger θ is rejected with the computed limit in the message.
TEST(FeScene, MisalignmentStudy)
{
  const FeScene s =
    parse("schema: clearjoint.fe/1\nstudy: misalignment\nmisalignment: {theta_deg: 2.5}\n");
  EXPECT_EQ(s.study, Study::misalignment);
  EXPECT_EQ(s.loading.journal, JournalLoading::rigid);
  EXPECT_DOUBLE_EQ(s.misalignment.theta_deg, 2.5);

  const FeScene m = parse(
    "schema: clearjoint.fe/1\nstudy: misalignment\nmisalignment: {theta_deg: theta_max}\n");
  EXPECT_NEAR(m.misalignment.theta_deg, 3.284226, 5e-7);  // docs/geometry.md, 7 digits

  const FeScene w = parse("schema: clearjoint.fe/1\nstudy: misalignment\n"
                          "sweep: {theta_deg: [1.0, 1.5, 2.0, 2.5, theta_max]}\n");
  ASSERT_EQ(w.sweep_theta_deg.size(), 5u);
  EXPECT_DOUBLE_EQ(w.sweep_theta_deg[1], 1.5);
  EXPECT_DOUBLE_EQ(w.sweep_theta_deg[4], m.misalignment.theta_deg);

  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\nmisalignment: {theta_deg: 3.3}\n",
               {"misalignment.theta_deg", "3.28423"});
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\nsweep: {theta_deg: [1.0, 4.0]}\n",
               {"sweep.theta_deg.1", "3.28423"});
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\nloading: {journal: end_faces}\n",
               {"loading.journal", "rigid"});
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\nmisalignment: {theta_deg: big}\n",
               {"misalignment.theta_deg", "theta_max"});
  // a different joint has its own θ_max (docs/geometry.md: 0.397515° for this one)
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\n"
               "geometry: {R_B: 0.025, c_r: 0.0001, L_B: 0.030, c_a: 0.0005}\n"
               "misalignment: {theta_deg: 0.5}\n",
               {"misalignment.theta_deg", "0.397515"});
  // a journal that can turn over has no θ_max
  expect_error("schema: clearjoint.fe/1\nstudy: misalignment\n"
               "geometry: {R_B: 0.010, c_r: 0.002, L_B: 0.006, c_a: 0.001}\n"
               "misalignment: {theta_deg: theta_max}\n",
               {"misalignment.theta_deg", "no root"});
  // θ sweep only for the misalignment study; one swept parameter per scene
  expect_error("schema: clearjoint.fe/1\nsweep: {theta_deg: [1.0]}\n", {"sweep.theta_deg"});
}

// fe_stage --preset (issue 15 item 7): the FE keys of pipeline.yaml's presets, read from the
// file run_pipeline reads, set on the scene before it is validated; a name the file does not
// have is an input error that lists the presets.
TEST(FePreset, ThePipelinePresetsSetTheSceneMesh)
{
  const std::string file = std::string(CLEARJOINT_SOURCE_DIR) + "/pipeline.yaml";
  const PresetOverrides fast = read_fe_preset(file, "fast");
  ASSERT_FALSE(fast.empty());
  nlohmann::json doc = parse_yaml_string("schema: clearjoint.fe/1\nmesh: {global_refinements: 3}\n",
                                         "test.yaml");
  apply_preset(doc, fast, file);
  const FeScene s = scene_from_json(doc, "test.yaml");
  const nlohmann::json pipeline = read_structured_file(file);
  const nlohmann::json &expected = pipeline["presets"]["fast"]["fe"];
  EXPECT_EQ(s.mesh.global_refinements, expected["mesh.global_refinements"].get<unsigned int>());
  EXPECT_EQ(s.mesh.n_circumferential, expected["mesh.n_circumferential"].get<unsigned int>());
  EXPECT_EQ(s.mesh.contact_refinements, expected["mesh.contact_refinements"].get<unsigned int>());
  // the three presets are nested mesh levels: standard one global refinement above fast
  const FeScene standard = [&] {
    nlohmann::json d = parse_yaml_string("schema: clearjoint.fe/1\n", "test.yaml");
    apply_preset(d, read_fe_preset(file, "standard"), file);
    return scene_from_json(d, "test.yaml");
  }();
  EXPECT_EQ(standard.mesh.global_refinements, s.mesh.global_refinements + 1);

  try
    {
      read_fe_preset(file, "fastest");
      FAIL() << "no error for an unknown preset";
    }
  catch (const InputError &e)
    {
      const std::string msg = e.what();
      for (const std::string part : {"--preset", "fastest", "fast", "standard", "accurate"})
        EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' missing in: " << msg;
    }
}

// The rolling study's scene with --preset gets what run_pipeline's rolling task runs: the
// preset's keys, then pipeline.yaml's rolling.overrides (the ring's base mesh whatever the
// preset), then its rolling.presets.<preset> (the contact's mesh and the time steps).
TEST(FePreset, TheRollingSceneGetsThePipelinesRollingSettings)
{
  const std::string file = std::string(CLEARJOINT_SOURCE_DIR) + "/pipeline.yaml";
  const nlohmann::json pipeline = read_structured_file(file);
  const nlohmann::json &rolling = pipeline["rolling"]["overrides"];
  ASSERT_TRUE(rolling.is_object() && !rolling.empty());
  for (const std::string preset : {"fast", "standard", "accurate"})
    {
      const nlohmann::json &own = pipeline["rolling"]["presets"][preset];
      ASSERT_TRUE(own.is_object() && own.contains("rolling.n_steps") &&
                  own.contains("mesh.contact_refinements"))
        << preset;
      const FeScene s = [&] {
        nlohmann::json d =
          parse_yaml_string("schema: clearjoint.fe/1\nstudy: rolling\n", "test.yaml");
        apply_preset(d, read_fe_preset(file, preset), file);  // as fe_stage main does
        apply_preset(d, read_rolling_overrides(file), file);
        apply_preset(d, read_rolling_preset(file, preset), file);
        return scene_from_json(d, "test.yaml");
      }();
      EXPECT_EQ(s.mesh.global_refinements, rolling["mesh.global_refinements"].get<unsigned int>())
        << preset;
      // the preset's own settings win over its fe map (which sets contact_refinements too)
      EXPECT_EQ(s.mesh.contact_refinements, own["mesh.contact_refinements"].get<unsigned int>())
        << preset;
      EXPECT_EQ(s.rolling.n_steps, own["rolling.n_steps"].get<unsigned int>()) << preset;
      EXPECT_EQ(read_rolling_preset(file, preset).size(), own.size()) << preset;
    }
  EXPECT_EQ(read_rolling_overrides(file).size(), rolling.size());
}

// A rolling.presets entry that is missing or not a mapping is an input error naming it; a
// null entry or no rolling.presets at all sets nothing.
TEST(FePreset, ARollingPresetsEntryIsAMappingOrNull)
{
  const test_support::ScratchDir dir("fe_rolling_presets");
  const auto with = [&](const std::string &rolling_block) {
    const std::string file = dir.file("p.yaml");
    test_support::write_text(file, "presets: {fast: {fe: null}}\nrolling:\n" + rolling_block);
    return file;
  };
  EXPECT_TRUE(read_rolling_preset(with("  scene: r.yaml\n"), "fast").empty());
  EXPECT_TRUE(read_rolling_preset(with("  presets: {fast: null}\n"), "fast").empty());
  EXPECT_EQ(read_rolling_preset(with("  presets: {fast: {rolling.n_steps: 8}}\n"), "fast").size(),
            1u);
  for (const std::string bad : {"  presets: {standard: null}\n", "  presets: {fast: 3}\n"})
    try
      {
        read_rolling_preset(with(bad), "fast");
        ADD_FAILURE() << "no error for " << bad;
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find("rolling.presets.fast"), std::string::npos)
          << e.what();
      }
}

TEST(FeScene, YieldStressDefaultsToTheHardeningTablesFirstPoint)
{
  EXPECT_DOUBLE_EQ(parse("schema: clearjoint.fe/1\n").material.yield_stress, 168.2e6);
  EXPECT_DOUBLE_EQ(parse("schema: clearjoint.fe/1\nmaterial: {yield_stress: 3.0e8}\n")
                     .material.yield_stress, 3.0e8);
  expect_error("schema: clearjoint.fe/1\nmaterial: {yield_stress: -1}\n",
               {"material.yield_stress", "-1"});
}

// Study impact (issue 12 item 6, issue 31 items 1 and 6): v ≤ 0, α outside Abaqus's [−1/2, 0], an
// unknown application, α with quasi_static (backward Euler has no α), a time step or end time
// ≤ 0 are input errors naming the key and its range; the sweep over velocities and journal
// masses is read.
TEST(FeScene, ImpactStudy)
{
  const std::string head = "schema: clearjoint.fe/1\nstudy: impact\n";
  const FeScene s = parse(head + "impact: {velocity: 0.15, alpha: -0.1, time_step: 1.0e-6, "
                                 "end_time: 2.0e-4, mass: consistent}\n"
                                 "sweep: {velocity: [0.05, 0.2]}\n");
  EXPECT_EQ(s.study, Study::impact);
  EXPECT_EQ(s.loading.journal, JournalLoading::rigid);
  EXPECT_DOUBLE_EQ(s.impact.velocity, 0.15);
  ASSERT_TRUE(s.impact.alpha.has_value());
  EXPECT_DOUBLE_EQ(*s.impact.alpha, -0.1);
  EXPECT_EQ(s.impact.application, DynamicApplication::moderate_dissipation);
  EXPECT_DOUBLE_EQ(s.impact.time_step, 1.0e-6);
  EXPECT_DOUBLE_EQ(s.impact.end_time, 2.0e-4);
  EXPECT_EQ(s.impact.mass, Impact::Mass::consistent);
  EXPECT_EQ(s.sweep_velocity, (std::vector<double>{0.05, 0.2}));
  const FeScene d = parse(head);
  // the paper's and Abaqus's default for models with contact; α from it
  EXPECT_EQ(d.impact.application, DynamicApplication::moderate_dissipation);
  EXPECT_FALSE(d.impact.alpha.has_value());
  for (const auto &[word, app] :
       {std::pair{"transient_fidelity", DynamicApplication::transient_fidelity},
        std::pair{"moderate_dissipation", DynamicApplication::moderate_dissipation},
        std::pair{"quasi_static", DynamicApplication::quasi_static}})
    {
      const FeScene a = parse(head + "impact: {application: " + word + "}\n");
      EXPECT_EQ(a.impact.application, app) << word;
      EXPECT_STREQ(application_name(a.impact.application), word);
    }
  // Abaqus's range [−1/2, 0]: its ends are accepted, with an HHT application
  EXPECT_DOUBLE_EQ(*parse(head + "impact: {alpha: -0.5}\n").impact.alpha, -0.5);
  EXPECT_DOUBLE_EQ(
    *parse(head + "impact: {application: transient_fidelity, alpha: 0}\n").impact.alpha, 0.0);
  EXPECT_EQ(d.impact.mass, Impact::Mass::redistributed);
  expect_error(head + "impact: {velocity: 0}\n", {"impact.velocity", "(0, 100) m/s"});
  expect_error(head + "impact: {velocity: -0.1}\n", {"impact.velocity", "-0.1"});
  expect_error(head + "impact: {alpha: -0.51}\n", {"impact.alpha", "-0.51", "[-0.5, 0]"});
  expect_error(head + "impact: {alpha: 0.1}\n", {"impact.alpha", "0.1", "[-0.5, 0]"});
  expect_error(head + "impact: {application: hht_md}\n",
               {"impact.application", "hht_md", "transient_fidelity", "moderate_dissipation",
                "quasi_static"});
  expect_error(head + "impact: {application: 1}\n", {"impact.application"});
  expect_error(head + "impact: {application: quasi_static, alpha: -0.1}\n",
               {"impact.alpha", "-0.1", "quasi_static"});
  expect_error(head + "impact: {time_step: 0}\n", {"impact.time_step", "s"});
  expect_error(head + "impact: {time_step: -1.0e-6}\n", {"impact.time_step"});
  expect_error(head + "impact: {end_time: 0}\n", {"impact.end_time", "s"});
  expect_error(head + "impact: {steps_per_period: 5}\n", {"impact.steps_per_period", "10"});
  expect_error(head + "impact: {mass: heavy}\n", {"impact.mass", "redistributed"});
  EXPECT_DOUBLE_EQ(parse(head + "impact: {journal_mass: 2.5}\n").impact.journal_mass, 2.5);
  // adaptive meshes marked at the expected peak (issue 32): the cycles and a target error
  EXPECT_EQ(parse(head + "mesh: {adaptive_cycles: 3}\n").mesh.adaptive_cycles, 3u);
  EXPECT_DOUBLE_EQ(parse(head + "mesh: {adaptive_cycles: 3, adaptive_target_error: 0.02}\n")
                     .mesh.adaptive_target_error,
                   0.02);
  EXPECT_DOUBLE_EQ(rigid_journal_mass(parse(head + "impact: {journal_mass: 2.5}\n")), 2.5);
  EXPECT_NEAR(rigid_journal_mass(parse(head)), 7800.0 * M_PI * 9.5e-3 * 9.5e-3 * 18e-3, 1e-12);
  expect_error(head + "impact: {journal_mass: 0}\n", {"impact.journal_mass", "kg"});
  expect_error(head + "loading: {journal: end_faces}\nimpact: {journal_mass: 1}\n",
               {"impact.journal_mass", "rigid"});
  EXPECT_EQ(parse(head + "loading: {journal: end_faces}\n").loading.journal,
            JournalLoading::end_faces);  // a deformable journal
  expect_error(head + "sweep: {velocity: [0.1, 0]}\n", {"sweep.velocity"});
  // issue 31 item 3: the journal mass as a sweep key, alone or with the velocity (every pair);
  // `own` is the rigid journal's ρ π R_J² L_J
  const double own = 7800.0 * M_PI * 9.5e-3 * 9.5e-3 * 18e-3;
  const FeScene ms = parse(head + "sweep: {journal_mass: [own, 1.0, 25]}\n");
  ASSERT_EQ(ms.sweep_journal_mass.size(), 3u);
  EXPECT_NEAR(ms.sweep_journal_mass[0], own, 1e-12);
  EXPECT_DOUBLE_EQ(ms.sweep_journal_mass[2], 25.0);
  EXPECT_TRUE(ms.sweep_velocity.empty());
  EXPECT_TRUE(has_sweep(ms));
  EXPECT_FALSE(has_sweep(d));
  const FeScene both = parse(head + "sweep: {velocity: [0.1, 0.2], journal_mass: [1.0]}\n");
  EXPECT_EQ(both.sweep_velocity, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(both.sweep_journal_mass, (std::vector<double>{1.0}));
  // own follows the material's density
  EXPECT_NEAR(parse(head + "material: {rho: 3900}\nsweep: {journal_mass: [own]}\n")
                .sweep_journal_mass[0],
              0.5 * own, 1e-12);
  expect_error(head + "sweep: {journal_mass: [1.0, 0]}\n",
               {"sweep.journal_mass.1", "0", "(0, inf) kg", "own"});
  expect_error(head + "sweep: {journal_mass: [-1]}\n", {"sweep.journal_mass.0", "-1", "kg"});
  expect_error(head + "sweep: {journal_mass: [heavy]}\n", {"sweep.journal_mass.0", "heavy"});
  expect_error(head + "sweep: {journal_mass: []}\n", {"sweep.journal_mass"});
  expect_error(head + "sweep: {journal_mass: 2.0}\n", {"sweep.journal_mass"});
  expect_error(head + "loading: {journal: end_faces}\nsweep: {journal_mass: [1.0]}\n",
               {"sweep.journal_mass", "rigid", "rho"});
  expect_error(head + "impact: {journal_mass: 2}\nsweep: {journal_mass: [1.0]}\n",
               {"impact.journal_mass", "sweep.journal_mass"});
  expect_error("schema: clearjoint.fe/1\nsweep: {journal_mass: [1.0]}\n",
               {"sweep.journal_mass", "study impact"});
  expect_error(head + "sweep: {t_B: [0.004], journal_mass: [1.0]}\n",
               {"sweep.journal_mass", "one swept parameter"});
  expect_error("schema: clearjoint.fe/1\nsweep: {velocity: [0.1]}\n",
               {"sweep.velocity", "study impact"});
}

// Study rolling (issue 13 item 1 and the bad inputs of item 6): the paper's §3.4 defaults, the
// hardening table read and checked, and every key that cannot work named with its range.
TEST(FeScene, RollingStudy)
{
  const std::string head = "schema: clearjoint.fe/1\nstudy: rolling\n";
  const FeScene d = parse(head);
  EXPECT_EQ(d.study, Study::rolling);
  EXPECT_EQ(d.material.model, Material::Model::elastoplastic);
  EXPECT_DOUBLE_EQ(d.contact.mu, 0.3);
  EXPECT_DOUBLE_EQ(d.loading.delta_max, 1.0e-3);
  EXPECT_EQ(d.loading.max_cuts, 10u);
  EXPECT_EQ(d.loading.journal, JournalLoading::rigid);
  EXPECT_DOUBLE_EQ(d.rolling.omega_B, 12.56);
  EXPECT_DOUBLE_EQ(d.rolling.ramp_time, 0.25);
  EXPECT_DOUBLE_EQ(rolling_end_time(d), 0.25);  // no end_time: the end of the ramp
  // ½ m R_J² of the journal, ρ = 7800 kg/m³, R_J = 9.5 mm, L_J = 18 mm (SPEC §2)
  const double m = 7800.0 * M_PI * 9.5e-3 * 9.5e-3 * 18e-3;
  EXPECT_NEAR(rolling_journal_inertia(d), 0.5 * m * 9.5e-3 * 9.5e-3, 1e-15);
  // the default hardening table is SPEC §2's
  const auto table = hardening_table(d.material, "test.yaml");
  EXPECT_DOUBLE_EQ(table.points().front().sigma_y, 168.2e6);

  const FeScene s = parse(head + "rolling: {omega_B: 6.28, ramp_time: 0.5, end_time: 0.6, "
                                 "n_steps: 12, journal_inertia: 2.0e-6}\n"
                                 "material: {hardening: [[0, 200.0e6], [0.2, 260.0e6]]}\n");
  EXPECT_DOUBLE_EQ(s.rolling.omega_B, 6.28);
  EXPECT_DOUBLE_EQ(rolling_end_time(s), 0.6);
  EXPECT_EQ(s.rolling.n_steps, 12u);
  EXPECT_DOUBLE_EQ(rolling_journal_inertia(s), 2.0e-6);
  EXPECT_DOUBLE_EQ(hardening_table(s.material, "test.yaml").points().back().sigma_y, 260.0e6);

  expect_error(head + "rolling: {omega_B: 0}\n", {"rolling.omega_B", "rad/s"});
  expect_error(head + "rolling: {ramp_time: -1}\n", {"rolling.ramp_time", "s"});
  expect_error(head + "rolling: {ramp_time: 0.25, end_time: 0.1}\n",
               {"rolling.end_time", "ramp_time"});
  expect_error(head + "rolling: {n_steps: 2}\n", {"rolling.n_steps"});
  expect_error(head + "rolling: {journal_inertia: 0}\n", {"rolling.journal_inertia", "kg m^2"});
  expect_error(head + "rolling: {support: glued}\n", {"rolling.support", "outer_surface"});
  expect_error(head + "material: {model: elastic}\n", {"material.model", "elastoplastic"});
  expect_error(head + "loading: {journal: end_faces}\n", {"loading.journal", "rigid or core"});
  // the deformable journal (core clamped in its own frame): paired by mortar, the bore the
  // slave; the search is redone at every time step anyway
  EXPECT_EQ(parse(head + "loading: {journal: core}\n").loading.journal, JournalLoading::core);
  expect_error(head + "loading: {journal: core}\ncontact: {pairing: node_to_node}\n",
               {"contact.pairing", "mortar"});
  expect_error(head + "loading: {journal: core}\ncontact: {mortar_slave: journal}\n",
               {"contact.mortar_slave", "bore"});
  expect_error(head + "loading: {journal: core}\ncontact: {sliding: finite}\n",
               {"contact.sliding", "small"});
  expect_error(head + "mesh: {adaptive_cycles: 1}\n", {"mesh.adaptive_cycles"});
  expect_error(head + "full_model: true\n", {"full_model"});
  // the hardening table: strains strictly increasing from 0, stresses non-decreasing
  expect_error(head + "material: {hardening: [[0.1, 200.0e6], [0.2, 210.0e6]]}\n",
               {"material.hardening"});
  expect_error(head + "material: {hardening: [[0, 200.0e6], [0, 210.0e6]]}\n",
               {"material.hardening"});
  expect_error(head + "material: {hardening: [[0, 200.0e6], [0.1, 190.0e6]]}\n",
               {"material.hardening"});
  expect_error(head + "material: {hardening: [[0, 200.0e6, 1]]}\n",
               {"material.hardening[0]", "[eps_p, sigma_y]"});
  expect_error(head + "material: {hardening: []}\n", {"material.hardening"});
  // elastoplastic only where it is integrated
  expect_error("schema: clearjoint.fe/1\nmaterial: {model: elastoplastic}\n",
               {"material.model", "rolling"});
}

// Issue 30: material.kinematics (small | finite) and the elastoplastic patch test; finite only
// with the J2 law (the patch test and the rolling study); solver.max_newton_iterations in
// [1, 1000].
TEST(FeScene, KinematicsAndTheElastoplasticPatchTest)
{
  const std::string patch = "schema: clearjoint.fe/1\nstudy: patch\n";
  EXPECT_EQ(parse(patch).material.kinematics, Material::Kinematics::small);  // the default
  const FeScene s =
    parse(patch + "material: {model: elastoplastic, kinematics: finite}\n"
                  "solver: {max_newton_iterations: 40}\n");
  EXPECT_EQ(s.material.model, Material::Model::elastoplastic);
  EXPECT_EQ(s.material.kinematics, Material::Kinematics::finite);
  EXPECT_EQ(s.solver.max_newton_iterations, 40u);
  EXPECT_EQ(parse(patch + "material: {model: elastoplastic, kinematics: small}\n")
              .material.kinematics,
            Material::Kinematics::small);
  expect_error(patch + "material: {model: elastoplastic, kinematics: large}\n",
               {"material.kinematics", "small", "finite"});
  expect_error(patch + "material: {kinematics: finite}\n",
               {"material.kinematics", "elastoplastic"});
  expect_error("schema: clearjoint.fe/1\nmaterial: {model: elastoplastic, kinematics: finite}\n",
               {"material.model"});  // radial: not elastoplastic at all
  // the rolling study is elastoplastic by default, and finite is its default (the paper's push
  // strains the bore to ~1); small stays available there
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nstudy: rolling\n").material.kinematics,
            Material::Kinematics::finite);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nstudy: rolling\nmaterial: {kinematics: finite}\n")
              .material.kinematics,
            Material::Kinematics::finite);
  EXPECT_EQ(parse("schema: clearjoint.fe/1\nstudy: rolling\nmaterial: {kinematics: small}\n")
              .material.kinematics,
            Material::Kinematics::small);
  expect_error(patch + "material: {model: elastoplastic}\n"
                       "verification: {indenter: deformable}\n",
               {"verification.indenter", "rigid flat"});
  expect_error(patch + "material: {model: elastoplastic}\nmesh: {adaptive_cycles: 1}\n",
               {"mesh.adaptive_cycles", "history"});
  expect_error(patch + "solver: {max_newton_iterations: 0}\n",
               {"solver.max_newton_iterations"});
}

// Issue 30 item 7: a step may turn the bearing by a quarter turn at most. ω_B = 1e3 rad/s over
// the default 0.25 s is 250 rad: 32 steps (7.8 rad each) are refused with the least number of
// steps that would do, ceil(250 / (π/2)) = 160, which is accepted.
TEST(FeScene, RollingStepsMayTurnTheBearingAQuarterTurnAtMost)
{
  const std::string rolling = "schema: clearjoint.fe/1\nstudy: rolling\n";
  expect_error(rolling + "rolling: {omega_B: 1000, n_steps: 32}\n",
               {"rolling.n_steps", "32", ">= 160", "quarter turn"});
  EXPECT_EQ(parse(rolling + "rolling: {omega_B: 1000, n_steps: 160}\n").rolling.n_steps, 160u);
  // the hold after the ramp counts too: 1 s at 12.56 rad/s is 12.56 rad, 4 steps too few
  expect_error(rolling + "rolling: {n_steps: 4, end_time: 1.0}\n", {"rolling.n_steps", ">= 8"});
  EXPECT_EQ(parse(rolling + "rolling: {omega_B: 1.0e-3, n_steps: 4}\n").rolling.n_steps, 4u);
}

// Issue 30 item 2: rolling.spin_solver, how a rolling step finds the journal's spin
TEST(FeScene, RollingSpinSolverIsBorderedCoupledOrNested)
{
  const std::string rolling = "schema: clearjoint.fe/1\nstudy: rolling\n";
  EXPECT_EQ(parse(rolling).rolling.spin_solver, Rolling::SpinSolver::bordered);  // the default
  EXPECT_EQ(parse(rolling + "rolling: {spin_solver: nested}\n").rolling.spin_solver,
            Rolling::SpinSolver::nested);
  EXPECT_EQ(parse(rolling + "rolling: {spin_solver: coupled}\n").rolling.spin_solver,
            Rolling::SpinSolver::coupled);
  EXPECT_EQ(parse(rolling + "rolling: {spin_solver: bordered}\n").rolling.spin_solver,
            Rolling::SpinSolver::bordered);
  expect_error(rolling + "rolling: {spin_solver: newton}\n",
               {"rolling.spin_solver", "bordered", "coupled", "nested"});
}

TEST(FeScene, SolverLineSearchIsOnByDefaultAndABoolean)
{
  const std::string rolling = "schema: clearjoint.fe/1\nstudy: rolling\n";
  EXPECT_TRUE(parse(rolling).solver.line_search);
  EXPECT_FALSE(parse(rolling + "solver: {line_search: false}\n").solver.line_search);
  EXPECT_TRUE(parse(rolling + "solver: {line_search: true}\n").solver.line_search);
  expect_error(rolling + "solver: {line_search: sometimes}\n", {"solver.line_search"});
}
