// Dynamic runs of the clearance joint outside the slider–crank: a free journal in a fixed
// bearing under gravity inclined to the axis (radial and axial contact together, Hertz-type
// walls), and the tilted slider–crank with a law family evaluated at the current tilt.
#include "scene_fixture.h"

#include "common/log.h"
#include "laws/law_family.h"
#include "laws/law_file.h"

#include <cmath>

#include <gtest/gtest.h>

#include <filesystem>

using namespace clearjoint;
using namespace clearjoint::mbd;
using namespace clearjoint::mbd::testing;

namespace
{
  nlohmann::json free_journal(const double mu, const double c_e)
  {
    return nlohmann::json::parse(R"({
      "schema": "clearjoint.mbd/1", "name": "free_journal", "duration": 0.08,
      "gravity": [-6.0, -7.0, 1.0],
      "bodies": [{"name": "pin", "mass": 0.15, "inertia": [1e-5, 1e-5, 1e-5],
                  "position": [0.0, 0.0, 0.0], "euler_parameters": [1.0, 0.0, 0.0, 0.0],
                  "velocity": [0.05, 0.02, -0.03], "angular_velocity": [2.0, 0.5, 0.0]}],
      "joints": [],
      "clearance_joints": [{
        "name": "cj",
        "bearing": {"body": "ground", "center": [0.0, 0.0, 0.0], "axis": [1.0, 0.0, 0.0]},
        "journal": {"body": "pin", "center": [0.0, 0.0, 0.0], "axis": [1.0, 0.0, 0.0]},
        "geometry": {"R_B": 0.010, "R_J": 0.0095, "L_B": 0.020, "L_J": 0.018},
        "material": {"E_bearing": 207e9, "nu_bearing": 0.3, "E_journal": 207e9, "nu_journal": 0.3},
        "normal": {"model": "hertz", "damping": "lankarani_nikravesh", "restitution": 0.5},
        "axial": {"K": 1e9, "n": 1.5, "damping": "lankarani_nikravesh", "restitution": 0.5},
        "friction": {"mu": 0.1, "v0": 1e-4, "v1": 1e-3}}],
      "integrator": {"method": "dopri5", "rtol": 1e-8, "atol_position": 1e-10,
                     "atol_velocity": 1e-7, "max_step": 0.0, "output_interval": 1e-4}
    })")
      .patch(nlohmann::json::parse(
        R"([{"op": "replace", "path": "/clearance_joints/0/friction/mu", "value": )" +
        std::to_string(mu) + R"(}, {"op": "replace", "path": "/clearance_joints/0/normal/restitution", "value": )" +
        std::to_string(c_e) + R"(}, {"op": "replace", "path": "/clearance_joints/0/axial/restitution", "value": )" +
        std::to_string(c_e) + "}]"));
  }
} // namespace

TEST(ClearanceScenarios, FreeJournalHitsRimAndWallTogether)
{
  const SimulationResult r = run(free_journal(0.1, 0.5));
  ASSERT_TRUE(r.complete) << r.failure;
  const auto &n = r.summary["clearance_joints"][0]["n_impacts"];
  EXPECT_GT(n["radial"].get<int>(), 0);
  EXPECT_GT(n["axial_neg"].get<int>(), 0);  // gravity has a −x component
  // Both at once at some output time.
  const auto Fr = r.column("cj_radial_F_n"), Fa = r.column("cj_axial_neg_F_n");
  bool together = false;
  for (std::size_t i = 0; i < Fr.size(); ++i)
    together = together || (Fr[i] > 0.0 && Fa[i] > 0.0);
  EXPECT_TRUE(together);
  // Losses booked: the balance closes (measured < 1e-6 of the energy scale).
  const double scale = 0.15 * 9.3 * 0.0105 + std::abs(r.E0);  // J: m·|g|·(clearance scale) + E0
  for (const double e : r.column("energy_error"))
    ASSERT_LT(std::abs(e), 1e-5 * scale);
}

TEST(ClearanceScenarios, FreeJournalWithoutLossesKeepsItsEnergy)
{
  const SimulationResult r = run(free_journal(0.0, 1.0));
  ASSERT_TRUE(r.complete) << r.failure;
  EXPECT_EQ(r.summary["energy"]["W_friction"].get<double>(), 0.0);
  EXPECT_EQ(r.summary["energy"]["W_damping"].get<double>(), 0.0);
  const auto E = r.column("E_total");
  const double scale = 0.15 * 9.3 * 0.0105 + std::abs(r.E0);
  for (const double e : E)
    ASSERT_NEAR(e, E.front(), 1e-5 * scale);  // measured ~1e-7 of the scale (2e-9 J)
}

TEST(ClearanceScenarios, TiltedSceneWithALawFamily)
{
  // A family over θ: the paper's law at 0 and a softer one at 2°; the tilted scene at 1° must
  // use the interpolated law (softer contact → lower peak force than the aligned law).
  const auto member = [](const double theta, const double K, const double n) {
    laws::LawFile lf;
    lf.law = {K, n};
    lf.delta_min = 0.0;
    lf.delta_max = 5e-5;
    lf.delta_ref = 5e-5;
    lf.source_kind = "fit";
    lf.source_description = "test family";
    return laws::LawFamilyMember{theta, lf};
  };
  const double t2 = 2.0 * 3.14159265358979 / 180.0;
  const laws::LawFamily fam("theta", "rad", 5e-5,
                            {member(0.0, 3.6595e8, 1.0114), member(t2, 0.5e8, 1.0114)},
                            laws::RangePolicy::error);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("clearjoint_family_" + std::to_string(::getpid()) + ".json")).string();
  laws::write_law_family(path, fam);
  nlohmann::json d = load_scene("slider_crank_tilted_1deg");
  d["duration"] = 0.01;  // s: through the first impact
  d["clearance_joints"][0]["normal"]["model"] = "law_family";
  d["clearance_joints"][0]["normal"]["law_file"] = path;
  const SimulationResult fam_run = run(d);
  d = load_scene("slider_crank_tilted_1deg");
  d["duration"] = 0.01;
  const SimulationResult aligned = run(d);
  std::filesystem::remove(path);
  ASSERT_TRUE(fam_run.complete) << fam_run.failure;
  ASSERT_TRUE(aligned.complete);
  EXPECT_LT(fam_run.first_impact_peak_force, 0.9 * aligned.first_impact_peak_force);
  EXPECT_LT(fam_run.max_relative_energy_error, 1e-4);
}

TEST(ClearanceScenarios, SublinearLawWithUnboundedStiffnessAtOnset)
{
  // SPEC §6 "δ → 0 (n < 1 makes dF/dδ large)": a law F = K·δ^0.9 from a law file; the onset is
  // located by root finding, so the infinite slope at δ = 0 is never integrated across.
  laws::LawFile lf;
  lf.law = {3.6595e8 * std::pow(5e-5, 1.0114 - 0.9), 0.9};  // same F at 0.05 mm as the paper's
  lf.delta_min = 0.0;
  lf.delta_max = 5e-5;
  lf.delta_ref = 5e-5;
  lf.source_kind = "fit";
  lf.source_description = "test: sublinear law";
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("clearjoint_sublinear_" + std::to_string(::getpid()) + ".json")).string();
  laws::write_law_file(path, lf);
  nlohmann::json d = free_journal(0.0, 1.0);
  d["clearance_joints"][0]["normal"] = {{"model", "fe_law"}, {"law_file", path},
                                        {"out_of_range", "extend"}, {"damping", "none"},
                                        {"restitution", 1.0}};
  const SimulationResult r = run(d);
  std::filesystem::remove(path);
  ASSERT_TRUE(r.complete) << r.failure;
  EXPECT_TRUE(all_finite(r));
  EXPECT_GT(r.summary["clearance_joints"][0]["n_impacts"]["radial"].get<int>(), 0);
  const auto E = r.column("E_total");
  const double scale = 0.15 * 9.3 * 0.0105 + std::abs(r.E0);
  for (const double e : E)
    ASSERT_NEAR(e, E.front(), 1e-5 * scale);  // conservative: energy kept (measured ~1e-7)
}
