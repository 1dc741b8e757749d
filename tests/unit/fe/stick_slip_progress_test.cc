// When the stick/slip iteration counts as cycling (fe_stage/contact/stick_slip_progress.h), on
// residual sequences taken from `fe_stage -v` logs.
#include "fe_stage/contact/stick_slip_progress.h"

#include <gtest/gtest.h>

using clearjoint::fe::StickSlipProgress;

TEST(StickSlipProgress, AResidualAlternatingBetweenTwoValuesCyclesOnItsThirdIteration)
{
  // the rolling study's deformable journal, δ = 0.125 mm: 326, 318, 326, 319 … N, sets unchanged
  StickSlipProgress p;
  EXPECT_FALSE(p.record(326.052, false));
  EXPECT_FALSE(p.record(318.259, false));
  EXPECT_TRUE(p.record(326.497, false));
}

TEST(StickSlipProgress, ARisingResidualCycles)
{
  // δ = 0.375 mm: nodes flipping between stick, slip and open
  StickSlipProgress p;
  EXPECT_FALSE(p.record(480.908, false));
  EXPECT_FALSE(p.record(1026.95, false));
  EXPECT_TRUE(p.record(1080.7, false));
}

TEST(StickSlipProgress, NewtonsConvergenceIsProgress)
{
  // the standard preset, t_B = 4 mm, μ = 0.1, increment 6 (docs/fe.md): 0.74, 0.57, 1.7e-3,
  // 1.1e-7 N; the second does not halve the first, the third does
  StickSlipProgress p;
  EXPECT_FALSE(p.record(0.74, false));
  EXPECT_FALSE(p.record(0.57, false));
  EXPECT_FALSE(p.record(1.7e-3, false));
  EXPECT_FALSE(p.record(1.1e-7, true));
}

TEST(StickSlipProgress, ASettledIterationNeverCycles)
{
  StickSlipProgress p;
  EXPECT_FALSE(p.record(1e-3, true));
  EXPECT_FALSE(p.record(1e-3, true));
  EXPECT_FALSE(p.record(1e-3, true));
}

TEST(StickSlipProgress, ARestartJudgesTheNextIterationsAfresh)
{
  StickSlipProgress p;
  p.record(100.0, false);
  p.record(90.0, false);
  ASSERT_TRUE(p.record(95.0, false));
  p.restart();  // c_T lowered: its first two iterations are its own
  EXPECT_FALSE(p.record(200.0, false));
  EXPECT_FALSE(p.record(150.0, false));
  EXPECT_TRUE(p.record(140.0, false));
  // without a restart the count goes on
  EXPECT_TRUE(p.record(130.0, false));
}
