// The adaptive run's error estimate (fe_stage/solve/adaptive_estimate.h): exact on sequences of
// the assumed form, a labelled lower bound otherwise, and a target met only by an extrapolation.
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
} // namespace

TEST(AdaptiveEstimate, RecoversTheLimitAndOrderOfAPowerLawSequence)
{
  // F = F_inf + C N^-q on unevenly growing meshes, as Kelly's refinement makes them
  const double F_inf = 19540.0, C = 4.0e5, q = 0.7;
  const std::vector<double> N = {3588, 7869, 17874, 41115};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F));
  ASSERT_TRUE(e.extrapolated) << e.method;
  // the bisection stops at 1e-12 in q; F_inf then to round-off of the differences (~1e-9 N)
  EXPECT_NEAR(e.order, q, 1e-9);
  EXPECT_NEAR(e.extrapolated_force, F_inf, 1e-6);
  EXPECT_NEAR(e.error, (F.back() - F_inf) / F_inf, 1e-12);
  EXPECT_TRUE(adaptive_target_met(e, 1.01 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.99 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.0));  // no target: never "met"
}

TEST(AdaptiveEstimate, FewMeshesOrNoLimitGiveALabelledLowerBound)
{
  EXPECT_LT(estimate_adaptive_error(sequence({1000}, {100.0})).error, 0.0);
  // two meshes: the last change, a lower bound, which never meets a target
  const AdaptiveEstimate two = estimate_adaptive_error(sequence({1000, 2000}, {110.0, 100.0}));
  EXPECT_FALSE(two.extrapolated);
  EXPECT_DOUBLE_EQ(two.error, 0.1);
  EXPECT_NE(two.method.find("lower bound"), std::string::npos);
  EXPECT_FALSE(adaptive_target_met(two, 0.5));
  // the differences grow (no limit of the form F_inf + C N^-q): a lower bound again
  const AdaptiveEstimate growing =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 108.0, 100.0}));
  EXPECT_FALSE(growing.extrapolated);
  EXPECT_DOUBLE_EQ(growing.error, 0.08);
  // not monotone (the last step reverses): a lower bound
  const AdaptiveEstimate zigzag =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 100.0, 101.0}));
  EXPECT_FALSE(zigzag.extrapolated);
  // a mesh that did not grow (a refinement that added nothing): no extrapolation
  EXPECT_FALSE(estimate_adaptive_error(sequence({1000, 2000, 2000}, {110.0, 100.0, 99.0}))
                 .extrapolated);
}
