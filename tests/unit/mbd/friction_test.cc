#include "mbd_stage/friction.h"

#include <gtest/gtest.h>

using namespace clearjoint::mbd;

TEST(Friction, AmbrosioRampAndBound)
{
  const CoulombFriction f{0.1, 1e-4, 1e-3};
  EXPECT_EQ(f.correction(0.0), 0.0);
  EXPECT_EQ(f.correction(1e-4), 0.0);
  EXPECT_NEAR(f.correction(5.5e-4), 0.5, 1e-12);
  EXPECT_EQ(f.correction(2e-3), 1.0);
  const Vector3 F = f.force(100.0, Vector3(0.3, -0.4, 0.0));  // N, m/s
  EXPECT_NEAR(F.norm(), 10.0, 1e-12);                          // μ·F_n
  EXPECT_LT(F.dot(Vector3(0.3, -0.4, 0.0)), 0.0);              // opposes sliding
}

TEST(Friction, ContinuousThroughZeroTangentialVelocity)
{
  // Sweep v_T through 0 along a line: the force never jumps by more than the ramp slope times
  // the sweep step (μ·F_n/(v1 − v0) · Δv), and is zero at v_T = 0.
  const CoulombFriction f{0.5, 1e-4, 1e-3};
  const double F_n = 1000.0, dv = 1e-6;  // N, m/s
  const double max_jump = f.mu * F_n / (f.v1 - f.v0) * dv * 1.0001;
  Vector3 prev = f.force(F_n, Vector3(-3e-3, -0.2 * 3e-3, 0));
  EXPECT_EQ(f.force(F_n, Vector3::Zero()).norm(), 0.0);
  for (double v = -3e-3 + dv; v <= 3e-3; v += dv)
  {
    const Vector3 F = f.force(F_n, Vector3(v, 0.2 * v, 0));
    EXPECT_LE((F - prev).norm(), max_jump * std::sqrt(1.04) + 1e-12) << "v = " << v;
    EXPECT_LE(F.norm(), f.mu * F_n * (1 + 1e-12));
    prev = F;
  }
}
