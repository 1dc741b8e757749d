// When the AMG counts as stale (fe_stage/solve/amg_staleness.h): the iterations lost against
// its first solve's rate, summed until they outweigh one build.
#include "fe_stage/solve/amg_staleness.h"

#include <gtest/gtest.h>

using clearjoint::fe::AmgStaleness;

TEST(AmgStaleness, AFreshAmgIsNotStale)
{
  AmgStaleness s;
  EXPECT_FALSE(s.stale());
  s.record(40, 1.0, 1e-10);  // sets the rate: 4 iterations per decade
  EXPECT_FALSE(s.stale());
  EXPECT_DOUBLE_EQ(s.lost_iterations(), 0.0);
}

TEST(AmgStaleness, SolvesAtTheFreshRateLoseNothingWhateverTheirTolerance)
{
  AmgStaleness s;
  s.record(40, 1.0, 1e-10);  // 4 per decade
  s.record(24, 1.0, 1e-6);   // a loose solve at the same rate
  s.record(8, 1e-3, 1e-5);   // a short one
  s.record(30, 1.0, 1e-10);  // faster than the first: no gain is counted either
  EXPECT_DOUBLE_EQ(s.lost_iterations(), 0.0);
  EXPECT_FALSE(s.stale());
}

TEST(AmgStaleness, LostIterationsAddUpUntilTheyOutweighABuild)
{
  AmgStaleness s;
  s.record(40, 1.0, 1e-10);  // 4 per decade
  s.record(46, 1.0, 1e-10);  // 6 lost
  EXPECT_DOUBLE_EQ(s.lost_iterations(), 6.0);
  EXPECT_FALSE(s.stale());
  s.record(30, 1.0, 1e-6);  // 24 at the fresh rate: 6 more lost, 12 in all
  EXPECT_DOUBLE_EQ(s.lost_iterations(), 12.0);
  EXPECT_GT(s.lost_iterations(), AmgStaleness::rebuild_after_lost_iterations);
  EXPECT_TRUE(s.stale());
}

TEST(AmgStaleness, ABuildStartsAfresh)
{
  AmgStaleness s;
  s.record(40, 1.0, 1e-10);
  s.record(100, 1.0, 1e-10);
  ASSERT_TRUE(s.stale());
  s.built();
  EXPECT_FALSE(s.stale());
  s.record(100, 1.0, 1e-10);  // the new AMG's rate: 10 per decade
  s.record(100, 1.0, 1e-10);
  EXPECT_FALSE(s.stale());
}

TEST(AmgStaleness, ASolveThatReducesNothingSaysNothing)
{
  AmgStaleness s;
  s.record(0, 1.0, 1.0);     // a start within tolerance
  s.record(5, 1.0, 2.0);     // a residual that grew (no rate)
  s.record(5, 1.0, 0.0);     // an exact zero (no logarithm)
  s.record(40, 1.0, 1e-10);  // so this one sets the rate
  s.record(40, 1.0, 1e-10);
  EXPECT_DOUBLE_EQ(s.lost_iterations(), 0.0);
}
