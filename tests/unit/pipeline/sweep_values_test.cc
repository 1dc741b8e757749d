// The theta_max keyword of a sweep's values: resolved from the sweep's scene geometry (after
// preset and overrides) with geometry::theta_max, exactly, and bad uses named by key.
#include "common/error.h"
#include "common/units.h"
#include "geometry/joint_geometry.h"
#include "pipeline/pipeline_config.h"
#include "pipeline/sweep_values.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;
using namespace clearjoint::pipeline;

namespace
{
  /// A pipeline with one misalignment-like sweep over `values`; `scene_geometry` is the base
  /// scene's geometry block, `sweep_extra` more sweep keys, `preset_fe` the fast preset's FE map.
  PipelineConfig config_with(const test_support::ScratchDir &dir, const std::string &values,
                             const std::string &scene_geometry = "",
                             const std::string &sweep_extra = "", const std::string &unit = "deg",
                             const std::string &preset_fe = "null")
  {
    test_support::write_text(dir.file("fe.yaml"), "schema: clearjoint.fe/1\nstudy: misalignment\n" +
                                                    scene_geometry +
                                                    "misalignment: {theta_deg: 1.0}\n");
    test_support::write_text(
      dir.file("p.yaml"),
      "schema: clearjoint.pipeline/1\nrun: r\npreset: fast\n"
      "presets: {fast: {fe: " + preset_fe + ", mbd: null}, standard: {fe: null, mbd: null}, "
      "accurate: {fe: null, mbd: null}}\n"
      "fe_sweeps:\n  - name: misalignment\n    scene: " + dir.file("fe.yaml") + "\n"
      "    parameter: {name: theta, unit: " + unit + ", key: misalignment.theta_deg}\n"
      "    values: " + values + "\n" + sweep_extra +
      "fit: {weighting: absolute}\nmbd_runs: []\n");
    return read_pipeline_config(dir.file("p.yaml"));
  }

  std::string resolve_error(PipelineConfig c)
  {
    return test_support::input_error_of([&] { resolve_value_keywords(c); });
  }
} // namespace

TEST(SweepValues, ThetaMaxOfTheDefaultGeometryIsEq3InDegrees)
{
  test_support::ScratchDir dir("sweep_values_default");
  auto c = config_with(dir, "[1.0, 1.5, 2.0, 2.5, theta_max]");
  EXPECT_TRUE(std::isnan(c.fe_sweeps[0].values[4])) << "unresolved until the preset is known";
  resolve_value_keywords(c);
  // The scene sets no geometry: the FE defaults, which are JointGeometry's.
  const double expected = geometry::degrees(*geometry::theta_max(geometry::JointGeometry{}));
  EXPECT_EQ(c.fe_sweeps[0].values[4], expected) << "full precision, no rounding";
  EXPECT_NEAR(expected, 3.284226, 5e-7) << "docs/geometry.md table";  // 6 digits printed there
  EXPECT_EQ(c.fe_sweeps[0].keywords[4], "theta_max");
  EXPECT_EQ(c.fe_sweeps[0].values[0], 1.0);
}

TEST(SweepValues, ThetaMaxFollowsANonDefaultGeometryFromSceneOverridesAndPreset)
{
  // docs/geometry.md: R_B 25, c_r 0.1, L_B 30, c_a 0.5 mm → θ_max = 0.397515°.
  test_support::ScratchDir dir("sweep_values_other");
  geometry::JointGeometry g;
  g.R_B = 25e-3, g.c_r = 0.1e-3, g.L_B = 30e-3, g.c_a = 0.5e-3;
  const double expected = geometry::degrees(*geometry::theta_max(g));
  EXPECT_NEAR(expected, 0.397515, 5e-7);
  {
    auto c = config_with(dir, "[0.1, theta_max]",
                         "geometry: {R_B: 0.025, c_r: 1.0e-4, L_B: 0.030, c_a: 5.0e-4}\n");
    resolve_value_keywords(c);
    EXPECT_EQ(c.fe_sweeps[0].values[1], expected) << "from the base scene";
  }
  {
    auto c = config_with(dir, "[0.1, theta_max]", "geometry: {R_B: 0.025, L_B: 0.030}\n",
                         "    overrides: {geometry.c_r: 1.0e-4, geometry.c_a: 5.0e-4}\n");
    resolve_value_keywords(c);
    EXPECT_EQ(c.fe_sweeps[0].values[1], expected) << "with the sweep's overrides";
  }
  {
    auto c = config_with(dir, "[0.1, theta_max]", "geometry: {R_B: 0.025, L_B: 0.030}\n", "",
                         "deg", "{geometry.c_r: 1.0e-4, geometry.c_a: 5.0e-4}");
    resolve_value_keywords(c);
    EXPECT_EQ(c.fe_sweeps[0].values[1], expected) << "with the preset's overrides";
  }
  {
    auto c = config_with(dir, "[0.001, theta_max]",
                         "geometry: {R_B: 0.025, c_r: 1.0e-4, L_B: 0.030, c_a: 5.0e-4}\n", "",
                         "rad");
    resolve_value_keywords(c);
    EXPECT_EQ(c.fe_sweeps[0].values[1], *geometry::theta_max(g)) << "a sweep in rad gets rad";
  }
}

TEST(SweepValues, BadUsesOfThetaMaxNameTheKey)
{
  test_support::ScratchDir dir("sweep_values_bad");
  // Eq. 3 has no root (docs/geometry.md: R_B 10, c_r 2, L_B 6, c_a 1 mm): no largest tilt.
  std::string m = resolve_error(
    config_with(dir, "[1.0, theta_max]", "geometry: {R_B: 0.010, c_r: 0.002, L_B: 0.006, c_a: 0.001}\n"));
  EXPECT_NE(m.find("fe_sweeps[0].values[1]"), std::string::npos) << m;
  EXPECT_NE(m.find("Eq. 3 has no root"), std::string::npos) << m;
  EXPECT_NE(m.find("p.yaml"), std::string::npos) << m;
  // Not an angle.
  m = resolve_error(config_with(dir, "[1.0, theta_max]", "", "", "m"));
  EXPECT_NE(m.find("fe_sweeps[0].values[1]"), std::string::npos) << m;
  EXPECT_NE(m.find("deg or rad"), std::string::npos) << m;
  // θ_max below an earlier value: the values no longer increase.
  m = resolve_error(config_with(dir, "[1.0, theta_max]",
                                "geometry: {R_B: 0.025, c_r: 1.0e-4, L_B: 0.030, c_a: 5.0e-4}\n"));
  EXPECT_NE(m.find("strictly increasing"), std::string::npos) << m;
  EXPECT_NE(m.find("theta_max = 0.3975"), std::string::npos) << m;
  // A bad geometry in the scene names the scene's key.
  m = resolve_error(config_with(dir, "[1.0, theta_max]", "geometry: {c_r: -1.0e-4}\n"));
  EXPECT_NE(m.find("geometry.c_r"), std::string::npos) << m;
  // Sweeping a key θ_max depends on.
  test_support::write_text(dir.file("fe2.yaml"), "schema: clearjoint.fe/1\n");
  auto c = config_with(dir, "[1.0, theta_max]");
  c.fe_sweeps[0].key = "geometry.c_r";
  m = resolve_error(c);
  EXPECT_NE(m.find("depends on geometry.c_r"), std::string::npos) << m;
  // A file with the deprecated key `fe_studies`: the message names the key as the file has it.
  c = config_with(dir, "[1.0, theta_max]", "", "", "m");
  c.fe_sweeps_key = "fe_studies";
  m = resolve_error(c);
  EXPECT_NE(m.find("fe_studies[0].values[1]"), std::string::npos) << m;
}

TEST(SweepValues, FamiliesAreStoredInSI)
{
  EXPECT_EQ(to_si(1.0, "deg").unit, "rad");
  EXPECT_DOUBLE_EQ(to_si(1.0, "deg").value, units::pi / 180.0);
  EXPECT_EQ(to_si(4.0, "mm").unit, "m");
  EXPECT_DOUBLE_EQ(to_si(4.0, "mm").value, 4e-3);
  EXPECT_EQ(to_si(0.004, "m").unit, "m");
  EXPECT_EQ(to_si(0.004, "m").value, 0.004);
}

TEST(SweepValues, LabelsReadBackExactly)
{
  for (const double v : {0.004, 0.002, 1.0, 1.5, 0.01,
                         geometry::degrees(*geometry::theta_max(geometry::JointGeometry{}))})
    EXPECT_EQ(std::strtod(value_label(v).c_str(), nullptr), v) << value_label(v);
  EXPECT_EQ(value_label(0.004), "0.004");
  EXPECT_EQ(value_label(1.0), "1");
}
