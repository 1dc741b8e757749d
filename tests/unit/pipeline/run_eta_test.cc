// run_pipeline's "task k of N" and time left: from the preset's measured times, then from what
// the run measures, with reused tasks costing nothing.
#include "pipeline/run_eta.h"

#include <gtest/gtest.h>

using namespace clearjoint::pipeline;

TEST(RunEta, StartsFromThePresetsMeasuredTimes)
{
  // 10 FE curves of 12.5 s each; the measured pipeline (185 s) leaves 60 s for 20 other tasks
  // (numbers exact in binary, so the printed duration is not at the mercy of round-off).
  const RunEta eta({{"fe_stage", 10}, {"fit_stage", 12}, {"mbd_stage", 8}}, 12.5, 185.0);
  EXPECT_EQ(eta.n_total(), 30);
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_FALSE(eta.time_left()->lower_bound);
  EXPECT_NEAR(eta.time_left()->seconds, 185.0, 1e-9);  // the whole measured pipeline
  EXPECT_EQ(eta.describe_next(), "task 1 of 30, about 3 min 05 s left");
}

TEST(RunEta, WhatTheRunMeasuresReplacesThePreset)
{
  RunEta eta({{"fe_stage", 3}, {"fit_stage", 3}}, 10.0, 36.0);  // others: (36 − 30)/3 = 2 s
  eta.finished("fe_stage", true, 40.0);                       // this machine is 4× slower
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_NEAR(eta.time_left()->seconds, 2 * 40.0 + 3 * 2.0, 1e-9);
  EXPECT_EQ(eta.n_done(), 1);
  EXPECT_EQ(eta.describe_next().substr(0, 11), "task 2 of 6");
}

TEST(RunEta, ReusedTasksCostNothing)
{
  RunEta eta({{"fe_stage", 4}}, 10.0, std::nullopt);
  eta.finished("fe_stage", false, 123.0);  // reused: its recorded wall time is not this run's
  eta.finished("fe_stage", false, 123.0);
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_EQ(eta.time_left()->seconds, 0.0);
  eta.finished("fe_stage", true, 8.0);  // 1 of 3 ran: the last one is expected at 1/3 of 8 s
  EXPECT_NEAR(eta.time_left()->seconds, 8.0 / 3.0, 1e-9);
}

TEST(RunEta, UnknownCostsGiveALowerBoundOrNothing)
{
  // No preset measurements: nothing is known before the first task.
  RunEta none({{"fe_stage", 2}, {"mbd_stage", 2}}, std::nullopt, std::nullopt);
  EXPECT_FALSE(none.time_left().has_value());
  EXPECT_EQ(none.describe_next(), "task 1 of 4");
  // FE measured, the rest not (the accurate preset has no pipeline time): a lower bound.
  RunEta fe_only({{"fe_stage", 2}, {"mbd_stage", 2}}, 100.0, std::nullopt);
  ASSERT_TRUE(fe_only.time_left().has_value());
  EXPECT_TRUE(fe_only.time_left()->lower_bound);
  EXPECT_EQ(fe_only.time_left()->seconds, 200.0);
}

TEST(RunEta, MoreTasksThanPlannedRaiseTheTotal)
{
  RunEta eta({{"mbd_stage", 1}}, std::nullopt, std::nullopt);
  eta.finished("mbd_stage", true, 1.0);
  eta.finished("mbd_stage", true, 1.0);
  EXPECT_EQ(eta.n_total(), 2);
  EXPECT_EQ(eta.time_left()->seconds, 0.0);
}

// The FE impact sweep is one task of several impacts: its own measured time, not an FE curve's,
// and it is taken out of the pipeline time that the other tasks share.
TEST(RunEta, TheImpactSweepHasItsOwnTime)
{
  // others: (200 − 10·10 − 60)/4 = 10 s each
  const RunEta eta({{"fe_stage", 10}, {"fe_impact", 1}, {"fit_stage", 4}}, 10.0, 200.0, 60.0);
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_NEAR(eta.time_left()->seconds, 10 * 10.0 + 60.0 + 4 * 10.0, 1e-9);
  EXPECT_FALSE(eta.time_left()->lower_bound);
  // not measured: a lower bound (the impact's share unknown)
  const RunEta unknown({{"fe_stage", 2}, {"fe_impact", 1}}, 10.0, 50.0);
  ASSERT_TRUE(unknown.time_left().has_value());
  EXPECT_TRUE(unknown.time_left()->lower_bound);
}

// The rolling study is one task with its own measured time, like the impact sweep: taken out
// of the pipeline time the other tasks share; unknown (null) → a lower bound.
TEST(RunEta, TheRollingStudyHasItsOwnTime)
{
  // others: (200 − 10·10 − 60 − 20)/4 = 5 s each
  const RunEta eta({{"fe_stage", 10}, {"fe_impact", 1}, {"fe_rolling", 1}, {"fit_stage", 4}},
                   10.0, 200.0, 60.0, 20.0);
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_NEAR(eta.time_left()->seconds, 10 * 10.0 + 60.0 + 20.0 + 4 * 5.0, 1e-9);
  EXPECT_FALSE(eta.time_left()->lower_bound);
  RunEta unknown({{"fe_stage", 2}, {"fe_rolling", 1}, {"fit_stage", 2}}, 10.0, 50.0);
  ASSERT_TRUE(unknown.time_left().has_value());
  EXPECT_TRUE(unknown.time_left()->lower_bound);
  // (50 − 2·10)/2 = 15 s per fit: the rolling task is not one of the "others"
  EXPECT_NEAR(unknown.time_left()->seconds, 2 * 10.0 + 2 * 15.0, 1e-9);
  // once it ran, its measured time counts
  unknown.finished("fe_rolling", true, 7.0);
  EXPECT_FALSE(unknown.time_left()->lower_bound);
}

// The deformable journal's impact (issue 31 item 2) is a task of its own, like the rigid
// journal's: its measured time is its own and is taken out of what the others share; unknown →
// a lower bound until it has run.
TEST(RunEta, TheDeformableImpactHasItsOwnTime)
{
  // others: (240 − 10·10 − 60 − 40)/4 = 10 s each
  const RunEta eta({{"fe_stage", 10}, {"fe_impact", 1}, {"fe_impact_deformable", 1},
                    {"fit_stage", 4}},
                   10.0, 240.0, 60.0, std::nullopt, 40.0);
  EXPECT_EQ(eta.expected_seconds("fe_impact_deformable").value_or(-1), 40.0);
  ASSERT_TRUE(eta.time_left().has_value());
  EXPECT_NEAR(eta.time_left()->seconds, 10 * 10.0 + 60.0 + 40.0 + 4 * 10.0, 1e-9);
  EXPECT_FALSE(eta.time_left()->lower_bound);
  RunEta unknown({{"fe_stage", 2}, {"fe_impact_deformable", 1}, {"fit_stage", 2}}, 10.0, 50.0);
  EXPECT_FALSE(unknown.expected_seconds("fe_impact_deformable").has_value());
  EXPECT_TRUE(unknown.time_left()->lower_bound);
  unknown.finished("fe_impact_deformable", true, 7.0);
  EXPECT_FALSE(unknown.time_left()->lower_bound);
}

TEST(RunEta, TasksAtOnceShareTheWork)
{
  // The numbers of RunPipeline.TheRollingStudyIsOneTaskWithItsOwnTime: 2 FE cases of 1 s, the
  // rolling study 50 s, 10 other tasks sharing (80 − 2 − 50)/10 = 2.8 s each: 80 s of work.
  const std::map<std::string, int> planned = {
    {"fe_stage", 2}, {"fe_rolling", 1}, {"fit_stage", 3}, {"mbd_stage", 7}};
  RunEta eta(planned, 1.0, 80.0, std::nullopt, 50.0);
  EXPECT_NEAR(eta.time_left()->seconds, 80.0, 1e-9);
  eta.set_concurrency(4);  // 80 s over 4 slots is 20 s, but the rolling task alone takes 50 s
  EXPECT_NEAR(eta.time_left()->seconds, 50.0, 1e-9);
  RunEta no_rolling({{"fe_stage", 4}, {"fit_stage", 4}}, 10.0, 48.0);  // fits: 2 s each
  no_rolling.set_concurrency(2);
  EXPECT_NEAR(no_rolling.time_left()->seconds, 48.0 / 2, 1e-9);
  // An FE case on 2 MPI ranks takes both slots: its 40 s of work do not share.
  no_rolling.set_concurrency(2, {{"fe_stage", 2}});
  EXPECT_NEAR(no_rolling.time_left()->seconds, (4 * 10.0 * 2 + 4 * 2.0) / 2, 1e-9);
  EXPECT_EQ(no_rolling.describe_next(2), "task 3 of 8 (2 running), about 44.0 s left");
}
