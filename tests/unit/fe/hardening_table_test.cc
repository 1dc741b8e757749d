// Tabulated isotropic hardening (fe_stage/material/hardening_table.h): the SPEC §2 default
// reproduces 168.2 + 280.25·ε_p MPa, interpolation and slopes on a non-uniform table, the two
// behaviours beyond the last point, and every bad-table message naming the key and range.
#include "fe_stage/material/hardening_table.h"

#include "common/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using clearjoint::InputError;
using clearjoint::fe::HardeningPoint;
using clearjoint::fe::HardeningTable;

namespace
{
  /// Expects an InputError whose key path and message contain the given fragments.
  void expect_input_error(const std::vector<HardeningPoint> &points, const std::string &key,
                          const std::string &allowed_fragment)
  {
    const std::string message = clearjoint::test_support::input_error_of(
      [&] { HardeningTable t(points, "material.hardening", "scene.yaml"); });
    EXPECT_NE(message.find("input error in scene.yaml: key '" + key + "'"), std::string::npos)
      << message;
    EXPECT_NE(message.find(allowed_fragment), std::string::npos) << message;
  }
} // namespace

TEST(HardeningTable, SpecDefaultIsTheLinearLaw)
{
  const HardeningTable t = HardeningTable::spec_default();
  ASSERT_EQ(t.n_points(), 11u);
  EXPECT_EQ(t.points().front().eps_p, 0.0);
  EXPECT_EQ(t.points().back().eps_p, 1.0);
  // The table is the line itself, so interpolation and extrapolation reproduce it everywhere;
  // 1e-12 relative: a few roundings of the segment arithmetic.
  for (double e = 0.0; e <= 1.5; e += 0.0137)
    {
      const double exact = (168.2 + 280.25 * e) * 1e6;
      EXPECT_NEAR(t.yield_stress(e), exact, 1e-12 * exact) << "eps_p = " << e;
      EXPECT_NEAR(t.slope(e), 280.25e6, 1e-9 * 280.25e6) << "eps_p = " << e;
    }
  EXPECT_NEAR(t.yield_stress(0.0), 168.2e6, 1e-6);   // end points exactly as SPEC §2 lists them
  EXPECT_NEAR(t.yield_stress(1.0), 448.45e6, 1e-6);
}

TEST(HardeningTable, InterpolatesANonUniformTable)
{
  // Three segments with slopes 1000, 0 (a plateau) and 250 MPa, then the tail.
  const HardeningTable t({{0.0, 200e6}, {0.01, 210e6}, {0.05, 210e6}, {0.45, 310e6}},
                         "material.hardening");
  EXPECT_DOUBLE_EQ(t.yield_stress(0.005), 205e6);
  EXPECT_DOUBLE_EQ(t.slope(0.005), 1000e6);
  EXPECT_DOUBLE_EQ(t.yield_stress(0.03), 210e6);
  EXPECT_DOUBLE_EQ(t.slope(0.03), 0.0);
  EXPECT_DOUBLE_EQ(t.yield_stress(0.25), 260e6);
  // At a table point the slope is the segment to the right (plastic loading moves right).
  EXPECT_EQ(t.segment(0.01), 1u);
  EXPECT_DOUBLE_EQ(t.slope(0.01), 0.0);
  EXPECT_DOUBLE_EQ(t.slope(0.05), 250e6);
  // Beyond the last point: the last segment extended.
  EXPECT_EQ(t.segment(0.5), 3u);
  EXPECT_DOUBLE_EQ(t.slope(0.5), 250e6);
  EXPECT_NEAR(t.yield_stress(0.85), 410e6, 1e-6);
  EXPECT_EQ(t.segment_end(0), 0.01);
  EXPECT_TRUE(std::isinf(t.segment_end(3)));
}

TEST(HardeningTable, HoldLastAndOnePoint)
{
  const HardeningTable hold({{0.0, 200e6}, {0.1, 300e6}}, "m.h", "",
                            HardeningTable::Beyond::hold_last);
  EXPECT_DOUBLE_EQ(hold.yield_stress(0.05), 250e6);
  EXPECT_DOUBLE_EQ(hold.yield_stress(0.7), 300e6);
  EXPECT_DOUBLE_EQ(hold.slope(0.7), 0.0);
  const HardeningTable perfect({{0.0, 250e6}}, "m.h");   // perfectly plastic
  EXPECT_DOUBLE_EQ(perfect.yield_stress(0.3), 250e6);
  EXPECT_DOUBLE_EQ(perfect.slope(0.3), 0.0);
}

TEST(HardeningTable, NegativeOrNanStrainIsAProgrammingError)
{
  const HardeningTable t = HardeningTable::spec_default();
  EXPECT_THROW(t.yield_stress(-1e-9), std::invalid_argument);
  EXPECT_THROW(t.slope(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(HardeningTable, BadTablesNameKeyAndRange)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_input_error({}, "material.hardening", "at least one");
  expect_input_error({{0.1, 200e6}}, "material.hardening[0][0]", "start at zero");
  expect_input_error({{0.0, 200e6}, {0.1, 210e6}, {0.1, 220e6}}, "material.hardening[2][0]",
                     "strictly increasing");
  expect_input_error({{0.0, 200e6}, {0.2, 210e6}, {0.1, 220e6}}, "material.hardening[2][0]",
                     "> 0.2");
  expect_input_error({{0.0, 200e6}, {0.1, 190e6}}, "material.hardening[1][1]", "non-decreasing");
  expect_input_error({{0.0, -5e6}}, "material.hardening[0][1]", "> 0 Pa");
  expect_input_error({{0.0, 0.0}}, "material.hardening[0][1]", "> 0 Pa");
  expect_input_error({{0.0, 200e6}, {nan, 210e6}}, "material.hardening[1][0]", "finite");
  expect_input_error({{0.0, 200e6}, {0.1, inf}}, "material.hardening[1][1]", "finite");
  expect_input_error({{-0.1, 200e6}}, "material.hardening[0][0]", "start at zero");
}
