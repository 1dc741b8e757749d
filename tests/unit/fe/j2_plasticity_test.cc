// J2 radial return (fe_stage/material/j2_plasticity.h) against closed forms: uniaxial stress
// along a hardening table (the lateral strains found by Newton with the consistent tangent,
// whose quadratic convergence is asserted), simple shear with elastic unloading and reverse
// yielding, the consistent tangent against central differences, plastic work ≥ 0, trial/commit
// semantics and the bad-input messages.
#include "fe_stage/material/j2_plasticity.h"

#include "common/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace clearjoint::fe;

namespace
{
  const double E  = 207e9;
  const double nu = 0.3;

  /// A table with slopes 1000 MPa, 0 (plateau), 250 MPa and a 250 MPa tail: the return must
  /// walk across segments, including one where H = 0.
  HardeningTable uneven_table()
  {
    return HardeningTable({{0.0, 200e6}, {0.01, 210e6}, {0.05, 210e6}, {0.45, 310e6}},
                          "material.hardening");
  }

  /// Root of a monotone increasing function on [lo, hi] by bisection (the tests' independent
  /// solver for the closed forms; 200 halvings reach the double resolution of any bracket).
  double bisect(const std::function<double(double)> &g, double lo, double hi)
  {
    for (int i = 0; i < 200; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        (g(mid) < 0 ? lo : hi) = mid;
      }
    return 0.5 * (lo + hi);
  }

  /// Uniaxial stress: ε11 prescribed, the other five strain components found by Newton so
  /// that σ22 = σ33 = σ23 = σ13 = σ12 = 0. Returns the response; `residuals` gets |σ_rest|
  /// per Newton iteration (the first entry before any update).
  J2Response uniaxial(const J2Plasticity &m, J2History &h, double eps11, Vector6 &e,
                      std::vector<double> &residuals)
  {
    e(0) = eps11;
    residuals.clear();
    J2Response r;
    for (int it = 0; it < 25; ++it)
      {
        r = m.evaluate(voigt_to_strain(e), h);
        EXPECT_TRUE(r.status.converged);
        const Vector6 s  = stress_to_voigt(r.stress);
        const auto    sr = s.tail<5>();
        residuals.push_back(sr.norm());
        // 1e-4 Pa = 1e-12 of σ_y: the stresses are sums of terms of size K·ε ~ 1e9 Pa that
        // carry rounding of ~1e-7 Pa, so this is round-off level with margin.
        if (sr.norm() <= 1e-4)
          return r;
        const Eigen::Matrix<double, 5, 5> Crr = r.tangent.bottomRightCorner<5, 5>();
        e.tail<5>() -= Crr.lu().solve(sr);
      }
    ADD_FAILURE() << "uniaxial Newton did not converge";
    return r;
  }

  void uniaxial_along_table(const HardeningTable &table, double deps, double eps_max)
  {
    const J2Plasticity m(E, nu, table);
    J2History          h;
    Vector6            e = Vector6::Zero();
    std::vector<double> res;
    int                 worst_iterations = 0;
    for (double eps11 = deps; eps11 <= eps_max + 1e-15; eps11 += deps)
      {
        const double     alpha_n = h.committed.alpha;
        const J2Response r       = uniaxial(m, h, eps11, e, res);
        worst_iterations         = std::max(worst_iterations, static_cast<int>(res.size()) - 1);
        // The return's local Newton: one step per table segment entered, plus one.
        if (r.plastic)
          EXPECT_LE(r.status.iterations,
                    static_cast<int>(table.segment(h.trial.alpha) - table.segment(alpha_n)) + 1);
        // Closed form: ε11 = σ_y(α)/E + α on the plastic branch (α = ε_p11), else σ = E ε11.
        const double sy0   = table.yield_stress(0.0);
        double       alpha = 0.0, sigma = E * eps11;
        if (E * eps11 > sy0)
          {
            alpha = bisect([&](double a) { return table.yield_stress(a) / E + a - eps11; }, 0.0,
                           eps11);
            sigma = table.yield_stress(alpha);
          }
        // 1e-9 relative: the closed-form α comes from bisection to ~1e-16 and the Newton
        // residual is 1e-4 Pa; the slack covers the conditioning 1/(E + H).
        EXPECT_NEAR(r.stress(0, 0), sigma, 1e-9 * sigma) << "eps11 = " << eps11;
        EXPECT_NEAR(h.trial.alpha, alpha, 1e-12 + 1e-9 * alpha) << "eps11 = " << eps11;
        EXPECT_NEAR(h.trial.eps_p(0, 0), alpha, 1e-12 + 1e-9 * alpha);
        EXPECT_NEAR(h.trial.eps_p(1, 1), -alpha / 2, 1e-12 + 1e-9 * alpha);
        // Lateral strain: elastic contraction plus incompressible plastic flow.
        EXPECT_NEAR(e(1), -nu * sigma / E - alpha / 2, 1e-12 + 1e-9 * alpha);
        EXPECT_NEAR(e(2), e(1), 1e-12);
        h.commit();
      }
    // Newton with the consistent tangent: a handful of iterations per increment even when an
    // increment crosses several table segments (a continuum tangent needs tens).
    EXPECT_LE(worst_iterations, 6);
  }
} // namespace

TEST(J2Plasticity, UniaxialStressAlongSpecTable)
{
  // Increments of 0.013 cross the 0.1-wide segments of the SPEC table every few steps.
  uniaxial_along_table(HardeningTable::spec_default(), 0.013, 0.6);
}

TEST(J2Plasticity, UniaxialStressAcrossUnevenTableInBigSteps)
{
  // 0.07 per step: one step jumps from the first segment over the plateau into the third.
  uniaxial_along_table(uneven_table(), 0.07, 0.7);
  // And in small steps through the plateau (H = 0).
  uniaxial_along_table(uneven_table(), 0.002, 0.08);
}

TEST(J2Plasticity, UniaxialStressPerfectPlasticAndHeldTail)
{
  // One point: perfectly plastic (σ = σ_y, α = ε11 − σ_y/E).
  uniaxial_along_table(HardeningTable({{0.0, 250e6}}, "material.hardening"), 0.01, 0.1);
  // Abaqus's convention beyond the last point: σ_y held, H = 0 past ε_p = 0.1.
  uniaxial_along_table(HardeningTable({{0.0, 200e6}, {0.1, 300e6}}, "material.hardening", "",
                                      HardeningTable::Beyond::hold_last),
                       0.03, 0.3);
}

TEST(J2Plasticity, MixedNewtonConvergesQuadratically)
{
  // Uniaxial stress in the lateral directions is affine within a segment (the flow direction
  // does not change), so Newton ends in one step there. A non-proportional step shows the
  // order: after uniaxial yielding, γ12 is added with ε11 and γ12 prescribed and the other four
  // stresses held at zero; the flow direction then rotates and the problem is nonlinear.
  const HardeningTable table = HardeningTable::spec_default();
  const J2Plasticity   m(E, nu, table);
  J2History            h;
  Vector6              e = Vector6::Zero();
  std::vector<double>  res;
  uniaxial(m, h, 0.004, e, res); // just past first yield
  h.commit();
  res.clear();
  e(0) = 0.006;
  e(5) = 0.01;
  const std::array<int, 4> free_components{1, 2, 3, 4};
  for (int it = 0; it < 25; ++it)
    {
      const J2Response r = m.evaluate(voigt_to_strain(e), h);
      ASSERT_TRUE(r.status.converged);
      ASSERT_TRUE(r.plastic);
      const Vector6 s = stress_to_voigt(r.stress);
      Eigen::Vector4d sr;
      Eigen::Matrix4d Crr;
      for (int a = 0; a < 4; ++a)
        {
          sr(a) = s(free_components[a]);
          for (int b = 0; b < 4; ++b)
            Crr(a, b) = r.tangent(free_components[a], free_components[b]);
        }
      res.push_back(sr.norm());
      if (sr.norm() <= 1e-4) // round-off level, as in uniaxial()
        break;
      const Eigen::Vector4d dx = Crr.lu().solve(sr);
      for (int a = 0; a < 4; ++a)
        e(free_components[a]) -= dx(a);
    }
  std::cout << "mixed Newton |sigma_free| [Pa] per iteration:";
  for (double r : res)
    std::cout << " " << r;
  std::cout << "\n";
  ASSERT_GE(res.size(), 3u);
  EXPECT_LE(res.back(), 1e-4);
  EXPECT_LE(res.size(), 8u);
  // Quadratic: r_{k+1} ≤ C r_k² with C = 10/σ_y (relative residuals square, a factor 10 of
  // slack for the curvature of the return map) while r_{k+1} is above round-off (1e-4 Pa).
  const double sy      = table.yield_stress(0.0);
  int          checked = 0;
  for (std::size_t k = 0; k + 1 < res.size(); ++k)
    if (res[k + 1] > 1e-4)
      {
        EXPECT_LE(res[k + 1], 10.0 * res[k] * res[k] / sy) << "iteration " << k;
        ++checked;
      }
  EXPECT_GE(checked, 1);
}

TEST(J2Plasticity, SimpleShearLoadUnloadReverse)
{
  const HardeningTable table = uneven_table();
  const J2Plasticity   m(E, nu, table);
  const double         G = m.shear_modulus();
  for (const int n_steps : {1, 7, 100}) // one step to γ_max equals many (radial path)
    {
      J2History    h;
      const double gamma_max = 0.3;
      J2Response   r;
      Vector6      e = Vector6::Zero();
      for (int i = 1; i <= n_steps; ++i)
        {
          e(5) = gamma_max * i / n_steps;
          r    = m.evaluate(voigt_to_strain(e), h);
          ASSERT_TRUE(r.status.converged);
          h.commit();
        }
      // Closed form: τ = σ_y(α)/√3 and γ = τ/G + √3 α (γ_p = 2ε_p12 = √3 α).
      const double a_max = bisect(
        [&](double a) { return table.yield_stress(a) / (std::sqrt(3.0) * G) + std::sqrt(3.0) * a -
                               gamma_max; },
        0.0, gamma_max);
      const double tau_max = table.yield_stress(a_max) / std::sqrt(3.0);
      EXPECT_NEAR(r.stress(0, 1), tau_max, 1e-9 * tau_max) << n_steps << " steps";
      EXPECT_NEAR(h.committed.alpha, a_max, 1e-12) << n_steps << " steps";
      // Only shear: the other stress components vanish (1e-6 Pa: round-off of 1e9-size terms).
      EXPECT_NEAR(r.stress(0, 0), 0.0, 1e-6);
      EXPECT_NEAR(r.stress(1, 2), 0.0, 1e-6);

      // Elastic unloading by Δ: τ drops by GΔ, α unchanged, no plastic work, elastic tangent.
      const double d = 1e-3;
      e(5)           = gamma_max - d;
      r              = m.evaluate(voigt_to_strain(e), h);
      ASSERT_TRUE(r.status.converged);
      EXPECT_FALSE(r.plastic);
      EXPECT_NEAR(r.stress(0, 1), tau_max - G * d, 1e-9 * tau_max);
      EXPECT_EQ(h.trial.alpha, a_max == h.committed.alpha ? a_max : h.committed.alpha);
      EXPECT_EQ(r.plastic_work, 0.0);
      EXPECT_NEAR((r.tangent - m.elastic_tangent()).norm(), 0.0, 1e-6 * G);
      h.commit();

      // Reverse yielding (isotropic hardening: at τ = −σ_y(α)/√3). From γ_p,max = √3 α_max,
      // γ = −σ_y(α)/(√3 G) + γ_p,max − √3(α − α_max).
      const double gp_max  = std::sqrt(3.0) * a_max;
      const double gamma_r = -0.05;
      e(5)                 = gamma_r;
      r                    = m.evaluate(voigt_to_strain(e), h);
      ASSERT_TRUE(r.status.converged);
      EXPECT_TRUE(r.plastic);
      const double a_r = bisect(
        [&](double a) { return table.yield_stress(a) / (std::sqrt(3.0) * G) - gp_max +
                               std::sqrt(3.0) * (a - a_max) + gamma_r; },
        a_max, 1.0);
      EXPECT_NEAR(r.stress(0, 1), -table.yield_stress(a_r) / std::sqrt(3.0), 1e-9 * tau_max);
      EXPECT_NEAR(h.trial.alpha, a_r, 1e-12);
    }
}

TEST(J2Plasticity, ConsistentTangentMatchesCentralDifferences)
{
  const HardeningTable table = uneven_table();
  const J2Plasticity   m(E, nu, table);
  std::mt19937         rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int n_plastic = 0, n_elastic = 0;
  std::vector<int> plastic_on_segment(table.n_points(), 0);
  // Strain sizes chosen so the solutions land on every segment of the table: the steep first
  // one, the plateau, the 250 MPa one and the tail.
  const double scales[4] = {0.004, 0.02, 0.15, 0.5};
  for (int sample = 0; sample < 80; ++sample)
    {
      // A committed plastic history, then a random strain step that may or may not yield.
      const double scale = scales[(sample / 2) % 4];
      J2History h;
      Vector6   e0;
      for (int I = 0; I < 6; ++I)
        e0(I) = scale * u(rng);
      ASSERT_TRUE(m.evaluate(voigt_to_strain(e0), h).status.converged);
      h.commit();
      // Even samples load further (mostly plastic); odd ones scale the elastic strain by 0.8
      // (trial q* = 0.8 σ_y: an elastic unloading step).
      Vector6 e = e0;
      if (sample % 2 == 0)
        for (int I = 0; I < 6; ++I)
          e(I) += 0.3 * scale * u(rng);
      else
        e = e0 - 0.2 * (e0 - strain_to_voigt(h.committed.eps_p));
      const J2Response r = m.evaluate(voigt_to_strain(e), h);
      ASSERT_TRUE(r.status.converged);
      const double a0 = h.trial.alpha;
      // Central differences need a smooth neighbourhood: skip samples whose solution lies
      // within 1e-6 of a table point (the kink) or of the yield surface (counted below, so a
      // run that skips everything fails).
      const std::size_t k   = table.segment(a0);
      const double      d_k = std::min(a0 - table.points()[k].eps_p, table.segment_end(k) - a0);
      if (r.plastic && d_k < 1e-6)
        continue;
      if (!r.plastic && std::abs(std::sqrt(1.5) * (r.stress - r.stress.trace() / 3 *
                                                   Eigen::Matrix3d::Identity()).norm() -
                                 table.yield_stress(a0)) < 1e-3 * table.yield_stress(a0))
        continue;
      // h = 1e-8: the stress rounding (~1e-7 Pa) over 2h gives ~5 Pa error on entries of
      // size 1e11; the truncation error h²·σ''' is far below that.
      const double step = 1e-8;
      Matrix6      C_fd;
      for (int J = 0; J < 6; ++J)
        {
          Vector6 ep = e, em = e;
          ep(J) += step;
          em(J) -= step;
          J2History hp = h, hm = h;
          const Vector6 sp = stress_to_voigt(m.evaluate(voigt_to_strain(ep), hp).stress);
          const Vector6 sm = stress_to_voigt(m.evaluate(voigt_to_strain(em), hm).stress);
          C_fd.col(J)      = (sp - sm) / (2 * step);
        }
      // 1e-6 of the largest modulus: far above the ~5e-11 difference noise, far below any
      // wrong term (the plastic correction 2Gθ̄ is ~0.5–1 of G).
      EXPECT_LE((C_fd - r.tangent).cwiseAbs().maxCoeff(), 1e-6 * r.tangent.cwiseAbs().maxCoeff())
        << "sample " << sample << (r.plastic ? " (plastic)" : " (elastic)");
      EXPECT_LE((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(),
                1e-12 * r.tangent.cwiseAbs().maxCoeff());
      (r.plastic ? n_plastic : n_elastic)++;
      if (r.plastic)
        ++plastic_on_segment[k];
    }
  EXPECT_GE(n_plastic, 20);
  EXPECT_GE(n_elastic, 20);
  for (std::size_t k = 0; k < table.n_points(); ++k)
    EXPECT_GE(plastic_on_segment[k], 1) << "no plastic sample on segment " << k;
}

TEST(J2Plasticity, PlasticWorkIsNonNegativeOnACyclicPath)
{
  const HardeningTable table = uneven_table();
  const J2Plasticity   m(E, nu, table);
  J2History            h;
  std::mt19937         rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector6 e = Vector6::Zero();
  double  total = 0.0;
  int     n_plastic = 0;
  for (int i = 0; i < 300; ++i)
    {
      for (int I = 0; I < 6; ++I)
        e(I) = 0.9 * e(I) + 0.004 * u(rng); // a wandering, reversing path
      const double     a_n = h.committed.alpha;
      const J2Response r   = m.evaluate(voigt_to_strain(e), h);
      ASSERT_TRUE(r.status.converged);
      EXPECT_GE(r.plastic_work, 0.0);
      EXPECT_GE(h.trial.alpha, a_n);
      // σ_{n+1}:Δε_p = σ_y(α_{n+1})·Δα (q = σ_y on the surface); 1e-9: rounding of q.
      EXPECT_NEAR(r.plastic_work, table.yield_stress(h.trial.alpha) * (h.trial.alpha - a_n),
                  1e-9 * table.yield_stress(h.trial.alpha) * (h.trial.alpha - a_n) + 1e-30);
      // The plastic strain stays deviatoric.
      EXPECT_NEAR(h.trial.eps_p.trace(), 0.0, 1e-15);
      total += r.plastic_work;
      n_plastic += r.plastic;
      h.commit();
    }
  EXPECT_GT(n_plastic, 30);
  EXPECT_GT(total, 0.0);
}

TEST(J2Plasticity, TrialDoesNotTouchCommitted)
{
  const J2Plasticity m(E, nu, HardeningTable::spec_default());
  J2History          h;
  const Eigen::Matrix3d eps = voigt_to_strain((Vector6() << 0.01, -0.002, 0, 0, 0, 0.004).finished());
  const J2Response   r1 = m.evaluate(eps, h);
  ASSERT_TRUE(r1.plastic);
  EXPECT_EQ(h.committed.alpha, 0.0);
  EXPECT_TRUE(h.committed.eps_p.isZero(0.0));
  const J2Response r2 = m.evaluate(eps, h); // a cut step re-evaluates from `committed`
  EXPECT_EQ((r1.stress - r2.stress).norm(), 0.0);
  h.commit();
  // Re-evaluating the converged strain after commit is elastic (on the surface, no new flow).
  const J2Response r3 = m.evaluate(eps, h);
  EXPECT_FALSE(r3.plastic);
  EXPECT_NEAR((r3.stress - r1.stress).norm(), 0.0, 1e-6);
}

TEST(J2Plasticity, BadInput)
{
  const HardeningTable t = HardeningTable::spec_default();
  using clearjoint::test_support::input_error_of;
  const std::string bad_E = input_error_of([&] { J2Plasticity m(-1.0, 0.3, t, "material"); });
  EXPECT_NE(bad_E.find("key 'material.E'"), std::string::npos) << bad_E;
  const std::string bad_nu = input_error_of([&] { J2Plasticity m(207e9, 0.5, t, "material"); });
  EXPECT_NE(bad_nu.find("key 'material.nu'"), std::string::npos) << bad_nu;
  const J2Plasticity m(E, nu, t);
  J2History          h;
  Eigen::Matrix3d    eps = Eigen::Matrix3d::Zero();
  eps(0, 0)              = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(m.evaluate(eps, h).status.converged);
}

TEST(J2Plasticity, VoigtConventionAndVonMises)
{
  // C_ijkl = C(voigt_of(i,j), voigt_of(k,l)) with no factors: σ_ij = Σ_kl C_ijkl ε_kl over all
  // nine (k, l) must equal the Voigt product, at a plastic state (non-trivial C).
  const J2Plasticity m(E, nu, HardeningTable::spec_default());
  J2History          h;
  const Vector6      e = (Vector6() << 0.01, -0.003, 0.002, 0.004, -0.001, 0.006).finished();
  const J2Response   r = m.evaluate(voigt_to_strain(e), h);
  ASSERT_TRUE(r.plastic);
  const Eigen::Matrix3d eps = voigt_to_strain(e);
  const Vector6         s_voigt = r.tangent * e;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      {
        double s = 0;
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            s += r.tangent(voigt_of(i, j), voigt_of(k, l)) * eps(k, l);
        // 1e-6 of |σ| ~ 1e9: the two sums round differently.
        EXPECT_NEAR(s, s_voigt(voigt_of(i, j)), 1e-6 * s_voigt.norm()) << i << j;
      }
  for (int I = 0; I < 6; ++I)
    EXPECT_EQ(voigt_of(voigt_index[I][0], voigt_index[I][1]), I);
  // von Mises: uniaxial σ → σ; pure shear τ → √3 τ; a pressure adds nothing.
  Eigen::Matrix3d u = Eigen::Matrix3d::Zero();
  u(0, 0)           = 250e6;
  EXPECT_NEAR(von_mises_stress(u), 250e6, 1e-6);
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  t(0, 1) = t(1, 0) = 100e6;
  EXPECT_NEAR(von_mises_stress(t + 5e8 * Eigen::Matrix3d::Identity()), std::sqrt(3.0) * 100e6, 1e-6);
  // On the yield surface after a plastic step: q = σ_y(α).
  EXPECT_NEAR(von_mises_stress(r.stress), m.hardening().yield_stress(h.trial.alpha),
              1e-9 * m.hardening().yield_stress(h.trial.alpha));
}
