// The rigid obstacles' gap functions (fe_stage/contact/rigid_obstacle.h) against closed forms:
// the aligned journal, the tilted journal on its side, beyond a rim and over its end face, the
// Hertz sphere and the patch test's plane. Tolerance 1e-15 m on lengths of ~1e-2 m: the closed
// forms and the implementation differ only by round-off (a few ulps of 0.02 m ≈ 3.5e-18 each).
#include "fe_stage/contact/rigid_obstacle.h"

#include <gtest/gtest.h>

#include <cmath>

using clearjoint::fe::RigidObstacle;
using clearjoint::fe::Vec3;

namespace
{
  constexpr double tol = 1e-15;  // [m] (see above); unit normals: the same bound relative to 1

  void expect_vec(const Vec3 &a, const Vec3 &b, const double t = tol)
  {
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(a[i], b[i], t) << "component " << i;
  }
  Vec3 add(const Vec3 &a, const Vec3 &b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
  Vec3 mul(const double s, const Vec3 &a) { return {s * a[0], s * a[1], s * a[2]}; }

  // The paper's joint: R_B = 10 mm, c_r = 0.5 mm, R_J = 9.5 mm, L_J = 20 mm.
  constexpr double R_B = 0.010, c_r = 0.0005, R_J = R_B - c_r, h = 0.010;
} // namespace

TEST(RigidObstacle, AlignedJournalTouchesTheBoreBottomAndPenetratesByDelta)
{
  RigidObstacle o;
  o.kind = RigidObstacle::Kind::cylinder;
  o.radius = R_J;
  o.offset = c_r;
  o.half_length = h;
  double g0 = 1.0;
  Vec3 n;
  // the bore's bottom (0, −R_B, z): first touch at δ = 0, penetration δ beyond it
  for (const double delta : {0.0, 1e-5, 5e-5})
    {
      ASSERT_TRUE(o.gap({0.0, -R_B, 0.003}, delta, g0, n));
      EXPECT_NEAR(g0, -delta, tol);
      expect_vec(n, {0.0, -1.0, 0.0});
    }
  // 90° round the bore: distance from the journal's axis (0, −c_r − δ) is √(R_B² + (c_r+δ)²)
  const double delta = 2e-5;
  ASSERT_TRUE(o.gap({R_B, 0.0, 0.0}, delta, g0, n));
  const double d = std::hypot(R_B, c_r + delta);
  EXPECT_NEAR(g0, d - R_J, tol);
  expect_vec(n, {R_B / d, (c_r + delta) / d, 0.0});
  // beyond the journal's end: never touches, and g0/n are left as they were
  g0 = 7.0;
  EXPECT_FALSE(o.gap({0.0, -R_B, h * 1.001}, delta, g0, n));
  EXPECT_EQ(g0, 7.0);
}

TEST(RigidObstacle, TiltedJournalSideRimAndEndFace)
{
  const double theta = 2.0 * 3.14159265358979323846 / 180.0;
  RigidObstacle o;
  o.kind = RigidObstacle::Kind::tilted_cylinder;
  o.radius = R_J;
  o.half_length = h;
  o.tilt = theta;
  o.offset = 0.0004;
  const double delta = 3e-5;
  const Vec3 C = {0.0, -o.offset - delta, 0.0};
  const Vec3 a = {0.0, std::sin(theta), std::cos(theta)};
  const Vec3 e1 = {1.0, 0.0, 0.0};                               // ⟂ a
  const Vec3 e2 = {0.0, std::cos(theta), -std::sin(theta)};      // ⟂ a and e1
  double g0;
  Vec3 n;
  // on the side, within the length: distance to the axis minus the radius, normal radial
  for (const auto &e : {e1, e2, mul(-1.0, e2)})
    for (const double s : {-0.9 * h, 0.0, 0.5 * h})
      {
        const Vec3 X = add(add(C, mul(s, a)), mul(R_J + 2e-4, e));
        ASSERT_TRUE(o.gap(X, delta, g0, n));
        EXPECT_NEAR(g0, 2e-4, tol);
        expect_vec(n, e);
      }
  // beyond an end, outside the rim circle: distance to the rim point
  const double b = 3e-4, out = 4e-4;
  for (const double sign : {1.0, -1.0})
    {
      const Vec3 X = add(add(C, mul(sign * (h + b), a)), mul(R_J + out, e2));
      ASSERT_TRUE(o.gap(X, delta, g0, n));
      const double dist = std::hypot(b, out);
      EXPECT_NEAR(g0, dist, tol);
      // v = X − rim cancels coordinates of ~1e-2 m down to |v| = 5e-4 m: the unit normal
      // carries ~(1e-2 / 5e-4) × 1e-16 relative round-off, so 1e-13
      expect_vec(n, add(mul(sign * b / dist, a), mul(out / dist, e2)), 1e-13);
    }
  // beyond an end, inside the rim circle: distance to the end face, normal along ±a
  const Vec3 X = add(add(C, mul(-(h + b), a)), mul(0.5 * R_J, e1));
  ASSERT_TRUE(o.gap(X, delta, g0, n));
  EXPECT_NEAR(g0, b, tol);
  expect_vec(n, mul(-1.0, a));
}

TEST(RigidObstacle, SphereAndPlane)
{
  RigidObstacle s;
  s.kind = RigidObstacle::Kind::sphere;
  s.radius = 0.02;
  double g0;
  Vec3 n;
  const double delta = 1e-5;
  // directly below the centre (0, R − δ, 0): the surface point at the origin penetrates by δ
  ASSERT_TRUE(s.gap({0.0, 0.0, 0.0}, delta, g0, n));
  EXPECT_NEAR(g0, -delta, tol);
  expect_vec(n, {0.0, -1.0, 0.0});
  // off axis at radius r on the plane y = 0: g0 = √(r² + (R − δ)²) − R
  const double r = 1e-3, d = std::hypot(r, s.radius - delta);
  ASSERT_TRUE(s.gap({r, 0.0, 0.0}, delta, g0, n));
  EXPECT_NEAR(g0, d - s.radius, tol);
  expect_vec(n, {r / d, -(s.radius - delta) / d, 0.0});

  RigidObstacle p;
  p.kind = RigidObstacle::Kind::plane;
  ASSERT_TRUE(p.gap({0.3, -2e-6, 0.1}, delta, g0, n));
  EXPECT_NEAR(g0, -delta + 2e-6, tol);
  expect_vec(n, {0.0, -1.0, 0.0});
}
