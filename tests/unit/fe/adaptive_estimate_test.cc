// The adaptive run's error estimate (fe_stage/solve/adaptive_estimate.h): exact on sequences of
// the assumed form with a rate up to p/d, larger (never smaller) for a faster rate, a labelled
// lower bound otherwise, a target met only by an extrapolation — and on the adaptive sequences
// fe_stage measured (docs/benchmarks.md), at least the error that independent references give,
// and not more than twice it.
#include "fe_stage/solve/adaptive_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::fe;

namespace
{
  struct Cycle  // the fields estimate_adaptive_error reads from fe_model.h's AdaptiveCycle
  {
    unsigned long n_dofs = 0;
    double force = 0.0;
  };
  std::vector<Cycle> sequence(const std::vector<double> &dofs, const std::vector<double> &forces)
  {
    std::vector<Cycle> c(dofs.size());
    for (std::size_t k = 0; k < dofs.size(); ++k)
      {
        c[k].n_dofs = static_cast<unsigned long>(dofs[k]);
        c[k].force = forces[k];
      }
    return c;
  }
  const unsigned int Q2 = 2;  // fe_stage's default degree: the bound on q is 2/3
} // namespace

TEST(AdaptiveEstimate, RecoversTheLimitAndOrderOfAPowerLawSequence)
{
  // F = F_inf + C N^-q on unevenly growing meshes, as Kelly's refinement makes them, with a
  // rate below the bound 2/3: the fit and the estimate are exact
  const double F_inf = 19540.0, C = 1.0e5, q = 0.5;
  const std::vector<double> N = {3588, 7869, 17874, 41115};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  // golden sections stop at 1e-12 in q (measured 1.6e-13 off); the tail, ~70 N here, moves
  // by ~1e-12 relative with it: F_inf to 1e-6 N leaves room for the round-off of the logs
  EXPECT_NEAR(e.fitted_order, q, 1e-9);
  EXPECT_NEAR(e.order, q, 1e-9);
  EXPECT_EQ(e.n_meshes_fitted, 4u);
  EXPECT_NEAR(e.extrapolated_force, F_inf, 1e-6);
  EXPECT_NEAR(e.error, (F.back() - F_inf) / F_inf, 1e-10);
  EXPECT_TRUE(adaptive_target_met(e, 1.01 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.99 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.0));  // no target: never "met"
  EXPECT_NE(e.method.find("least squares over the last 4 meshes"), std::string::npos) << e.method;
}

TEST(AdaptiveEstimate, ARateAboveTheBoundIsCreditedOnlyUpToIt)
{
  // q = 1 > 2/3 (Q2 in 3D): the fit finds 1, the estimate uses 2/3 and so over-estimates, by
  // exactly ((N_k/N_{k-2}) - 1) / ((N_k/N_{k-2})^(2/3) - 1) for this exact power law
  const double F_inf = 22000.0, C = 2.0e6, q = 1.0;
  const std::vector<double> N = {1782, 3873, 9024, 21057};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  EXPECT_NEAR(e.fitted_order, q, 1e-9);  // as above
  EXPECT_DOUBLE_EQ(e.order, 2.0 / 3.0);
  const double ratio = N[3] / N[1];
  const double tail = (F[1] - F[3]) / (std::pow(ratio, 2.0 / 3.0) - 1.0);
  EXPECT_NEAR(e.error, tail / (F[3] - tail), 1e-12);  // the same formula: round-off only
  EXPECT_GT(e.error, (F[3] - F_inf) / F_inf);
  EXPECT_NE(e.method.find("the bound p/d"), std::string::npos) << e.method;
  // Q1 elements: the bound is 1/3
  EXPECT_DOUBLE_EQ(estimate_adaptive_error(sequence(N, F), 1).order, 1.0 / 3.0);
}

TEST(AdaptiveEstimate, TheFitUsesTheLastFiveMeshes)
{
  // a wild first mesh (a change 100x the power law's) is left out once there are six meshes
  const double F_inf = 100.0, C = 50.0, q = 0.4;
  const std::vector<double> N = {1e3, 2e3, 4e3, 8e3, 16e3, 32e3};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  F[0] += 100.0 * (F[0] - F[1]);
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  EXPECT_EQ(e.n_meshes_fitted, 5u);
  EXPECT_NEAR(e.order, q, 1e-9);  // as in the first test
  EXPECT_NEAR(e.extrapolated_force, F_inf, 1e-6);
}

TEST(AdaptiveEstimate, FewMeshesOrNoLimitGiveALabelledLowerBound)
{
  EXPECT_LT(estimate_adaptive_error(sequence({1000}, {100.0}), Q2).error, 0.0);
  // two meshes: the last change, a lower bound, which never meets a target
  const AdaptiveEstimate two = estimate_adaptive_error(sequence({1000, 2000}, {110.0, 100.0}), Q2);
  EXPECT_FALSE(two.extrapolated);
  EXPECT_DOUBLE_EQ(two.error, 0.1);
  EXPECT_NE(two.method.find("lower bound"), std::string::npos);
  EXPECT_FALSE(adaptive_target_met(two, 0.5));
  // the differences grow (no limit of the form F_inf + C N^-q): a lower bound again
  const AdaptiveEstimate growing =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 108.0, 100.0}), Q2);
  EXPECT_FALSE(growing.extrapolated);
  EXPECT_DOUBLE_EQ(growing.error, 0.08);
  // not monotone (the last step reverses): a lower bound
  const AdaptiveEstimate zigzag =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 100.0, 101.0}), Q2);
  EXPECT_FALSE(zigzag.extrapolated);
  // a reversal among the fitted changes, not only in the last one: a lower bound
  EXPECT_FALSE(
    estimate_adaptive_error(sequence({1000, 2000, 4000, 8000}, {110.0, 112.0, 105.0, 103.0}), Q2)
      .extrapolated);
  // a mesh that did not grow (a refinement that added nothing): no extrapolation
  EXPECT_FALSE(
    estimate_adaptive_error(sequence({1000, 2000, 2000}, {110.0, 100.0, 99.0}), Q2).extrapolated);
}
