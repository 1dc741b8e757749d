// Verification of the FE contact model against closed forms and invariances (SPEC §2, issue 3
// item 7). Tolerances carry their reason beside them.
#include "fe_test_util.h"

#include "common/log.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  // A coarse quarter model of the default joint: enough to exercise every part of the radial
  // study in seconds (about 3.5 k DoFs).
  const std::string coarse_radial =
    "contact: {mu: 0}\n"
    "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n"
    "loading: {journal: rigid, n_increments: 3}\n";
  // The same mesh with the deformable journal (two bodies, dual mortar by default).
  std::string coarse_two_body(const std::string &journal)
  {
    return "contact: {mu: 0}\n"
           "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n"
           "loading: {journal: " +
           journal + ", n_increments: 3}\n";
  }
}  // namespace

namespace
{
  /// Runs a Hertz scene (4 increments) and checks issue 3's limits: the fitted n within 0.03
  /// of 1.5 and K, compared at the Hertz exponent, within 3 % of (4/3) E* √R.
  RunResult run_and_check_hertz(const FeScene &s, const double E_star, const char *label)
  {
    const RunResult r = run(s);
    EXPECT_TRUE(r.complete) << r.message;
    EXPECT_EQ(r.increments.size(), 4u);
    if (!r.complete || r.increments.size() != 4u)
      return r;
    const auto [K_free, n] = fit_power_law(r);
    (void)K_free;  // in N/m^n: with n free, K moves ~7 % per 0.006 of n at δ ≈ 10 µm, so K is
                   // compared at the Hertz exponent: K = exp(mean(log F − 1.5 log δ))
    double mean_log_K = 0.0;
    for (const auto &i : r.increments)
      mean_log_K += (std::log(i.force) - 1.5 * std::log(i.delta)) / r.increments.size();
    const double K_hertz = 4.0 / 3.0 * E_star * std::sqrt(s.verification.sphere_radius);
    const double K_ratio = std::exp(mean_log_K) / K_hertz;
    ::testing::Test::RecordProperty("n", std::to_string(n));
    ::testing::Test::RecordProperty("K_over_K_hertz", std::to_string(K_ratio));
    std::printf("%s: n = %.5f, K/K_hertz = %.5f\n", label, n, K_ratio);
    EXPECT_NEAR(n, 1.5, 0.03);
    EXPECT_NEAR(K_ratio, 1.0, 0.03);
    return r;
  }
}  // namespace

// Rigid sphere on an elastic block (quarter model): Hertz, F = (4/3) E* √R δ^{3/2} with
// 1/E* = (1 − ν²)/E (only the block deforms). Issue 3: fitted n within 0.03 of 1.5, K (at
// n = 1.5) within 3 %. The block (20 mm) is 30x the largest contact radius (0.32 mm), so the finite-body
// correction is of order a/H ≈ 1.6 % at most; the contact zone has ≥ 8 cells across its radius.
TEST(FeHertz, RigidSphereOnBlockMatchesHertz)
{
  const FeScene s = scene("study: hertz\ncontact: {mu: 0}\n"
                          "loading: {delta_max: 1.0e-5, n_increments: 4}\n"
                          "verification: {n_cells: 8, contact_refinements: 5, "
                          "refine_radius: 0.5e-3}\n");
  run_and_check_hertz(s, s.material.E / (1.0 - s.material.nu * s.material.nu), "Hertz");
}

// The SPEC's same-material Hertz test: both bodies deform, 1/E* = 2(1 − ν²)/E. The indenter is
// a block whose bottom is Hertz's profile r²/2R near the contact (IndenterChart), meshed with
// 5 coarse cells per edge against the block's 6, so the contact surfaces do not match and are
// coupled by dual mortar. Pushed 10 µm at its top; the two 20 mm bodies add a finite-body
// compliance of order a/H ≈ 1.5 % (a ≤ 0.22 mm): limits of issue 3 (n ± 0.03, K ± 3 %).
TEST(FeHertz, SameMaterialTwoBodiesOnNonMatchingMeshesMatchHertz)
{
  const FeScene s = scene("study: hertz\ncontact: {mu: 0}\n"
                          "loading: {delta_max: 1.0e-5, n_increments: 4}\n"
                          "verification: {n_cells: 6, contact_refinements: 5, "
                          "refine_radius: 0.5e-3, indenter: deformable, indenter_n_cells: 5}\n");
  const RunResult r =
    run_and_check_hertz(s, s.material.E / (2.0 * (1.0 - s.material.nu * s.material.nu)),
                        "two-body Hertz");
  for (const auto &inc : r.increments)
    {
      // equilibrium: contact force = support reaction = reaction on the pushed top (CG 1e-10,
      // AMG; measured ≤ 2e-7)
      EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-6);
      EXPECT_NEAR(inc.force_load / inc.force, 1.0, 1e-6);
      EXPECT_LT(inc.max_penetration, 1e-9 * s.loading.delta_max);  // exact at active nodes
    }
}

// Two-body contact patch test: a block (H = 20 mm) pressed by a second block (H_i = 20 mm) of
// the same material, both on rollers with free lateral faces: uniaxial stress σ = E δ/(H + H_i)
// in both, which Q2 represents exactly. Matching meshes (4 | 4 cells per edge) and
// non-matching ones (4 | 3) with dual mortar; SPEC: pressure uniform within 0.1 % (matching)
// and 2 % (non-matching), total force exact.
TEST(FePatch, TwoBlocksMatchingAndNonMatchingMeshes)
{
  for (const unsigned int upper_cells : {4u, 3u})
    {
      const FeScene s = scene("study: patch\ncontact: {mu: 0}\n"
                              "loading: {delta_max: 1.0e-5, n_increments: 2}\n"
                              "verification: {n_cells: 4, contact_refinements: 0, "
                              "indenter: deformable, indenter_n_cells: " +
                              std::to_string(upper_cells) + "}\n");
      const RunResult r = run(s);
      ASSERT_TRUE(r.complete) << r.message;
      const auto &V = s.verification;
      const bool matching = upper_cells == V.n_cells;
      for (const auto &inc : r.increments)
        {
          const double p_exact = s.material.E * inc.delta / (V.block_height + V.indenter_height);
          const double F_exact = p_exact * 4.0 * V.block_width * V.block_width;
          // Matching: 1e-8 (solver tolerance 1e-10 plus summation). Non-matching: the mortar
          // integrals' quadrature error across master-face edges (≈ 2e-3 of a master nodal
          // force, mortar_test) perturbs the uniform state; measured 3.2e-8, limit 1e-6.
          EXPECT_NEAR(inc.force / F_exact, 1.0, matching ? 1e-8 : 1e-6) << upper_cells;
          EXPECT_NEAR(inc.force_load / F_exact, 1.0, matching ? 1e-8 : 1e-6) << upper_cells;
          const double tol = matching ? 1e-3 : 2e-2;  // SPEC §2
          EXPECT_NEAR(inc.pressure_min / p_exact, 1.0, tol) << upper_cells;
          EXPECT_NEAR(inc.pressure_max / p_exact, 1.0, tol) << upper_cells;
          EXPECT_EQ(inc.n_active, 81u);  // every node of the block's 4 x 4 Q2 top face
        }
    }
}

// Contact patch test: a rigid flat pushed δ into a block on rollers (free lateral faces) gives
// uniaxial stress σ = E δ/H exactly, which Q2 represents exactly: the total force must equal
// E δ/H · (2W)² to solver tolerance and the nodal pressure λ_i/w_i must be uniform.
TEST(FePatch, RigidFlatGivesExactForceAndUniformPressure)
{
  const FeScene s = scene("study: patch\ncontact: {mu: 0}\n"
                          "loading: {delta_max: 1.0e-5, n_increments: 2}\n"
                          "verification: {n_cells: 2, contact_refinements: 1}\n");
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  const auto &V = s.verification;
  for (const auto &inc : r.increments)
    {
      const double p_exact = s.material.E * inc.delta / V.block_height;
      const double F_exact = p_exact * 4.0 * V.block_width * V.block_width;
      // 1e-8: linear solver tolerance 1e-10 plus round-off of summing ~100 nodal forces
      EXPECT_NEAR(inc.force / F_exact, 1.0, 1e-8);
      EXPECT_NEAR(inc.force_support / F_exact, 1.0, 1e-8);
      // SPEC: uniform within 0.1 % on matching meshes
      EXPECT_NEAR(inc.pressure_min / p_exact, 1.0, 1e-3);
      EXPECT_NEAR(inc.pressure_max / p_exact, 1.0, 1e-3);
      EXPECT_EQ(inc.n_active, 81u);  // every node of the 4 x 4 Q2 top face (9 x 9)
    }
}

namespace
{
  /// Coulomb's law at every node of every converged increment (IncrementRecord's friction_*
  /// checks, from K u and the displacements).
  void expect_coulomb_holds(const RunResult &r, const double mu, const char *label)
  {
    for (const auto &f : r.increments)
      {
        if (f.n_active == 0)
          continue;
        std::printf("%s, delta = %.3g m: cone excess %.2e, slip-law error %.2e, direction "
                    "error %.2e (of mu*lambda_max)\n",
                    label, f.delta, f.friction_cone_excess, f.friction_slip_law_error,
                    f.friction_direction_error);
        // The Newton loop stops when |t_T − μλŵ| ≤ 1e-6 λ_max at every slipping node, i.e.
        // 1e-6/μ of μλ_max; a sticking node's |t_T| ≤ μλ is its classification.
        EXPECT_LE(f.friction_cone_excess, 1e-6 / mu);
        EXPECT_LE(f.friction_slip_law_error, 1e-6 / mu);
        // friction opposes the slip: 1 + cos(angle) ≈ angle²/2, the angle ≤ ~1e-3 rad
        EXPECT_LE(f.friction_direction_error, 1e-6);
      }
  }
}  // namespace

// Coulomb friction μ = 0.1 between journal and bore (two bodies, end_faces): the push makes
// the journal's surface and the bore slide against each other, friction resists it, so the
// joint gets stiffer — SPEC §2 (a peer model): by about 0.5 %. Equilibrium must still hold
// with the friction forces (contact = support = load), non-penetration stays exact, Coulomb's
// law holds at every node, and the converged state must not depend on the complementarity
// constant c (×0.1, ×10).
TEST(FeFriction, CoulombStiffensTheJointByAboutHalfAPercent)
{
  const RunResult frictionless = run(scene(coarse_two_body("end_faces")));
  FeScene s = scene(coarse_two_body("end_faces"));
  s.contact.mu = 0.1;
  const RunResult r = run(s);
  FeScene s10 = s, s01 = s, st = s;
  s10.contact.active_set_scale = 10.0;
  s01.contact.active_set_scale = 0.1;
  st.contact.tangential_scale = 0.3;  // friction's own constant c_T = 0.3 c
  const RunResult r10 = run(s10), r01 = run(s01), rt = run(st);
  ASSERT_TRUE(frictionless.complete && r.complete && r10.complete && r01.complete && rt.complete)
    << r.message << r10.message << r01.message << rt.message;
  ASSERT_EQ(r.increments.size(), frictionless.increments.size());
  for (std::size_t i = 0; i < r.increments.size(); ++i)
    {
      const auto &f = r.increments[i];
      const double change = f.force / frictionless.increments[i].force - 1.0;
      std::printf("delta = %.3g m: F = %.6g N, frictionless %.6g N (%+.3f %%), %u of %u slip, "
                  "c x10: %+.2e, c x0.1: %+.2e\n",
                  f.delta, f.force, frictionless.increments[i].force, 100.0 * change, f.n_slip,
                  f.n_active, r10.increments[i].force / f.force - 1.0,
                  r01.increments[i].force / f.force - 1.0);
      EXPECT_GT(change, 0.0);
      EXPECT_LT(change, 0.02);  // "about 0.5 %": a factor 4 of room for this coarse mesh
      EXPECT_GT(f.n_slip, 0u);
      // equilibrium with the friction forces: CG/GMRES to 1e-10, measured ~1e-9
      EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);
      EXPECT_NEAR(f.force_load / f.force, 1.0, 1e-6);
      EXPECT_LT(f.max_penetration, 1e-9 * s.loading.delta_max);
      // c steers the Newton path only; the converged states differ by the slip-law tolerance
      // (≤ 1e-6 of the largest nodal force per slipping node, a few 1e-7 of F summed) and the
      // linear solves' 1e-10: measured ≤ 5e-9. Issue 11 asks < 0.1 % for c ×10.
      EXPECT_NEAR(r10.increments[i].force / f.force, 1.0, 1e-6);
      EXPECT_NEAR(r01.increments[i].force / f.force, 1.0, 1e-6);
      EXPECT_NEAR(rt.increments[i].force / f.force, 1.0, 1e-6);
    }
  expect_coulomb_holds(r, 0.1, "mu = 0.1");
  expect_coulomb_holds(r10, 0.1, "mu = 0.1, c x10");
}

// The semi-smooth Newton method linearises the slip direction too, so it converges in a few
// iterations for large friction coefficients as well (the fixed-point iteration it replaced
// needed 9–11 per increment at μ = 0.1 here, and its cycle breakers made F depend on c).
// μ → 0 is the frictionless problem; F grows with μ.
TEST(FeFriction, SemiSmoothNewtonConvergesForLargeAndVanishingCoefficients)
{
  const RunResult frictionless = run(scene(coarse_two_body("end_faces")));
  ASSERT_TRUE(frictionless.complete) << frictionless.message;
  unsigned int iterations_frictionless = 0;
  for (const auto &f : frictionless.increments)
    iterations_frictionless += f.contact_iterations;
  std::vector<double> previous_force;
  for (const double mu : {1e-9, 0.1, 0.3, 0.5})
    {
      FeScene s = scene(coarse_two_body("end_faces"));
      s.contact.mu = mu;
      const RunResult r = run(s);
      ASSERT_TRUE(r.complete) << "mu = " << mu << ": " << r.message;
      ASSERT_EQ(r.increments.size(), frictionless.increments.size());
      unsigned int iterations = 0;
      for (std::size_t i = 0; i < r.increments.size(); ++i)
        {
          const auto &f = r.increments[i];
          iterations += f.contact_iterations;
          EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);  // as above
          if (mu < 1e-6)
            // friction forces of 1e-9 λ: F moves by ~1e-9 of itself (measured 1e-10)
            EXPECT_NEAR(f.force / frictionless.increments[i].force, 1.0, 1e-8);
          else if (!previous_force.empty())
            EXPECT_GT(f.force, previous_force[i]);
        }
      std::printf("mu = %g: %u active-set iterations (frictionless %u), F(delta_max) = %.8g N\n",
                  mu, iterations, iterations_frictionless, r.increments.back().force);
      // Issue 11's target is ≤ 3× the frictionless iterations on the default mesh; measured
      // ≤ 2.2× here. A return to linear convergence would take ≥ 5×.
      EXPECT_LE(iterations, 3 * iterations_frictionless);
      if (mu > 1e-6)
        expect_coulomb_holds(r, mu, ("mu = " + std::to_string(mu)).c_str());
      previous_force.clear();
      for (const auto &f : r.increments)
        previous_force.push_back(f.force);
    }
}

// Friction with hanging nodes inside the contact zone: a hanging node's share of the contact
// force reaches its masters, in the friction rows as in the evaluation, so Newton converges
// and Coulomb's law holds on the masters' forces.
TEST(FeFriction, HangingNodesInsideTheContactZone)
{
  FeScene s = scene(coarse_two_body("end_faces"));
  s.mesh.contact_refinements = 1;
  s.mesh.contact_window_deg = 20.0;  // the contact zone reaches ~30°
  s.contact.mu = 0.3;
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  for (const auto &f : r.increments)
    {
      EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);  // CG/GMRES to 1e-10
      EXPECT_NEAR(f.force_load / f.force, 1.0, 1e-6);
      EXPECT_LE(f.contact_iterations, 10u);  // measured 5–7: sets settle, then 2–3 Newton steps
    }
  expect_coulomb_holds(r, 0.3, "hanging, mu = 0.3");
}

// Dual mortar on the joint (contact.pairing: mortar): the bore's faces coupled to the
// deformable journal's curved surface by the weighted gap and the mortar coefficients, as if
// the meshes did not match. On the generated ray-matched mesh it must give node-to-node's
// force within issue 11's 0.05 %, frictionless and with friction, with equilibrium, exact
// (weighted) non-penetration and Coulomb's law; also with hanging nodes in the contact zone.
TEST(FeMortarJoint, MatchesNodeToNodeOnTheRayMatchedMesh)
{
  struct Case
  {
    const char *label;
    double mu;
    bool hanging;
  };
  for (const Case c : {Case{"frictionless", 0.0, false}, Case{"mu = 0.1", 0.1, false},
                       Case{"mu = 0.3, hanging nodes in the zone", 0.3, true}})
    {
      FeScene rays = scene(coarse_two_body("end_faces"));
      rays.contact.mu = c.mu;
      rays.contact.pairing = Contact::Pairing::node_to_node;
      if (c.hanging)
        {
          rays.mesh.contact_refinements = 1;
          rays.mesh.contact_window_deg = 20.0;  // the contact zone reaches ~30°
        }
      FeScene mortar = rays;
      mortar.contact.pairing = Contact::Pairing::mortar;
      const RunResult a = run(rays), b = run(mortar);
      ASSERT_TRUE(a.complete && b.complete) << c.label << ": " << a.message << b.message;
      ASSERT_EQ(a.increments.size(), b.increments.size());
      for (std::size_t i = 0; i < a.increments.size(); ++i)
        {
          const auto &f = b.increments[i];
          std::printf("%s, delta = %.3g m: F node-to-node %.8g N, mortar %.8g N (%+.2e), "
                      "%u vs %u iterations\n",
                      c.label, f.delta, a.increments[i].force, f.force,
                      f.force / a.increments[i].force - 1.0, a.increments[i].contact_iterations,
                      f.contact_iterations);
          EXPECT_NEAR(f.force / a.increments[i].force, 1.0, 5e-4);  // issue 11: 0.05 %
          EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);        // CG/GMRES to 1e-10
          EXPECT_NEAR(f.force_load / f.force, 1.0, 1e-6);
          EXPECT_LT(f.max_penetration, 1e-9 * mortar.loading.delta_max);
        }
      if (c.mu > 0.0)
        expect_coulomb_holds(b, c.mu, c.label);
    }
}

namespace
{
  /// An adaptive run's meshes against a reference value F_ref: more DoFs and a smaller error on
  /// every mesh, the last mesh's F the recorded curve's, and the run's estimate bounding the
  /// last error, which must be below `limit`.
  void expect_cycles_approach(const RunResult &r, const double F_ref, const double limit)
  {
    double previous_error = 1.0;
    for (std::size_t k = 0; k < r.adaptive_cycles.size(); ++k)
      {
        const auto &c = r.adaptive_cycles[k];
        const double error = std::abs(c.force / F_ref - 1.0);
        std::printf("mesh %zu: %lu cells, %lu DoFs, F(delta_max) = %.8g N, %.3f %% from the "
                    "reference, %u contact iterations\n",
                    k, c.n_cells, c.n_dofs, c.force, 100.0 * error, c.contact_iterations);
        if (k > 0)
          EXPECT_GT(c.n_dofs, r.adaptive_cycles[k - 1].n_dofs);
        EXPECT_LT(error, previous_error);
        previous_error = error;
      }
    EXPECT_DOUBLE_EQ(r.adaptive_cycles.back().force, r.increments.back().force);
    std::printf("estimated error %.3f %% (%s); true %.3f %%\n", 100.0 * r.adaptive_error,
                r.adaptive_error_method.c_str(), 100.0 * previous_error);
    EXPECT_GE(r.adaptive_error, 0.0);
    EXPECT_LE(previous_error, r.adaptive_error);  // the estimate bounds the error here
    EXPECT_LT(previous_error, limit);
  }
}  // namespace

// Adaptive refinement (mesh.adaptive_cycles): Kelly's indicator refines the rigid journal's
// joint (frictionless, the fast preset's base mesh) in 3 cycles; the force must approach the
// uniform meshes' Richardson value F_ref = 22 060.9 N (levels 0–2 of the same base mesh, p =
// 2.05, docs/benchmarks.md "FE stage": an independent computation of the same problem), each
// cycle closer, the final mesh within its own error estimate of it and more accurate than the
// uniform level 2 (0.28 % with 72 k DoFs), with equilibrium and exact non-penetration.
TEST(FeAdaptive, CyclesApproachTheUniformRichardsonValueWithinTheirEstimate)
{
  FeScene s = scene("contact: {mu: 0}\n"
                    "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1, "
                    "adaptive_cycles: 3, adaptive_fraction: 0.2}\n"
                    "loading: {journal: rigid, n_increments: 3}\n");
  const double F_ref = 22060.9;  // [N] printed to 0.1 N: 5e-6 of F, far below what is tested
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.adaptive_cycles.size(), 4u);   // 3 cycles + the recorded curve's mesh
  expect_cycles_approach(r, F_ref, 0.0028);  // better than uniform level 2 (0.28 %)
  for (const auto &f : r.increments)
    {
      EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);  // CG to 1e-10
      EXPECT_LT(f.max_penetration, 1e-9 * s.loading.delta_max);
    }
}

// Friction on adaptively refined meshes (issue 11 item 4): Kelly's refinement scatters hanging
// nodes through the contact zone, and a cell beside a hanging node need not hold the contact
// nodes it hangs from. The friction rows must carry that cell's share of their force, as the
// evaluation reads it, or Newton's matrix is not the slip law's derivative: before they did,
// the second refined mesh cycled for all 100 iterations (two nodes stick <-> slip, one open <->
// stick). Now every cycle settles, Newton converges, Coulomb's law holds at every node and the
// sequence approaches the uniform levels' Richardson value with friction.
TEST(FeAdaptive, FrictionOnKellyRefinedContactZones)
{
  FeScene s = scene("contact: {mu: 0.1}\n"
                    "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1, "
                    "adaptive_cycles: 3, adaptive_fraction: 0.2}\n"
                    "loading: {journal: rigid, n_increments: 3}\n");
  // [N] the uniform levels 0-2 with mu = 0.1 and 3 increments, Richardson p = 2.14 (level 2
  // at 0.25 %): bench/fe_bench.py --levels 0 1 2 --ranks 2 --journals rigid --increments 3
  // --mu 0.1 (docs/benchmarks.md); printed to 0.1 N, 5e-6 of F
  const double F_ref = 22128.8;
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.adaptive_cycles.size(), 4u);
  expect_cycles_approach(r, F_ref, 0.0025);  // better than uniform level 2 (0.25 %)
  // 3 increments: measured 10-17 iterations per mesh; the old cycling took 100 in one
  for (const auto &c : r.adaptive_cycles)
    EXPECT_LE(c.contact_iterations, 30u);
  for (const auto &f : r.increments)
    {
      EXPECT_NEAR(f.force_support / f.force, 1.0, 1e-6);  // GMRES to 1e-10
      EXPECT_LT(f.max_penetration, 1e-9 * s.loading.delta_max);
      EXPECT_GT(f.n_slip, 0u);
    }
  expect_coulomb_holds(r, 0.1, "adaptive, mu = 0.1");
}

// A target error instead of a number of cycles (mesh.adaptive_target_error, issue 11 item 4):
// the cycles stop at the first mesh whose extrapolated estimate meets the target, and the curve
// is computed there; a target out of reach runs every allowed cycle and says so.
TEST(FeAdaptive, TargetErrorStopsTheCyclesWhereTheEstimateMeetsIt)
{
  const std::string base = "contact: {mu: 0.1}\n"
                           "loading: {journal: rigid, n_increments: 3}\n"
                           "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, "
                           "contact_refinements: 1, adaptive_fraction: 0.2, ";
  const double F_ref = 22128.8;  // [N] as in FrictionOnKellyRefinedContactZones
  FeScene s = scene(base + "adaptive_cycles: 5, adaptive_target_error: 0.01}\n");
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  const double error = std::abs(r.increments.back().force / F_ref - 1.0);
  std::printf("target 1 %%: %zu meshes, %lu DoFs, estimate %.3f %% (%s), true %.3f %%\n",
              r.adaptive_cycles.size(), r.n_dofs, 100.0 * r.adaptive_error,
              r.adaptive_error_method.c_str(), 100.0 * error);
  EXPECT_TRUE(r.adaptive_target_reached);
  EXPECT_LE(r.adaptive_error, 0.01);
  // an extrapolation needs three meshes; 1 % is met before the fifth cycle (measured: on the
  // fourth mesh, 21 k DoFs, estimate 0.69 %; the third's 2.3 % does not meet it)
  EXPECT_GE(r.adaptive_cycles.size(), 3u);
  EXPECT_LT(r.adaptive_cycles.size(), 6u);
  EXPECT_EQ(r.adaptive_cycles.back().n_dofs, r.n_dofs);  // the curve's mesh closes the list
  EXPECT_DOUBLE_EQ(r.adaptive_cycles.back().force, r.increments.back().force);
  // and the error itself meets the target (measured 0.037 % against F_ref; F_ref is too high,
  // the six-mesh run of docs/benchmarks.md puts this mesh's error at 0.46-0.61 %)
  EXPECT_LT(error, 0.01);

  // out of reach in two cycles: every cycle runs, the run completes and says so
  const RunResult u = run(scene(base + "adaptive_cycles: 2, adaptive_target_error: 1e-5}\n"));
  ASSERT_TRUE(u.complete) << u.message;
  EXPECT_FALSE(u.adaptive_target_reached);
  EXPECT_EQ(u.adaptive_cycles.size(), 3u);
  EXPECT_GT(u.adaptive_error, 1e-5);
}

// The method's own parameter: the active-set constant c only steers the iteration; the
// converged solution satisfies n·u = −g0 exactly at active nodes, so F must not change when c
// is made 10x and 1000x larger (issue 3 item 3 asks < 0.5 % for 10x; we demand solver accuracy).
TEST(FeRadial, ActiveSetConstantDoesNotChangeTheForce)
{
  const RunResult r1 = run(scene(coarse_radial));
  FeScene s10 = scene(coarse_radial);
  s10.contact.active_set_scale = 10.0;
  FeScene s1000 = scene(coarse_radial);
  s1000.contact.active_set_scale = 1000.0;
  const RunResult a = run(s10), b = run(s1000);
  ASSERT_TRUE(r1.complete && a.complete && b.complete);
  const double F = r1.increments.back().force;
  EXPECT_GT(F, 0.0);
  // 1e-8: two CG solves to 1e-10 relative residual
  EXPECT_NEAR(a.increments.back().force / F, 1.0, 1e-8);
  EXPECT_NEAR(b.increments.back().force / F, 1.0, 1e-8);
  EXPECT_EQ(a.increments.back().n_active, r1.increments.back().n_active);
  EXPECT_EQ(b.increments.back().n_active, r1.increments.back().n_active);
  for (const auto &inc : r1.increments)
    EXPECT_LT(inc.max_penetration, 1e-9 * s10.loading.delta_max);  // exact non-penetration
}

// A Krylov solve that fails even with a fresh AMG (here forced: one iteration allowed) is solved
// by MUMPS instead of failing the increment: the run completes with the direct solver's result.
TEST(FeRadial, AFailedKrylovSolveIsSolvedByTheDirectSolver)
{
  FeScene direct = scene(coarse_radial);
  direct.solver.linear = LinearSolver::direct;
  FeScene starved = scene(coarse_radial);
  starved.solver.linear = LinearSolver::cg_amg;
  starved.solver.max_linear_iterations = 1;
  const RunResult a = run(direct), b = run(starved);
  ASSERT_TRUE(a.complete) << a.message;
  ASSERT_TRUE(b.complete) << b.message;
  ASSERT_EQ(a.increments.size(), b.increments.size());
  for (std::size_t i = 0; i < a.increments.size(); ++i)
    {
      // 1e-9: two exact factorisations of the same systems (round-off only)
      EXPECT_NEAR(b.increments[i].force / a.increments[i].force, 1.0, 1e-9);
      EXPECT_EQ(b.increments[i].n_active, a.increments[i].n_active);
    }
}

// Equilibrium: the contact force equals the support reaction; the force grows with δ; the full
// model gives the quarter model's force (the quarter's symmetry factor 4 is right).
TEST(FeRadial, EquilibriumMonotonicityAndQuarterEqualsFull)
{
  const FeScene quarter = scene(coarse_radial);
  FeScene full = quarter;
  full.full_model = true;
  const RunResult q = run(quarter), f = run(full);
  ASSERT_TRUE(q.complete && f.complete);
  EXPECT_DOUBLE_EQ(q.symmetry_factor, 4.0);
  EXPECT_DOUBLE_EQ(f.symmetry_factor, 1.0);
  double previous = 0.0;
  for (std::size_t i = 0; i < q.increments.size(); ++i)
    {
      const auto &a = q.increments[i];
      EXPECT_GT(a.force, previous);
      previous = a.force;
      // 1e-7: both are sums of K·u with u from a 1e-10 solve; they differ by round-off only
      EXPECT_NEAR(a.force_support / a.force, 1.0, 1e-7);
      // 1e-6: same mesh mirrored; differences come from the linear solver only
      EXPECT_NEAR(f.increments[i].force / a.force, 1.0, 1e-6);
    }
}

// Two deformable bodies: the contact force on the bearing, the reaction of its supports and
// the reaction on the journal's loaded set (the paper's measure) are one force; the journal
// does not penetrate the bearing at any contact node.
TEST(FeTwoBody, ContactForceEqualsSupportAndLoadReactions)
{
  for (const std::string journal : {"end_faces", "axis_line", "core"})
    {
      const FeScene s = scene(coarse_two_body(journal));
      const RunResult r = run(s);
      ASSERT_TRUE(r.complete) << r.message;
      for (const auto &i : r.increments)
        {
          // 1e-7: sums of K·u over different node sets, u from a 1e-10 solve
          EXPECT_NEAR(i.force_support / i.force, 1.0, 1e-7) << journal;
          EXPECT_NEAR(i.force_load / i.force, 1.0, 1e-7) << journal;
          EXPECT_LT(i.max_penetration, 1e-9 * s.loading.delta_max) << journal;
        }
    }
}

// Compliance adds up: the rigid journal gives the stiffest contact; a journal driven on its end
// faces, or moved by its rigid inner core (r ≤ R_J/2, SPEC §2), adds the journal's own
// compliance; one driven only on its axis line is softer still (SPEC §2). Core and end faces
// load this short journal (L_J = 18 mm, R_J = 9.5 mm) almost alike: measured 19950.5 against
// 19967.9 N (0.09 %), so their order is not asserted.
TEST(FeTwoBody, RigidStifferThanEndFacesOrCoreStifferThanAxisLine)
{
  const RunResult rigid = run(scene(coarse_radial));
  const RunResult core = run(scene(coarse_two_body("core")));
  const RunResult ends = run(scene(coarse_two_body("end_faces")));
  const RunResult axis = run(scene(coarse_two_body("axis_line")));
  ASSERT_TRUE(rigid.complete && core.complete && ends.complete && axis.complete);
  const double Fr = rigid.increments.back().force, Fc = core.increments.back().force,
               Fe = ends.increments.back().force, Fa = axis.increments.back().force;
  std::printf("F(delta_max): rigid %.1f N, core %.1f N, end_faces %.1f N, axis_line %.1f N\n", Fr,
              Fc, Fe, Fa);
  EXPECT_GT(Fr, Fe);
  EXPECT_GT(Fe, Fa);
  EXPECT_GT(Fr, Fc);
  EXPECT_GT(Fc, Fa);
  // the core's outer half under the contact: softer than rigid by what the end faces show
  EXPECT_NEAR(Fc, Fe, 0.05 * (Fr - Fa));
}

// The two-body quarter model equals the full two-body model (symmetry factor).
TEST(FeTwoBody, QuarterEqualsFull)
{
  const FeScene quarter = scene(coarse_two_body("end_faces"));
  FeScene full = quarter;
  full.full_model = true;
  const RunResult q = run(quarter), f = run(full);
  ASSERT_TRUE(q.complete && f.complete) << q.message << f.message;
  for (std::size_t i = 0; i < q.increments.size(); ++i)
    {
      // 1e-3, not solver accuracy: the journal's core is meshed differently in the two models
      // (the full core is one Coons patch, the quarter's runs straight along x = 0), which
      // moved F by 1.2e-4 here; the bearing and both contact surfaces are identical.
      EXPECT_NEAR(f.increments[i].force / q.increments[i].force, 1.0, 1e-3);
    }
}

namespace
{
  // A coarse half model of the tilted joint: the contact zone refined twice around the rim
  // patch (about 8 k DoFs).
  std::string coarse_misaligned(const double theta_deg)
  {
    return "study: misalignment\ncontact: {mu: 0}\n"
           "misalignment: {theta_deg: " +
           std::to_string(theta_deg) +
           "}\n"
           "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 2}\n"
           "loading: {n_increments: 4}\n";
  }
}  // namespace

namespace
{
  // The aligned journal pushed at its core over the whole length, its surface the mortar slave,
  // moved axially: `loading` adds loading keys (axial_offset / axial_slide), `sliding` is
  // contact.sliding.
  std::string coarse_axial(const std::string &loading, const std::string &sliding)
  {
    return "contact: {mu: 0, sliding: " + sliding +
           "}\n"
           "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1}\n"
           "loading: {journal: core, n_increments: 2, " +
           loading + "}\n";
  }
}  // namespace

// Issue 3 item 6: two MPI ranks give F within 1e-6 relative of one rank. Run under
// `mpirun -np 2` by ctest (fe_mpi_np2_matches_np1); with one rank it compares a run with
// itself and is skipped.
namespace
{
  /// Runs `s` on all ranks and on rank 0 alone; the forces must agree to 1e-6 (SPEC §2) and the
  /// active sets exactly.
  void expect_ranks_agree(FeScene s)
  {
    const int size = world_size();
    s.solver.linear = LinearSolver::cg_amg;
    const AllRanksAndRankZero runs = run_on_all_ranks_and_on_rank_zero(s);
    const RunResult &parallel = runs.all;
    ASSERT_TRUE(parallel.complete) << parallel.message;
    EXPECT_EQ(parallel.n_ranks, static_cast<unsigned int>(size));
    if (runs.rank_zero)
      {
        const RunResult &serial = *runs.rank_zero;
        ASSERT_TRUE(serial.complete);
        EXPECT_EQ(serial.n_ranks, 1u);
        ASSERT_EQ(serial.increments.size(), parallel.increments.size());
        for (std::size_t i = 0; i < serial.increments.size(); ++i)
          {
            // 1e-6: both solve to a 1e-10 relative residual; the partition changes only the
            // order of the sums and the AMG, not the active set
            EXPECT_NEAR(parallel.increments[i].force / serial.increments[i].force, 1.0, 1e-6);
            EXPECT_NEAR(parallel.increments[i].force_load / serial.increments[i].force_load, 1.0,
                        1e-6);
            EXPECT_EQ(parallel.increments[i].n_active, serial.increments[i].n_active);
          }
        std::printf("%s: np=1 F = %.12g N, np=%d F = %.12g N\n",
                    (s.study == Study::radial ? to_string(s.loading.journal) + " journal" :
                                                to_string(s.study) + " study")
                      .c_str(),
                    serial.increments.back().force, size, parallel.increments.back().force);
      }
  }
}  // namespace

// Results do not depend on the number of ranks: the rigid journal, and the deformable journal
// whose contact partners (journal nodes facing each bearing node) may live on another rank.
TEST(FeMpi, TwoRanksMatchOneRank)
{
  if (world_size() < 2)
    GTEST_SKIP() << "needs mpirun -np 2";
  expect_ranks_agree(scene(coarse_radial));
  expect_ranks_agree(scene(coarse_two_body("end_faces")));
  expect_ranks_agree(scene(coarse_two_body("axis_line")));
  expect_ranks_agree(scene(coarse_two_body("core")));
  FeScene hanging = scene(coarse_two_body("end_faces"));
  hanging.mesh.contact_refinements = 1;
  hanging.mesh.contact_window_deg = 20.0;  // hanging nodes inside the contact zone
  expect_ranks_agree(hanging);
  FeScene friction = scene(coarse_two_body("end_faces"));
  friction.contact.mu = 0.1;  // stick/slip sets and slip directions, GMRES
  expect_ranks_agree(friction);
  hanging.contact.mu = 0.3;  // friction rows with hanging shares, partners on other ranks
  expect_ranks_agree(hanging);
  // node-to-node on the common rays (the joint's default pairing is dual mortar, whose
  // journal surface faces are gathered on every rank)
  friction.contact.pairing = Contact::Pairing::node_to_node;
  expect_ranks_agree(friction);
  // adaptive refinement: Kelly's indicator and p4est's refinement across ranks
  FeScene adaptive = scene(coarse_radial);
  adaptive.mesh.adaptive_cycles = 1;
  expect_ranks_agree(adaptive);
  // with friction and mortar: the friction rows of hanging DoFs whose masters another rank owns
  FeScene adaptive_friction = scene(coarse_two_body("end_faces"));
  adaptive_friction.mesh.adaptive_cycles = 1;
  adaptive_friction.contact.mu = 0.1;
  expect_ranks_agree(adaptive_friction);
  // the tilted deformable journal as the mortar slave, the bore's faces gathered on every
  // rank, with friction
  FeScene tilted = scene(coarse_misaligned(1.0));
  tilted.loading.journal = JournalLoading::core;
  tilted.contact.mu = 0.1;
  expect_ranks_agree(tilted);
  // finite sliding with friction: the mortar search redone, the pattern and ghosts rebuilt
  FeScene sliding = scene(coarse_axial("axial_slide: 0.8e-3", "finite"));
  sliding.contact.mu = 0.1;
  expect_ranks_agree(sliding);
  // dual mortar between non-matching meshes (master faces gathered on every rank)
  expect_ranks_agree(scene("study: patch\ncontact: {mu: 0}\nloading: {n_increments: 2}\n"
                           "verification: {n_cells: 4, contact_refinements: 0, "
                           "indenter: deformable, indenter_n_cells: 3}\n"));
  expect_ranks_agree(scene("study: hertz\ncontact: {mu: 0}\n"
                           "loading: {delta_max: 1.0e-5, n_increments: 2}\n"
                           "verification: {n_cells: 4, contact_refinements: 3, "
                           "refine_radius: 1.0e-3, indenter: deformable, indenter_n_cells: 3}\n"));
}

// Hanging nodes inside the two-body contact zone (refined window 20°, contact reaches ~30°):
// any mix of active and inactive contact nodes fits the sparsity pattern, the hanging nodes'
// forces reach their masters, and the three measures of the force agree.
TEST(FeTwoBody, HangingNodesInsideTheContactZone)
{
  FeScene s = scene(coarse_two_body("end_faces"));
  s.mesh.contact_refinements = 1;
  s.mesh.contact_window_deg = 20.0;
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  for (const auto &inc : r.increments)
    {
      // 1e-7: sums of K·u with u from a 1e-10 solve; they differ by round-off only
      EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-7);
      EXPECT_NEAR(inc.force_load / inc.force, 1.0, 1e-7);
      EXPECT_LT(inc.max_penetration, 1e-9 * s.loading.delta_max);
    }
}

// The misalignment study at θ = 0 is the aligned joint: its half model (both rims, the whole
// length) gives the quarter model's rigid-journal force. 0.5 %: the two meshes differ (axial
// slices and the refined zone), so they agree to their discretisation error only; measured
// 0.02 % at δ_max on 2026-11-22.
TEST(FeMisalignment, ZeroTiltEqualsAlignedRigidJournal)
{
  const FeScene tilted = scene(coarse_misaligned(0.0));
  const FeScene aligned = scene("contact: {mu: 0}\n"
                                "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, "
                                "contact_refinements: 2}\n"
                                "loading: {journal: rigid, n_increments: 4}\n");
  const RunResult t = run(tilted), a = run(aligned);
  ASSERT_TRUE(t.complete && a.complete) << t.message << a.message;
  EXPECT_DOUBLE_EQ(t.symmetry_factor, 2.0);  // only the x = 0 plane
  EXPECT_NEAR(t.increments.back().force / a.increments.back().force, 1.0, 5e-3);
}

// Tilted 1°: only a rim patch carries the load, so at the same δ the force lies well below the
// aligned one (SPEC §2: a peer model lost ~75 % from 0° to 1°; we assert < 50 %). Equilibrium
// holds with hanging nodes inside the contact zone (their share is passed to their masters),
// and the force grows with δ.
TEST(FeMisalignment, TiltedForceWellBelowAlignedAndInEquilibrium)
{
  const RunResult t0 = run(scene(coarse_misaligned(0.0)));
  const RunResult t1 = run(scene(coarse_misaligned(1.0)));
  ASSERT_TRUE(t0.complete && t1.complete) << t1.message;
  EXPECT_LT(t1.increments.back().force, 0.5 * t0.increments.back().force);
  double previous = 0.0;
  for (const auto &inc : t1.increments)
    {
      EXPECT_GT(inc.force, previous);
      previous = inc.force;
      EXPECT_GT(inc.n_active, 0u);
      // 1e-7: both are sums of K·u with u from a 1e-10 solve; they differ by round-off only
      EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-7);
      EXPECT_LT(inc.max_penetration, 1e-9 * 0.05e-3);  // exact at the contact nodes
    }
}

// The deformable journal of the misalignment study, pushed at its inner core (SPEC §2), its
// surface the mortar slave. At θ = 0 it is the aligned joint: the half model gives the radial
// study's quarter-model force with the same core loading. 1 %: the meshes differ (the tilted
// mesh's axial slices, its gap-driven refinement, and which surface is the slave); measured
// 0.42 % at δ_max on 2026-11-27. On one mesh the slave side alone moves F by 3.6e-4 (same
// day; 2e-3 allowed: the two sides' dual bases discretise the pressure differently).
TEST(FeMisalignment, DeformableCoreJournalAtZeroTiltEqualsAlignedCoreJournal)
{
  const std::string mesh = "mesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, "
                           "contact_refinements: 2}\n";
  FeScene tilted = scene(coarse_misaligned(0.0));
  tilted.loading.journal = JournalLoading::core;
  const FeScene aligned =
    scene("contact: {mu: 0}\n" + mesh + "loading: {journal: core, n_increments: 4}\n");
  const FeScene aligned_journal_slave = scene("contact: {mu: 0, mortar_slave: journal}\n" + mesh +
                                              "loading: {journal: core, n_increments: 4}\n");
  const RunResult t = run(tilted), a = run(aligned), j = run(aligned_journal_slave);
  ASSERT_TRUE(t.complete && a.complete && j.complete) << t.message << a.message << j.message;
  EXPECT_DOUBLE_EQ(t.symmetry_factor, 2.0);
  EXPECT_NEAR(t.increments.back().force / a.increments.back().force, 1.0, 1e-2);
  EXPECT_NEAR(j.increments.back().force / a.increments.back().force, 1.0, 2e-3);
  for (const RunResult *r : {&t, &j})
    for (const auto &inc : r->increments)
      {
        // 1e-6: sums of K·u with u from a 1e-10 solve (observed ≤ 2e-9)
        EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-6);
        EXPECT_NEAR(inc.force_load / inc.force, 1.0, 1e-6);
        EXPECT_LT(inc.max_penetration, 1e-9 * 0.05e-3);
      }
}

// Tilted 1° with the deformable core-loaded journal: the rim carries the load, the journal's
// own compliance in series makes the force at each δ lower than the rigid tilted journal's
// (measured 3621 N against 5197 N at δ_max, 2026-11-27), and equilibrium holds between the
// contact, the supports and the driven core.
TEST(FeMisalignment, TiltedDeformableJournalIsSofterThanTheRigidOneAndInEquilibrium)
{
  FeScene deformable = scene(coarse_misaligned(1.0));
  deformable.loading.journal = JournalLoading::core;
  const RunResult d = run(deformable), r = run(scene(coarse_misaligned(1.0)));
  ASSERT_TRUE(d.complete && r.complete) << d.message << r.message;
  ASSERT_EQ(d.increments.size(), r.increments.size());
  double previous = 0.0;
  for (std::size_t k = 0; k < d.increments.size(); ++k)
    {
      const auto &inc = d.increments[k];
      EXPECT_GT(inc.force, previous);
      previous = inc.force;
      EXPECT_LT(inc.force, r.increments[k].force);
      EXPECT_GT(inc.n_active, 0u);
      EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-6);  // as above
      EXPECT_NEAR(inc.force_load / inc.force, 1.0, 1e-6);
      EXPECT_LT(inc.max_penetration, 1e-9 * 0.05e-3);
    }
}

// Finite sliding (contact.sliding: finite). The core pushes the journal down by δ and slides it
// 0.8 mm along its axis at the same time; without friction the end state does not depend on
// the path, so it must equal the journal meshed 0.8 mm off-centre and pushed straight down.
// The axial slide does not change the weighted gaps of a straight bore, only which bore nodes
// the journal bears on: with the search done once (small sliding) the journal keeps pushing on
// the bore where it started and F is that of the centred journal, 0.40 % off (measured
// 2026-11-27: 20384.3 against 20303.4 N; the bore's free end is 0.2 mm from the journal's
// there); searched again until the coupling settles, 1.5e-5 off (20303.7 N). Tolerances:
// 1e-4 for finite sliding (the settled coupling moved by < 1e-3 in its last search), and the
// small-sliding result must miss by more than 2e-3 (half the end effect), so that the test
// tells the two apart.
TEST(FeTwoBody, FiniteSlidingFollowsAnAxialSlide)
{
  const RunResult offset = run(scene(coarse_axial("axial_offset: 0.8e-3", "small")));
  const RunResult finite = run(scene(coarse_axial("axial_slide: 0.8e-3", "finite")));
  const RunResult small = run(scene(coarse_axial("axial_slide: 0.8e-3", "small")));
  ASSERT_TRUE(offset.complete && finite.complete && small.complete)
    << offset.message << finite.message << small.message;
  EXPECT_DOUBLE_EQ(offset.symmetry_factor, 2.0);  // the whole length, the x = 0 plane
  const double f_ref = offset.increments.back().force;
  EXPECT_NEAR(finite.increments.back().force / f_ref, 1.0, 1e-4);
  EXPECT_GT(std::abs(small.increments.back().force / f_ref - 1.0), 2e-3);
  // the slide moved the partners: the coupling was redone (and solved again) in each increment
  EXPECT_GE(finite.sliding_resolves, finite.increments.size());
  EXPECT_EQ(small.sliding_resolves, 0u);
  for (const auto &inc : finite.increments)
    {
      // 1e-6: sums of K·u with u from a 1e-10 solve
      EXPECT_NEAR(inc.force_support / inc.force, 1.0, 1e-6);
      EXPECT_NEAR(inc.force_load / inc.force, 1.0, 1e-6);
      EXPECT_LT(inc.max_penetration, 1e-9 * 0.05e-3);
    }
}

// A contact iteration that does not settle names the nodes that still change and how (the
// contact chatter an analyst looks for), in mm, in the failure's message: here the first
// iteration of the coarse joint cannot have settled (every node starts open).
TEST(FeTwoBody, AnUnsettledActiveSetNamesItsNodes)
{
  FeScene s = scene(coarse_two_body("end_faces"));
  s.contact.max_iterations = 1;
  s.loading.max_cuts = 0;
  const RunResult r = run(s);
  ASSERT_FALSE(r.complete);
  EXPECT_NE(r.message.find("active set did not settle in 1 iterations"), std::string::npos)
    << r.message;
  EXPECT_NE(r.message.find(" mm open -> closed"), std::string::npos) << r.message;
}

// `-v` sets the debug level on rank 0 only (fe_stage/main.cc): a debug-only check that is
// collective must still run on every rank. A frictional case with rank 0 at the debug level and
// the others at the error level, as fe_stage runs them: before the friction rows' check was
// made collective on every rank, a two-rank rolling run with -v stopped with MPI_ERR_TRUNCATE
// (its maximum met another collective on the other rank).
TEST(FeMpi, VerboseOnRankZeroOnlyRunsAndMatches)
{
  if (world_size() < 2)
    GTEST_SKIP() << "needs mpirun -np 2";
  const clearjoint::log::Level before = clearjoint::log::level();
  clearjoint::log::set_level(rank() == 0 ? clearjoint::log::Level::debug :
                                           clearjoint::log::Level::error);
  FeScene friction = scene(coarse_two_body("end_faces"));
  friction.contact.mu = 0.1;
  expect_ranks_agree(friction);
  clearjoint::log::set_level(before);
}
