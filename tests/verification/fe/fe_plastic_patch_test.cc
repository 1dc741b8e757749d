// The elastoplastic patch test (issue 30): the rigid flat pushed δ into the block on rollers
// (free lateral faces, frictionless) leaves it in a homogeneous uniaxial stress state, which
// Q2 elements represent exactly. So the contact force must be the material point law's under
// the same load path — the small-strain J2 law (material/j2_plasticity.h) with ε = diag(e, −δ/H,
// e), and the finite-strain J2 law in the logarithmic strain space (material/finite_j2.h) with
// F = diag(a, 1 − δ/H, a) — where the lateral strain e (stretch a) makes the lateral stress
// vanish. This checks the elastoplastic quasi-static push (the material Newton iteration), and
// with finite kinematics the total-Lagrangian internal force (the first Piola stress on the
// reference configuration). The tangent is checked on its own (fe_finite_assembly_test): in
// this uniaxial state its geometric part is S/E ~ 1e-3 of it, and the Newton iteration took
// the same three iterations per increment without it (tried by hand).
#include "fe_test_util.h"

#include "fe_stage/material/finite_j2.h"
#include "fe_stage/material/j2_plasticity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  /// The root of a decreasing-or-increasing g on [lo, hi] by bisection (g(lo), g(hi) of
  /// opposite signs), to the last bits of x.
  double bisect(const std::function<double(double)> &g, double lo, double hi)
  {
    double g_lo = g(lo);
    EXPECT_LT(g_lo * g(hi), 0.0) << "the bracket does not hold a root";
    for (int i = 0; i < 200 && hi - lo > 1e-15 * std::abs(hi); ++i)
      {
        const double mid = 0.5 * (lo + hi);
        const double g_mid = g(mid);
        if ((g_mid < 0.0) == (g_lo < 0.0))
          lo = mid, g_lo = g_mid;
        else
          hi = mid;
      }
    return 0.5 * (lo + hi);
  }

  J2Plasticity scene_law(const FeScene &s)
  {
    return J2Plasticity(s.material.E, s.material.nu, hardening_table(s.material, s.source_file),
                        "material", s.source_file);
  }

  /// Full-block force [N] of the small-strain law, uniaxial stress, at each δ of the run.
  std::vector<double> small_strain_forces(const FeScene &s, const std::vector<double> &deltas)
  {
    const J2Plasticity law = scene_law(s);
    const double H = s.verification.block_height, W = s.verification.block_width;
    J2History history;
    std::vector<double> forces;
    for (const double delta : deltas)
      {
        const double e_y = -delta / H;
        auto strain = [&](const double e) {
          Eigen::Matrix3d eps = Eigen::Matrix3d::Zero();
          eps(0, 0) = eps(2, 2) = e;
          eps(1, 1) = e_y;
          return eps;
        };
        // the lateral strain lies between 0 and the incompressible −e_y/2
        const double e = bisect(
          [&](const double e) { return law.evaluate(strain(e), history).stress(0, 0); }, 0.0,
          -0.6 * e_y);
        const J2Response r = law.evaluate(strain(e), history);
        history.commit();
        forces.push_back(-r.stress(1, 1) * 4.0 * W * W);
      }
    return forces;
  }

  /// The same with the finite-strain law: the force is P_yy on the reference area.
  std::vector<double> finite_strain_forces(const FeScene &s, const std::vector<double> &deltas)
  {
    const FiniteJ2 law(scene_law(s));
    const double H = s.verification.block_height, W = s.verification.block_width;
    J2History history;
    std::vector<double> forces;
    for (const double delta : deltas)
      {
        const double stretch = 1.0 - delta / H;
        auto gradient = [&](const double a) {
          Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
          F(0, 0) = F(2, 2) = a;
          F(1, 1) = stretch;
          return F;
        };
        // the lateral stretch lies between 1 and the incompressible 1/√stretch (with margin)
        const double a = bisect(
          [&](const double a) { return law.evaluate(gradient(a), history).stress_pk1(0, 0); },
          1.0, 1.2 / std::sqrt(stretch));
        const FiniteJ2Response r = law.evaluate(gradient(a), history);
        EXPECT_TRUE(r.status.converged) << r.status.reason;
        history.commit();
        forces.push_back(-r.stress_pk1(1, 1) * 4.0 * W * W);
      }
    return forces;
  }

  std::vector<double> deltas_of(const RunResult &r)
  {
    std::vector<double> d;
    for (const auto &inc : r.increments)
      d.push_back(inc.delta);
    return d;
  }

  // The block of the rigid-flat patch test, coarse (its state is homogeneous: any mesh is
  // exact), frictionless, elastoplastic, pushed to 20 % of its height in 8 increments.
  const std::string plastic_patch = "study: patch\n"
                                    "contact: {mu: 0}\n"
                                    "loading: {delta_max: 4.0e-3, n_increments: 8}\n"
                                    "verification: {n_cells: 2, contact_refinements: 0}\n";
}  // namespace

TEST(FePlasticPatch, SmallStrainForceIsThePointLaws)
{
  const FeScene s = scene(plastic_patch + "material: {model: elastoplastic}\n");
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.increments.size(), 8u);
  // (no cuts: the point law below walks the same increments, and for J2 the result of a step
  // depends on its size only off proportional paths)
  const std::vector<double> expected = small_strain_forces(s, deltas_of(r));
  for (std::size_t k = 0; k < expected.size(); ++k)
    {
      std::printf("small strain, delta %.3g mm: F %.9g N, point law %.9g N\n",
                  1e3 * r.increments[k].delta, r.increments[k].force, expected[k]);
      // 1e-6: the material Newton stops at a correction of 1e-7 δ_max (4e-10 m against
      // displacements of ~1e-3 m), the linear solves at 1e-10; the point law's bisection is
      // exact to round-off
      EXPECT_NEAR(r.increments[k].force / expected[k], 1.0, 1e-6) << "increment " << k + 1;
    }
}

TEST(FePlasticPatch, FiniteStrainForceIsThePointLaws)
{
  const FeScene s = scene(plastic_patch + "material: {model: elastoplastic, kinematics: finite}\n");
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.increments.size(), 8u);
  const std::vector<double> expected = finite_strain_forces(s, deltas_of(r));
  const std::vector<double> small = small_strain_forces(s, deltas_of(r));
  for (std::size_t k = 0; k < expected.size(); ++k)
    {
      std::printf("finite strain, delta %.3g mm: F %.9g N, point law %.9g N (small strain "
                  "%.9g N)\n",
                  1e3 * r.increments[k].delta, r.increments[k].force, expected[k], small[k]);
      // 1e-6: as the small-strain test (the same Newton and linear tolerances)
      EXPECT_NEAR(r.increments[k].force / expected[k], 1.0, 1e-6) << "increment " << k + 1;
    }
  // At 20 % compression the two kinematics must differ by far more than the tolerance above
  // (P on the reference area against σ of a small-strain law whose strain is off by O(ε²)):
  // otherwise the finite path was not taken.
  EXPECT_GT(std::abs(expected.back() / small.back() - 1.0), 1e-2);
}
