// Verification of the rolling study (issue 13 item 3) in its elastic limit (a yield stress of
// 1e12 Pa: the material Newton and the plastic bookkeeping run, nothing yields), on a coarse
// ring (8 × 2 × 1 cells, one contact refinement, 7 k DoFs, ~6 s): without friction the
// journal does not spin, the bore node's Eq. 8 gives the drive's rate and the push's work is
// stored. With friction and with plasticity the study does not converge reliably yet, so those
// tests are not here (docs/fe.md "Rolling study").
#include "fe_test_util.h"

#include <cmath>
#include <cstdio>

using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  std::string coarse_rolling(const std::string &extra)
  {
    return "study: rolling\n"
           "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
           "material: {hardening: [[0, 1.0e12], [1, 1.0e12]]}\n" + extra;
  }
} // namespace

TEST(FeRolling, FrictionlessJournalDoesNotSpinAndThePushWorkIsStored)
{
  const FeScene s = scene(coarse_rolling("contact: {mu: 0}\nrolling: {n_steps: 8}\n"));
  const RunResult r = run(s);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.rolling_steps.size(), 8u);
  const double omega = s.rolling.omega_B;
  for (const auto &st : r.rolling_steps)
    {
      EXPECT_EQ(st.gamma_rate, 0.0) << "t " << st.time;  // no friction, no torque
      EXPECT_EQ(st.max_plastic_strain, 0.0);
      EXPECT_EQ(st.plastic_dissipation, 0.0);
      // Eq. 8 on the bore node must give the drive's rate (the paper's check); its chord
      // formula is exact for a point on the circle, the node moves off it by u ≤ δ
      EXPECT_NEAR(st.phi_rate_paper, omega, 2e-3 * omega) << "t " << st.time;
    }
  const auto &last = r.rolling_steps.back();
  EXPECT_GT(last.force_normal, 0.0);
  // no friction: no friction dissipation beyond round-off of the sums
  EXPECT_LT(std::abs(last.friction_dissipation), 1e-8 * last.work_push);
  // The normal forces act along the journal's radii, whose centre is off the bearing's axis:
  // their moment about that axis vanishes only for a patch symmetric about the line of
  // centres, which the coarse ring's 22.5° cells turning under it are not (measured 13 J, 0.16 %
  // of the push's work)
  EXPECT_LT(std::abs(last.work_drive), 1e-2 * last.work_push);
  // the push's work (trapezoid rule over 8 steps of a curve F ∝ δ^~1.1) is the stored energy:
  // measured 0.05 % apart; 1 % leaves room for the rule's error on other meshes
  EXPECT_NEAR(last.elastic_energy, last.work_push, 1e-2 * last.work_push);
  // and the balance with the drive's work closes to the same order
  EXPECT_LT(std::abs(last.energy_balance_error), 1e-2 * last.work_push);
  std::printf("rolling mu=0: F(%.3g m) = %.6g N, W_push %.6g J, U %.6g J, balance %.3g J\n",
              last.delta, last.force_normal, last.work_push, last.elastic_energy,
              last.energy_balance_error);
}
