// The rolling study's kinematics (fe_stage/solve/rolling_kinematics.h) against closed forms:
// the co-rotating frame, the rigid journal's surface motion (zero for rolling without slip at
// the contact point), the paper's Eqs. 4–6 against the exact angle, the slip stages on a
// synthetic speed history.
#include "fe_stage/solve/rolling_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace clearjoint::fe::rolling;

namespace
{
  const double pi = std::acos(-1.0);

  // SPEC §2's joint: R_B = 10 mm, c_r = 0.5 mm, R_J = 9.5 mm; ω_B and the ramp of the rolling
  // study
  Motion spec_motion() { return Motion{12.56, 0.25, 1e-3, 0.5e-3, 10e-3, 9.5e-3}; }
}  // namespace

TEST(RollingKinematics, RotationAndFrame)
{
  const Vec3 r = rotate_z({1.0, 0.0, 2.0}, 0.5 * pi);
  EXPECT_NEAR(r[0], 0.0, 1e-15);  // round-off of cos(π/2)
  EXPECT_NEAR(r[1], 1.0, 1e-15);
  EXPECT_EQ(r[2], 2.0);

  const Motion m = spec_motion();
  EXPECT_DOUBLE_EQ(m.delta(0.125), 0.5e-3);
  EXPECT_DOUBLE_EQ(m.delta(0.5), 1e-3);  // held after the ramp
  EXPECT_DOUBLE_EQ(m.delta(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(m.rolling_rate(0.0), 12.56 * 10.0 / 9.5);   // first touch: at R_B
  EXPECT_DOUBLE_EQ(m.rolling_rate(0.25), 12.56 * 11.0 / 9.5);  // pushed 1 mm into the bore
  EXPECT_DOUBLE_EQ(m.slip_speed(0.25, 0.0), 12.56 * 11e-3);
  // the axis seen from the frame turned by φ: fixed = R(φ)·frame
  const double t = 0.1;
  const Vec3 f = m.centre_frame(t), back = rotate_z(f, m.phi(t));
  const Vec3 c = m.centre_fixed(t);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(back[k], c[k], 1e-18);  // 1e-15 relative to |c| ≈ 1e-3 m
}

TEST(RollingKinematics, SurfaceStepIsZeroAtTheContactPointWhenRolling)
{
  // The journal's axis fixed, the journal turning by Δψ in the frame: the surface point that
  // faces n moved along the circle; |d| = 2 R_J sin(Δψ/2), tangent at the mid-angle.
  const double R_J = 0.01, dpsi = 0.2;
  const Vec3 c{0.0, -1e-3, 0.0};
  const Vec3 n{0.0, -1.0, 0.0};
  const Vec3 d = journal_surface_step(c, c, R_J, n, dpsi);
  EXPECT_NEAR(std::hypot(d[0], d[1]), 2.0 * R_J * std::sin(0.5 * dpsi), 1e-17);
  EXPECT_EQ(d[2], 0.0);
  // a pure translation of the axis moves every surface point by it
  const Vec3 c1{2e-6, -1.003e-3, 0.0};
  const Vec3 tr = journal_surface_step(c, c1, R_J, n, 0.0);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(tr[k], c1[k] - c[k], 1e-17);  // round-off of c + R_J n, |R_J n| = 1e-2 m
  // Rolling without slip at the deepest point: in the frame the axis turns with −ω_B at the
  // distance e = c_r + δ and the journal by Δψ = (γ̇ − ω_B)Δt, so the journal's point at the
  // contact moves by [γ̇ R_J − ω_B (e + R_J)] Δt = [γ̇ R_J − ω_B (R_B + δ)] Δt to first
  // order: zero at rolling_rate(t), and −ω_B δ Δt at the nominal ω_B R_B / R_J.
  const Motion m = spec_motion();
  const double dt = 1e-6, t = 0.26;  // after the ramp: δ = 1 mm, the axis stands still
  const Vec3 c0f = m.centre_frame(t), c1f = m.centre_frame(t + dt);
  const Vec3 nc = rotate_z({0.0, -1.0, 0.0}, -m.phi(t + dt));  // contact direction in frame
  const Vec3 dr = journal_surface_step(c0f, c1f, m.R_J, nc, (m.rolling_rate(t) - m.omega_B) * dt);
  // first order would be ω_B R_B Δt ≈ 1.3e-7 m; what is left is O(ω² R Δt²) ≈ 2e-12 m
  EXPECT_LT(std::hypot(dr[0], dr[1]), 1e-11);
  const double nominal = m.omega_B * m.R_B / m.R_J;
  const Vec3 dn = journal_surface_step(c0f, c1f, m.R_J, nc, (nominal - m.omega_B) * dt);
  EXPECT_NEAR(std::hypot(dn[0], dn[1]), m.omega_B * m.delta(t) * dt, 1e-11);
}

TEST(RollingKinematics, PaperAnglesMatchTheExactRotation)
{
  // Eq. 4–5: a point on a circle of radius R turned by θ moved by |U| = 2R sin(θ/2)
  const double R = 10e-3;
  for (const double theta : {1e-4, 0.3, 1.0, 2.5, pi})
    {
      const Vec3 X{0.0, -R, 0.0};
      const Vec3 x = rotate_z(X, theta);
      const double got = paper_angle({x[0] - X[0], x[1] - X[1], 0.0}, R);
      EXPECT_NEAR(got, theta, 1e-7) << "theta " << theta;  // asin near 1 loses ~√eps at π
    }
}

// Issue 30 item 5: past half a turn the chord folds back (a point turned by 3.3 rad has the
// chord of 2π − 3.3); unwrapped by continuity from the previous step's angle, the paper's
// angle follows the exact rotation through several turns, forwards and backwards.
TEST(RollingKinematics, PaperAngleUnwrapsPastHalfATurn)
{
  const double R = 10e-3;
  const Vec3 X{0.0, -R, 0.0};
  for (const double rate : {0.21, -0.37})  // [rad] per step (the paper's case: ~0.2)
    {
      double unwrapped = 0.0;
      for (int step = 1; step <= 60; ++step)  // to 12.6 and −22 rad: several turns
        {
          const double theta = rate * step;
          const Vec3 x = rotate_z(X, theta);
          const double chord = paper_angle({x[0] - X[0], x[1] - X[1], 0.0}, R);
          EXPECT_LE(chord, pi + 1e-12);                            // the fold itself
          const bool positive = X[0] * x[1] - X[1] * x[0] >= 0.0;  // sin θ from the radii
          unwrapped = unwrap_paper_angle(chord, positive, unwrapped);
          // 1e-7: the chord's own accuracy near a half turn (asin near 1, previous test)
          EXPECT_NEAR(unwrapped, theta, 1e-7) << "step " << step << ", rate " << rate;
        }
    }
  EXPECT_DOUBLE_EQ(unwrap_paper_angle(0.5, true, 0.0), 0.5);  // below half a turn: the chord
}

TEST(RollingKinematics, SlipStagesOnASyntheticHistory)
{
  // v = 1 until 0.1 s, falling linearly to 0.02 by 0.2 s, then 0.02: the fall crosses 0.5 at
  // t = 0.1 + 0.1·(0.5/0.98) and the band ±0.05 about 0.02 is entered at 0.2 − 0.1·(0.05/0.98)
  std::vector<double> t, v;
  for (int i = 0; i <= 300; ++i)
    {
      const double ti = 1e-3 * i;
      t.push_back(ti);
      v.push_back(ti < 0.1 ? 1.0 : ti < 0.2 ? 1.0 - 0.98 * (ti - 0.1) / 0.1 : 0.02);
    }
  const SlipStages s = slip_stages(t, v);
  ASSERT_TRUE(s.found);
  EXPECT_DOUBLE_EQ(s.v_max, 1.0);
  EXPECT_DOUBLE_EQ(s.v_final, 0.02);
  EXPECT_NEAR(s.end_of_slip, 0.1 + 0.1 * 0.5 / 0.98, 1.01e-3);  // one sample of 1 ms
  EXPECT_NEAR(s.settled, 0.2 - 0.1 * 0.05 / 0.98, 1.01e-3);
  EXPECT_FALSE(slip_stages({0.0, 1.0}, {1.0, 1.0}).found);            // too short
  EXPECT_FALSE(slip_stages({0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}).found);  // no slip at all
  // the speed rises to its largest value at the end and never falls: no stage is located
  // (before, both stages were reported at the last sample)
  EXPECT_FALSE(slip_stages({0.0, 1.0, 2.0, 3.0}, {0.0, 0.2, 0.25, 0.3}).found);
  EXPECT_FALSE(slip_stages({0.0, 1.0, 2.0, 3.0}, {0.0, 0.3, 0.2, 0.25}).found);  // wanders
}

TEST(RollingKinematics, RigidSpinGivesNoStrainInTheCoRotatingFrame)
{
  // Issue 13 item 3: a rigid spin of a free body gives zero stress. The bearing is computed in
  // its co-rotating frame: a point at x = R(φ)·X in the fixed frame is at X again in the
  // frame, so the displacement, its gradient and the small strain are zero to round-off for
  // any φ. The same spin read as a small displacement in the fixed frame, u = (R(φ) − I)·X,
  // has the strain sym ∇u = (cos φ − 1) in x and y: −2 at half a turn — why small strain
  // needs the frame. Gradient by central differences over a 1 mm cell of the bearing.
  const double h = 1e-3;
  for (const double phi : {1e-3, 0.5, 1.0, 2.0, 0.5 * 12.56 * 0.25 * 2.0})  // up to π
    {
      double eps_frame = 0.0, eps_fixed_xx = 0.0;
      const Vec3 X{0.002, -0.0105, 0.003};
      for (int k = 0; k < 2; ++k)
        {
          Vec3 a = X, b = X;
          a[k] -= h;
          b[k] += h;
          const Vec3 ya = rotate_z(rotate_z(a, phi), -phi), yb = rotate_z(rotate_z(b, phi), -phi);
          for (int c = 0; c < 3; ++c)  // ∂u_c/∂X_k with u = y − X, in the frame
            eps_frame = std::max(eps_frame, std::abs(((yb[c] - b[c]) - (ya[c] - a[c])) / (2 * h)));
          if (k == 0)
            eps_fixed_xx = ((rotate_z(b, phi)[0] - b[0]) - (rotate_z(a, phi)[0] - a[0])) / (2 * h);
        }
      EXPECT_LT(eps_frame, 1e-12) << "phi " << phi;  // round-off of two rotations / 2h
      EXPECT_NEAR(eps_fixed_xx, std::cos(phi) - 1.0, 1e-9) << "phi " << phi;
    }
}

TEST(RollingKinematics, SpinRunawayIsTenTimesTheRollingRateInEitherSense)
{
  const Motion m = spec_motion();
  const double t = 0.1, roll = m.rolling_rate(t);  // 13.2… rad/s at δ(0.1 s)
  EXPECT_FALSE(m.spin_ran_away(t, roll));
  EXPECT_FALSE(m.spin_ran_away(t, 0.0));  // a frictionless journal's
  EXPECT_FALSE(m.spin_ran_away(t, -9.9 * roll));
  EXPECT_TRUE(m.spin_ran_away(t, 10.1 * roll));
  EXPECT_FALSE(m.spin_ran_away(t, -90.7));  // μ = 5 on the coarse ring: ~6.5 times, not yet
  EXPECT_TRUE(m.spin_ran_away(t, -170.4));  // its next step, where the run stops
  Motion at_rest = m;
  at_rest.omega_B = 1e-6;  // the bearing nearly at rest: the bound scales with it
  EXPECT_TRUE(at_rest.spin_ran_away(t, 1e-3));
  EXPECT_FALSE(at_rest.spin_ran_away(t, at_rest.rolling_rate(t)));
}
