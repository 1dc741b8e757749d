// Bad input (SPEC §6, issue 5 item 9): each case gives an InputError naming the field and its
// valid range; the executable exits 1 and writes nothing. Plus one short good run through the
// executable (outputs, units line, manifest status).
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include "common/error.h"
#include "common/strict_reader.h"
#include "laws/law_family.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

using namespace clearjoint;
using namespace clearjoint::mbd;
namespace fs = std::filesystem;

namespace
{
  const std::string scenes = std::string(CLEARJOINT_SOURCE_DIR) + "/mbd_stage/scenes";

  nlohmann::json base()
  {
    return read_yaml_file(scenes + "/slider_crank_fe_law_damped.yaml");
  }

  /// Expects scene_from_json to throw an InputError whose message contains every `needle`.
  void expect_error(const std::function<void(nlohmann::json &)> &mutate,
                    const std::vector<std::string> &needles)
  {
    nlohmann::json doc = base();
    mutate(doc);
    const std::string msg =
      test_support::input_error_of([&] { scene_from_json(doc, "bad.yaml", scenes); });
    for (const auto &n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }

  std::string temp_dir(const std::string &name)
  {
    const fs::path p = fs::temp_directory_path() / ("clearjoint_mbd_test_" + name + "_" +
                                                    std::to_string(::getpid()));
    fs::remove_all(p);
    return p.string();
  }
} // namespace

TEST(Scene, TheShippedScenesAllRead)
{
  int n = 0;
  for (const auto &f : fs::directory_iterator(scenes))
    if (f.path().extension() == ".yaml")
    {
      EXPECT_NO_THROW(read_scene(f.path().string())) << f.path();
      ++n;
    }
  EXPECT_GE(n, 10);
}

TEST(Scene, UnknownAndMissingKeys)
{
  expect_error([](auto &d) { d["bodies"][0]["colour"] = "red"; }, {"bodies[0].colour", "unknown key"});
  expect_error([](auto &d) { d["bodies"][1].erase("mass"); }, {"bodies[1].mass", "missing"});
  expect_error([](auto &d) { d.erase("integrator"); }, {"integrator", "missing"});
  expect_error([](auto &d) { d["schema"] = "clearjoint.mbd/2"; }, {"schema", "clearjoint.mbd/1"});
  expect_error([](auto &d) { d["clearance_joints"][0]["normal"]["damping"] = "magic"; },
               {"normal.damping", "lankarani_nikravesh"});
}

TEST(Scene, JointNamingAMissingBody)
{
  expect_error([](auto &d) { d["joints"][1]["body_j"] = "piston"; },
               {"joints[1].body_j", "piston", "crank"});
  expect_error([](auto &d) { d["clearance_joints"][0]["journal"]["body"] = "pin"; },
               {"clearance_joints[0].journal.body", "pin"});
}

TEST(Scene, NonPositiveMassAndInertia)
{
  expect_error([](auto &d) { d["bodies"][0]["mass"] = 0.0; }, {"bodies[0].mass", "(0, 1e+06] kg"});
  expect_error([](auto &d) { d["bodies"][2]["inertia"][1] = -0.001; },
               {"bodies[2].inertia[1]", "kg*m^2"});
}

TEST(Scene, EulerParametersFarFromUnitNorm)
{
  expect_error([](auto &d) { d["bodies"][0]["euler_parameters"] = {1.0, 0.1, 0.0, 0.0}; },
               {"bodies[0].euler_parameters", "unit norm"});
}

TEST(Scene, NonPositiveClearance)
{
  expect_error([](auto &d) { d["clearance_joints"][0]["geometry"]["R_J"] = 0.010; },
               {"geometry.R_J", "c_r"});
  expect_error([](auto &d) { d["clearance_joints"][0]["geometry"]["R_J"] = 0.011; },
               {"geometry.R_J"});
  expect_error([](auto &d) { d["clearance_joints"][0]["geometry"]["L_J"] = 0.025; },
               {"geometry.L_J", "c_a"});
}

TEST(Scene, MissingOrWrongLawFile)
{
  expect_error([](auto &d) { d["clearance_joints"][0]["normal"]["law_file"] = "no_such_law.json"; },
               {"normal.law_file", "no_such_law.json"});
  // A file of the wrong schema: this scene file itself.
  expect_error([](auto &d) {
    d["clearance_joints"][0]["normal"]["law_file"] = "slider_crank_johnson.yaml";
  }, {"normal.law_file", "clearjoint.law/1"});
}

TEST(Scene, ExecutableRejectsBadInputWithExit1AndNoOutputs)
{
  nlohmann::json doc = base();
  doc["bodies"][0]["mass"] = -1.0;
  doc["clearance_joints"][0]["normal"]["law_file"] = scenes + "/../../laws/paper_tB4.json";
  const std::string dir = temp_dir("bad");
  const std::string scene = dir + "_scene.json";
  std::ofstream(scene) << doc.dump();
  const std::string cmd = std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " + dir +
                          " --no-plots -q 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 1);
  EXPECT_FALSE(fs::exists(dir));
  fs::remove(scene);
}

TEST(Scene, ExecutableWritesOutputsAtomically)
{
  nlohmann::json doc = base();
  doc["duration"] = 0.004;  // s: through the first impact, quickly
  doc["clearance_joints"][0]["normal"]["law_file"] = scenes + "/../../laws/paper_tB4.json";
  const std::string dir = temp_dir("good");
  const std::string scene = dir + "_scene.json";
  std::ofstream(scene) << doc.dump();
  const std::string cmd = std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " + dir +
                          " --no-plots -q 2>/dev/null";
  const int rc = std::system(cmd.c_str());
  ASSERT_EQ(WEXITSTATUS(rc), 0);
  for (const char *f : {"timeseries.csv", "summary.json", "manifest.json"})
    EXPECT_TRUE(fs::exists(dir + "/" + f)) << f;
  const nlohmann::json manifest = read_json_file(dir + "/manifest.json");
  EXPECT_EQ(manifest["status"], "complete");
  std::ifstream csv(dir + "/timeseries.csv");
  std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("# units: s,m,m/s,m/s^2"), std::string::npos);
  EXPECT_NE(text.find("# status: complete"), std::string::npos);
  // No temporary directory left behind.
  for (const auto &p : fs::directory_iterator(fs::path(dir).parent_path()))
    EXPECT_EQ(p.path().string().find(dir + ".tmp"), std::string::npos);
  fs::remove_all(dir);
  fs::remove(scene);
}

TEST(Scene, InconsistentInitialVelocitiesAreCorrected)
{
  nlohmann::json doc = base();
  doc["bodies"][2]["velocity"] = {0.0, 0.3, 0.5};  // m/s: the slider may only move along y
  doc["duration"] = 1e-4;
  Scene s = scene_from_json(doc, "v.yaml", scenes);
  EXPECT_GT(s.system->initial_velocity_correction(), 1e-3);
  const SimulationResult r = simulate(s);
  ASSERT_TRUE(r.complete);
  // After the correction the velocity constraints hold at t = 0 (to rounding).
  EXPECT_LT(r.column("phi_dot_max").front(), 1e-12);
}

TEST(Scene, ExecutableHelpDocumentsExitCodes)
{
  const std::string out = temp_dir("help") + ".txt";
  const int rc = std::system((std::string(MBD_STAGE_EXECUTABLE) + " --help > " + out).c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 0);
  std::ifstream f(out);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  for (const char *s : {"Exit codes", "0  success", "1  input error", "2  numerical failure"})
    EXPECT_NE(text.find(s), std::string::npos) << s;
  fs::remove(out);
}

TEST(Scene, LawRangeErrorPolicyStopsTheRunWithExit2AndMarksOutputsFailed)
{
  // A law 1000× softer penetrates beyond the law file's 0.05 mm: with out_of_range = error the
  // run stops, exit code 2, manifest "failed", table "incomplete".
  nlohmann::json doc = base();
  doc["duration"] = 0.01;
  doc["clearance_joints"][0]["normal"]["law_file"] = scenes + "/../../laws/paper_tB4.json";
  doc["clearance_joints"][0]["normal"]["stiffness_scale"] = 1e-3;
  doc["clearance_joints"][0]["normal"]["out_of_range"] = "error";
  const std::string dir = temp_dir("range");
  const std::string scene = dir + "_scene.json";
  std::ofstream(scene) << doc.dump();
  const int rc = std::system((std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " +
                              dir + " --no-plots -q 2>/dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  const nlohmann::json manifest = read_json_file(dir + "/manifest.json");
  EXPECT_EQ(manifest["status"], "failed");
  std::ifstream csv(dir + "/timeseries.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("# status: incomplete"), std::string::npos);
  fs::remove_all(dir);
  fs::remove(scene);
}

TEST(Scene, DuplicateNamesAreRejected)
{
  expect_error([](auto &d) { d["joints"][1]["name"] = "ground_crank"; }, {"joints[1].name", "ground_crank"});
  expect_error([](auto &d) { d["clearance_joints"][0]["name"] = "crank_rod"; },
               {"clearance_joints[0].name"});
}

TEST(Scene, ExecutableRefusesToReplaceAForeignDirectory)
{
  const std::string dir = temp_dir("foreign");
  fs::create_directories(dir);
  std::ofstream(dir + "/precious.txt") << "keep me\n";
  nlohmann::json doc = base();
  doc["duration"] = 0.001;
  doc["clearance_joints"][0]["normal"]["law_file"] = scenes + "/../../laws/paper_tB4.json";
  const std::string scene = dir + "_scene.json";
  std::ofstream(scene) << doc.dump();
  const int rc = std::system((std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " +
                              dir + " --no-plots -q 2>/dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 1);
  EXPECT_TRUE(fs::exists(dir + "/precious.txt"));
  EXPECT_FALSE(fs::exists(dir + "/manifest.json"));
  // A previous mbd_stage output, however, is replaced.
  fs::remove_all(dir);
  ASSERT_EQ(WEXITSTATUS(std::system((std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " +
                                     dir + " --no-plots -q 2>/dev/null").c_str())), 0);
  EXPECT_EQ(WEXITSTATUS(std::system((std::string(MBD_STAGE_EXECUTABLE) + " " + scene + " --output " +
                                     dir + " --no-plots -q 2>/dev/null").c_str())), 0);
  fs::remove_all(dir);
  fs::remove(scene);
}

TEST(Scene, LawFamilyMustBeOverTheTiltInRadians)
{
  // mbd_stage evaluates a law family at the current tilt θ [rad]; a family over θ in degrees
  // (1° would be read as 1 rad) or over t_B would give wrong forces without any error.
  const std::string dir = temp_dir("family_unit");
  fs::create_directories(dir);
  laws::LawFile member = laws::read_law_file(scenes + "/../../laws/paper_tB4.json");
  const auto write = [&](const std::string &name, const std::string &parameter,
                         const std::string &unit, double v0, double v1) {
    const laws::LawFamily family(parameter, unit, member.delta_ref, {{v0, member}, {v1, member}},
                                 laws::RangePolicy::clamp);
    laws::write_law_family(dir + "/" + name, family);
    return dir + "/" + name;
  };
  const std::string deg = write("deg.json", "theta", "deg", 1.0, 2.0);
  const std::string t_B = write("tB.json", "t_B", "m", 0.002, 0.004);
  const std::string rad = write("rad.json", "theta", "rad", 0.0175, 0.035);
  for (const auto &[path, needle] : {std::pair{deg, "over theta in deg"}, {t_B, "over t_B in m"}})
    expect_error([&](auto &d) {
      d["clearance_joints"][0]["normal"]["model"] = "law_family";
      d["clearance_joints"][0]["normal"]["law_file"] = path;
    }, {"normal.law_file", "a law family over the tilt theta in rad", needle});
  nlohmann::json doc = base();
  doc["clearance_joints"][0]["normal"]["model"] = "law_family";
  doc["clearance_joints"][0]["normal"]["law_file"] = rad;
  EXPECT_NO_THROW(scene_from_json(doc, "good.yaml", scenes));
  fs::remove_all(dir);
}
