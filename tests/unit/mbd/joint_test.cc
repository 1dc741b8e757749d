// Joint Jacobians D, Φ_t and the acceleration terms γ against finite differences of Φ along an
// exact rigid motion with constant v and ω' (so q̈-terms come only from γ) — STYLE.md: analytic
// derivatives against finite differences.
#include "mbd_stage/joint.h"

#include <gtest/gtest.h>

#include <random>

using namespace clearjoint::mbd;

namespace
{
  /// Body kinematics at time t for a motion with constant v_G and constant body-frame ω'.
  BodyKinematics advance(const BodyKinematics &k0, const double t)
  {
    BodyKinematics k = k0;
    k.r = k0.r + t * k0.v;
    const double wn = k0.w_B.norm();
    const Matrix3 A = k0.A * Eigen::AngleAxisd(t * wn, k0.w_B / wn).toRotationMatrix();
    k.A = A;
    k.e = euler_parameters_from_rotation(A);
    return k;
  }

  std::vector<BodyKinematics> random_bodies(std::mt19937 &rng)
  {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<BodyKinematics> b(2);
    for (auto &k : b)
    {
      k.r = Vector3(U(rng), U(rng), U(rng));
      k.e = euler_parameters_from_axis_angle(Vector3(U(rng), U(rng), U(rng)), 2 * U(rng));
      k.A = rotation_matrix(k.e);
      k.v = Vector3(U(rng), U(rng), U(rng));
      k.w_B = 3.0 * Vector3(U(rng), U(rng), U(rng));
    }
    return b;
  }

  void check_rows(const std::function<void(const KinematicsView &, double, std::vector<ConstraintRow> &)> &eval,
                  const std::vector<BodyKinematics> &b0, const double t0)
  {
    const double h = 1e-5;  // s; central differences, errors O(h²)·|Φ'''| ~ 1e-9
    Eigen::VectorXd u(12);
    u << b0[0].v, b0[0].w_B, b0[1].v, b0[1].w_B;
    std::vector<ConstraintRow> r0, rp, rm;
    std::vector<BodyKinematics> bp{advance(b0[0], h), advance(b0[1], h)},
      bm{advance(b0[0], -h), advance(b0[1], -h)};
    eval(KinematicsView(&b0), t0, r0);
    eval(KinematicsView(&bp), t0 + h, rp);
    eval(KinematicsView(&bm), t0 - h, rm);
    ASSERT_EQ(r0.size(), rp.size());
    for (std::size_t i = 0; i < r0.size(); ++i)
    {
      const double phi_dot_fd = (rp[i].phi - rm[i].phi) / (2 * h);
      const double phi_ddot_fd = (rp[i].phi - 2 * r0[i].phi + rm[i].phi) / (h * h);
      const double phi_dot = r0[i].D.dot(u) + r0[i].phi_t;
      // With u̇ = 0 along this motion, Φ̈ = −γ.
      EXPECT_NEAR(phi_dot, phi_dot_fd, 1e-7) << "row " << i;
      EXPECT_NEAR(-r0[i].gamma, phi_ddot_fd, 2e-3 * (1.0 + std::abs(phi_ddot_fd))) << "row " << i;
    }
  }
} // namespace

TEST(Joint, JacobiansAndGammaMatchFiniteDifferences)
{
  std::mt19937 rng(42);
  for (const JointType type : {JointType::revolute, JointType::translational, JointType::spherical,
                               JointType::fixed})
    for (int trial = 0; trial < 5; ++trial)
    {
      const auto b0 = random_bodies(rng);
      const Joint j("j", type, 0, 1, Vector3(0.1, 0.2, -0.3), Vector3(0.2, 1.0, 0.4),
                    KinematicsView(&b0));
      EXPECT_EQ(j.n_equations(), type == JointType::spherical ? 3 : (type == JointType::fixed ? 6 : 5));
      check_rows([&](const KinematicsView &k, double, std::vector<ConstraintRow> &rows) {
        j.evaluate(k, rows);
      }, b0, 0.0);
    }
}

TEST(Joint, DriverRowsMatchFiniteDifferencesIncludingTime)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial)
  {
    const auto b0 = random_bodies(rng);
    const Joint j("j", JointType::revolute, 0, 1, Vector3(0, 0, 0), Vector3(1, 0.3, 0),
                  KinematicsView(&b0));
    const Driver d("d", j, 4.0);
    check_rows([&](const KinematicsView &k, double t, std::vector<ConstraintRow> &rows) {
      d.evaluate(k, t, rows);
    }, b0, 0.37);
  }
}

TEST(Joint, ConstraintsVanishAtTheDefiningConfiguration)
{
  std::mt19937 rng(3);
  const auto b0 = random_bodies(rng);
  for (const JointType type : {JointType::revolute, JointType::translational, JointType::spherical,
                               JointType::fixed})
  {
    const Joint j("j", type, 0, 1, Vector3(0.5, -0.2, 0.1), Vector3(0, 0, 1), KinematicsView(&b0));
    std::vector<ConstraintRow> rows;
    j.evaluate(KinematicsView(&b0), rows);
    for (const auto &r : rows)
      EXPECT_NEAR(r.phi, 0.0, 1e-14);  // defined at this configuration: Φ(q0) = 0 to rounding
  }
}
