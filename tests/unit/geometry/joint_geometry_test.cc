// Joint dimensions (Eqs. 1–2), validation messages, and θ_max (Eq. 3) against independent
// closed forms.
#include "common/error.h"
#include "geometry/joint_geometry.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace clearjoint;
using namespace clearjoint::geometry;

namespace
{
  using test_support::input_error_of;

  JointGeometry make(double R_B_mm, double c_r_mm, double L_B_mm, double c_a_mm)
  {
    return JointGeometry{R_B_mm * 1e-3, 4e-3, L_B_mm * 1e-3, c_r_mm * 1e-3, c_a_mm * 1e-3};
  }

  // Independent route 1: half-angle substitution u = tan(θ/2) turns Eq. 3 into the quadratic
  // (c_r + 2R_J)u² − L_J u + c_r = 0; the smaller root (written without cancellation) is the
  // physical one.
  double theta_half_angle(const JointGeometry &g)
  {
    const double c = g.c_r, R = g.R_J(), L = g.L_J();
    const double disc = L * L - 4.0 * c * (c + 2.0 * R);
    return 2.0 * std::atan(2.0 * c / (L + std::sqrt(disc)));
  }

  // Independent route 2: R_J cos θ + (L_J/2) sin θ = D cos(θ − φ) = R_B with D the journal's
  // half-diagonal and φ = atan(L_J / 2R_J).
  double theta_phase(const JointGeometry &g)
  {
    const double R = g.R_J(), H = 0.5 * g.L_J();
    return std::atan2(H, R) - std::acos(g.R_B / std::hypot(R, H));
  }

  double eq3(const JointGeometry &g, double t)
  {
    return g.c_r + g.R_J() * (1.0 - std::cos(t)) - 0.5 * g.L_J() * std::sin(t);
  }
} // namespace

TEST(JointGeometry, JournalFromClearances)
{
  const JointGeometry g;  // SPEC §2 defaults
  EXPECT_DOUBLE_EQ(g.R_J(), 9.5e-3);
  EXPECT_DOUBLE_EQ(g.L_J(), 18e-3);
  const auto h = JointGeometry::from_journal(10e-3, 4e-3, 20e-3, 9.5e-3, 18e-3);
  EXPECT_DOUBLE_EQ(h.c_r, 0.5e-3);
  EXPECT_DOUBLE_EQ(h.c_a, 1e-3);
}

// SPEC §2: 3.2842° for the defaults (quoted to 4 decimals, so ±0.5e-4°).
TEST(ThetaMax, DefaultGeometryMatchesSpec)
{
  const auto t = theta_max(JointGeometry{});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(degrees(*t), 3.2842, 0.5e-4);
}

// Defaults and two other geometries against both closed forms and by substitution. 1e-12
// relative: all three are double-precision evaluations of well-conditioned expressions (the
// root is simple: f'(θ_max) is far from zero); |f| ≤ 1e-18 m is ~1e-15 of the lengths involved.
TEST(ThetaMax, AgreesWithClosedFormsForThreeGeometries)
{
  for (const auto &g : {make(10, 0.5, 20, 1), make(25, 0.1, 30, 0.5), make(5, 0.02, 40, 2)})
  {
    const auto t = theta_max(g);
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, theta_half_angle(g), 1e-12 * *t);
    EXPECT_NEAR(*t, theta_phase(g), 1e-9 * *t);  // acos near 1 loses ~half the digits
    EXPECT_LE(std::abs(eq3(g, *t)), 1e-18);
    // The physical root: f > 0 (free) just below, f < 0 (interference) just above.
    EXPECT_GT(eq3(g, 0.999 * *t), 0.0);
    EXPECT_LT(eq3(g, 1.001 * *t), 0.0);
    std::printf("theta_max(R_B=%g, c_r=%g, L_B=%g, c_a=%g mm) = %.6f deg\n", g.R_B * 1e3,
                g.c_r * 1e3, g.L_B * 1e3, g.c_a * 1e3, degrees(*t));
  }
}

// Smaller clearance → smaller tilt; longer journal → smaller tilt.
TEST(ThetaMax, MonotoneInClearanceAndLength)
{
  EXPECT_LT(*theta_max(make(10, 0.25, 20, 1)), *theta_max(make(10, 0.5, 20, 1)));
  EXPECT_LT(*theta_max(make(10, 0.5, 40, 1)), *theta_max(make(10, 0.5, 20, 1)));
}

// A journal whose half-diagonal √(R_J² + L_J²/4) is below R_B can turn over: no root.
TEST(ThetaMax, NoRootForAShortJournal)
{
  const auto g = make(10, 2, 6, 1);  // R_J = 8, L_J = 4: D = 8.25 mm < 10 mm
  EXPECT_FALSE(theta_max(g).has_value());
  EXPECT_NO_THROW(check_tilt(g, radians(89.0)));
  EXPECT_NE(input_error_of([&] { check_tilt(g, radians(90.0)); }).find("no root"),
            std::string::npos);
}

// Near the grazing case (D just above R_B) the root sits close to the minimum of f, where
// Newton alone is ill-conditioned: the bracket keeps it converging.
TEST(ThetaMax, NearlyGrazingGeometryConverges)
{
  // R_J = 8 mm, choose L_J so that D = R_B (1 + 1e-6).
  const double R_B = 10e-3, R_J = 8e-3, D = R_B * (1.0 + 1e-6);
  const double L_J = 2.0 * std::sqrt(D * D - R_J * R_J);
  const auto g = JointGeometry::from_journal(R_B, 4e-3, L_J + 2e-3, R_J, L_J);
  const auto t = theta_max(g);
  ASSERT_TRUE(t.has_value());
  // Double root in the limit: a 1e-6 perturbation moves the root by O(√1e-6); 1e-6 relative.
  EXPECT_NEAR(*t, theta_half_angle(g), 1e-6 * *t);
  EXPECT_LE(std::abs(eq3(g, *t)), 1e-15);
}

TEST(CheckTilt, AcceptsThetaMaxAndRejectsMoreWithTheLimitInTheMessage)
{
  const JointGeometry g;
  const double t = *theta_max(g);
  EXPECT_NO_THROW(check_tilt(g, t));
  EXPECT_NO_THROW(check_tilt(g, radians(2.5)));
  EXPECT_NO_THROW(check_tilt(g, 0.0));
  const auto m =
    input_error_of([&] { check_tilt(g, t + radians(1e-3), "scene.yaml", "study.theta"); });
  EXPECT_NE(m.find("scene.yaml"), std::string::npos) << m;
  EXPECT_NE(m.find("study.theta"), std::string::npos) << m;
  EXPECT_NE(m.find("theta_max = 3.28423 deg"), std::string::npos) << m;
  EXPECT_NE(m.find("3.28523"), std::string::npos) << m;  // the offending value
  const auto negative = input_error_of([&] { check_tilt(g, -radians(1.0)); });
  EXPECT_NE(negative.find("allowed: 0 <= theta <= theta_max"), std::string::npos) << negative;
}

TEST(JointGeometryValidation, NamesFieldAndRange)
{
  auto with = [](auto edit) {
    JointGeometry g;
    edit(g);
    return input_error_of([&] { g.validate("joint.yaml", "geometry"); });
  };
  auto has = [](const std::string &m, const std::string &s) {
    return m.find(s) != std::string::npos;
  };
  std::string m = with([](JointGeometry &g) { g.c_r = 0.0; });
  EXPECT_TRUE(has(m, "joint.yaml") && has(m, "geometry.c_r") && has(m, "0 < c_r < R_B")) << m;
  m = with([](JointGeometry &g) { g.c_r = -1e-4; });
  EXPECT_TRUE(has(m, "geometry.c_r") && has(m, "journal larger than bearing")) << m;
  m = with([](JointGeometry &g) { g.c_r = 0.02; });
  EXPECT_TRUE(has(m, "geometry.c_r") && has(m, "R_J")) << m;
  m = with([](JointGeometry &g) { g.t_B = 0.0; });
  EXPECT_TRUE(has(m, "geometry.t_B") && has(m, "> 0 m")) << m;
  m = with([](JointGeometry &g) { g.c_a = 0.0; });
  EXPECT_TRUE(has(m, "geometry.c_a") && has(m, ">= L_B")) << m;
  m = with([](JointGeometry &g) { g.c_a = 0.011; });
  EXPECT_TRUE(has(m, "geometry.c_a") && has(m, "<= 0")) << m;
  m = with([](JointGeometry &g) { g.R_B = std::numeric_limits<double>::quiet_NaN(); });
  EXPECT_TRUE(has(m, "geometry.R_B")) << m;
  EXPECT_EQ(with([](JointGeometry &) {}), test_support::accepted);

  m = input_error_of(
    [] { JointGeometry::from_journal(10e-3, 4e-3, 20e-3, 10.5e-3, 18e-3, "j.yaml"); });
  EXPECT_TRUE(has(m, "geometry.R_J") && has(m, "journal larger than bearing") &&
              has(m, "< R_B = 0.01 m")) << m;
  m = input_error_of(
    [] { JointGeometry::from_journal(10e-3, 4e-3, 20e-3, 9.5e-3, 20e-3, "j.yaml"); });
  EXPECT_TRUE(has(m, "geometry.L_J") && has(m, "< L_B")) << m;
  // theta_max validates first.
  EXPECT_THROW(theta_max(JointGeometry{10e-3, 4e-3, 20e-3, 0.0, 1e-3}), InputError);
}
