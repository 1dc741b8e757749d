// The steppers' one step-size policy (fe_stage/solve/step_controller.h): cuts per step, the
// floor, the size carried over after cuts and its growth back to the nominal.
#include "fe_stage/solve/step_controller.h"

#include <gtest/gtest.h>

#include <stdexcept>

using clearjoint::fe::StepController;

TEST(StepController, CutsAtMostMaxCutsPerStepAndNeverBelowTheFloor)
{
  StepController c(1.0, 3, 2);
  EXPECT_DOUBLE_EQ(c.floor(), 0.125);
  EXPECT_DOUBLE_EQ(c.begin_step(), 1.0);
  EXPECT_TRUE(c.cut());
  EXPECT_TRUE(c.cut());
  EXPECT_TRUE(c.cut());
  EXPECT_DOUBLE_EQ(c.size(), 0.125);
  EXPECT_EQ(c.cuts(), 3u);
  EXPECT_FALSE(c.cut());  // max_cuts reached: the size stays
  EXPECT_DOUBLE_EQ(c.size(), 0.125);
  // the next step starts at the cut size; its own cuts are counted from 0, but the floor stops
  // it: the carried size cannot shrink without end (the rolling study's stall, issue 13)
  c.accept();
  EXPECT_DOUBLE_EQ(c.begin_step(), 0.125);
  EXPECT_EQ(c.cuts(), 0u);
  EXPECT_TRUE(c.at_floor());
  EXPECT_FALSE(c.cut());
  EXPECT_DOUBLE_EQ(c.size(), 0.125);
}

TEST(StepController, TheCarriedSizeGrowsBackAfterEasySteps)
{
  StepController c(1.0, 4, 2);
  c.begin_step();
  ASSERT_TRUE(c.cut());
  ASSERT_TRUE(c.cut());
  c.accept();  // converged at 0.25 after two cuts
  EXPECT_DOUBLE_EQ(c.begin_step(), 0.25);
  c.accept();  // one easy step: not yet
  EXPECT_DOUBLE_EQ(c.begin_step(), 0.25);
  c.accept();  // two: doubles
  EXPECT_DOUBLE_EQ(c.begin_step(), 0.5);
  c.accept();
  c.begin_step();
  c.accept();
  EXPECT_DOUBLE_EQ(c.begin_step(), 1.0);  // back at the nominal, never above
  c.accept();
  c.begin_step();
  c.accept();
  EXPECT_DOUBLE_EQ(c.begin_step(), 1.0);
}

TEST(StepController, TheRemainingPartShortensAnAttemptWithoutChangingTheCarriedSize)
{
  StepController c(1.0, 4, 1);
  EXPECT_DOUBLE_EQ(c.begin_step(0.3), 0.3);  // e.g. the end time reached exactly
  ASSERT_TRUE(c.cut());
  EXPECT_DOUBLE_EQ(c.size(), 0.15);
  c.accept();  // a cut step carries its size
  EXPECT_DOUBLE_EQ(c.begin_step(), 0.15);
  // the floor holds for a shortened step too: 1/16 here, so 0.15 → 0.075 is the last cut
  ASSERT_TRUE(c.cut());
  EXPECT_FALSE(c.cut());
  EXPECT_DOUBLE_EQ(c.size(), 0.075);
  EXPECT_NE(c.floor_note("s").find("halved 4 times, loading.max_cuts"), std::string::npos)
    << c.floor_note("s");
  StepController d(1.0, 2, 1);
  d.begin_step(0.3);
  d.accept();  // no cut: the carried size stays the nominal
  EXPECT_DOUBLE_EQ(d.begin_step(), 1.0);
}

TEST(StepController, RefusesANonPositiveNominal)
{
  EXPECT_THROW(StepController(0.0, 3, 2), std::invalid_argument);
  EXPECT_THROW(StepController(-1.0, 3, 2), std::invalid_argument);
  EXPECT_THROW(StepController(1.0, 3, 0), std::invalid_argument);
}

// A restart file keeps what carries between steps (solve/rolling_restart.h): restored, a
// controller grows and cuts as the one it was taken from; a size outside (0, nominal] is refused.
TEST(StepController, ARestoredControllerGoesOnAsTheOriginal)
{
  StepController a(1.0, 4, 2);
  a.begin_step();
  ASSERT_TRUE(a.cut());
  ASSERT_TRUE(a.cut());
  a.accept();  // carries 0.25
  a.begin_step();
  a.accept();  // one easy step of two
  StepController b(1.0, 4, 2);
  b.restore(a.carried());
  for (StepController *c : {&a, &b})
    {
      EXPECT_DOUBLE_EQ(c->begin_step(), 0.25);
      c->accept();  // the second easy step: grows
      EXPECT_DOUBLE_EQ(c->begin_step(), 0.5);
    }
  EXPECT_THROW(b.restore({0.0, 0}), std::invalid_argument);
  EXPECT_THROW(b.restore({2.0, 0}), std::invalid_argument);
}
