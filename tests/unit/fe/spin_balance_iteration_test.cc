// The spin's Newton iteration on the journal's torque balance (fe_stage/solve/
// spin_balance_iteration.h): which slope it steps with, when it has converged, and when it
// hands the step to the root finder.
#include "fe_stage/solve/spin_balance_iteration.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using clearjoint::fe::SpinBalanceIteration;
using Trend = SpinBalanceIteration::Trend;

TEST(SpinBalanceIteration, ALinearBalanceConvergesInOneStepByTheBorderedSlope)
{
  // g(γ̇) = 0.5 (γ̇ − 13): the column's slope is exact, so one step lands on the root
  SpinBalanceIteration b(0.0);
  const double roll = 12.56, tol = 1e-10;
  double rate = 12.0;
  ASSERT_TRUE(b.take_bordered_slope(0.5));
  const double s = b.step(0.5 * (rate - 13.0), roll);
  EXPECT_DOUBLE_EQ(s, 1.0);
  EXPECT_FALSE(b.converged(tol, tol, s, roll));  // a step of 1 rad/s is still to be taken
  EXPECT_EQ(b.trend(tol, 0.5 * (rate - 13.0)), Trend::continues);
  b.advance(rate, 0.5 * (rate - 13.0));
  rate += s;
  ASSERT_TRUE(b.take_bordered_slope(0.5));
  EXPECT_TRUE(b.converged(tol, tol, b.step(0.5 * (rate - 13.0), roll), roll));
}

TEST(SpinBalanceIteration, ABorderedSlopeThatDoesNotRiseKeepsTheLastOrHandsOver)
{
  SpinBalanceIteration b(0.0);
  EXPECT_FALSE(b.take_bordered_slope(-1.0));  // none of its own yet: the root finder
  EXPECT_FALSE(b.take_bordered_slope(std::numeric_limits<double>::quiet_NaN()));
  ASSERT_TRUE(b.take_bordered_slope(2.0));
  EXPECT_TRUE(b.take_bordered_slope(-1.0));  // keeps 2
  EXPECT_DOUBLE_EQ(b.slope(), 2.0);
}

TEST(SpinBalanceIteration, TheCoupledSecantIsTakenOnlyWhereItIsPlausible)
{
  SpinBalanceIteration b(1.0);  // the last step's slope
  b.take_secant(10.0, 1.0, 1e-3, 1e-10);  // no previous iterate: nothing to take
  EXPECT_FALSE(b.own_slope());
  EXPECT_DOUBLE_EQ(b.slope(), 1.0);
  b.advance(10.0, 1.0);
  b.take_secant(11.0, 1.0 + 20.0, 1e-3, 1e-10);  // 20 > 5 × 1: implausible while far off
  EXPECT_FALSE(b.own_slope());
  b.take_secant(11.0, 1.0 + 20.0, 1e-8, 1e-10);  // the bodies nearly converged: taken
  EXPECT_TRUE(b.own_slope());
  EXPECT_DOUBLE_EQ(b.slope(), 20.0);
  b.take_secant(12.0, -5.0, 1e-3, 1e-10);  // a falling secant is never taken
  EXPECT_DOUBLE_EQ(b.slope(), 20.0);
}

TEST(SpinBalanceIteration, TheStepIsAtMostHalfTheRollingRateAndZeroOnABalanceThatHolds)
{
  SpinBalanceIteration b(1e-3);  // a tiny slope: −g/slope would be thousands of rad/s
  EXPECT_DOUBLE_EQ(b.step(1.0, 12.56), -6.28);
  EXPECT_DOUBLE_EQ(b.step(-1.0, 12.56), 6.28);
  EXPECT_DOUBLE_EQ(b.step(1e-7, 12.56), 0.0);
}

TEST(SpinBalanceIteration, ConvergedNeedsTheBodiesAndTheBalanceOrATinyStepByItsOwnSlope)
{
  const double roll = 12.56, tol = 1e-10;
  SpinBalanceIteration b(1.0);
  EXPECT_TRUE(b.converged(tol, tol, 0.0, roll));
  EXPECT_FALSE(b.converged(2 * tol, tol, 0.0, roll));       // the bodies have not converged
  EXPECT_FALSE(b.converged(tol, tol, 1e-12, roll));         // a tiny step by the last step's slope
  ASSERT_TRUE(b.take_bordered_slope(1.0));
  EXPECT_TRUE(b.converged(tol, tol, 1e-12, roll));          // … by its own
  EXPECT_FALSE(b.converged(tol, tol, 1e-8, roll));
}

TEST(SpinBalanceIteration, ThreeGrowingCorrectionsDiverge)
{
  SpinBalanceIteration b(1.0);
  double g = 1.0;
  for (const double c : {1e-6, 2e-6, 3e-6})
    {
      ASSERT_EQ(b.trend(c, g), Trend::continues);
      b.advance(10.0, g);
      g *= 0.1;  // the balance converging: not the stall
    }
  EXPECT_EQ(b.trend(4e-6, g), Trend::diverges);
}

TEST(SpinBalanceIteration, ABalanceThatDoesNotHalveOverFourIterationsStalls)
{
  // a first version's spin-up step crept 25 iterations at g ≈ 3.25
  SpinBalanceIteration b(1.0);
  double c = 1e-3;
  for (const double g : {3.4, 3.35, 3.3, 3.28})
    {
      ASSERT_EQ(b.trend(c, g), Trend::continues);
      b.advance(10.0, g);
      c *= 0.5;  // the bodies converging: not the divergence
    }
  EXPECT_EQ(b.trend(c, 3.25), Trend::stalls);
  // a balance that halves goes on, and one already within 1e-6 never stalls
  SpinBalanceIteration h(1.0);
  for (const double g : {3.4, 3.35, 3.3, 3.28})
    h.trend(1e-3, g), h.advance(10.0, g);
  EXPECT_EQ(h.trend(1e-4, 1.6), Trend::continues);
  SpinBalanceIteration z(1.0);
  for (int i = 0; i < 4; ++i)
    z.trend(1e-3, 1e-7), z.advance(10.0, 1e-7);
  EXPECT_EQ(z.trend(1e-4, 1e-7), Trend::continues);
}
