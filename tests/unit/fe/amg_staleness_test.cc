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

TEST(AmgStaleness, ASolveIsStoppedOnceItHasLostABuildNotBefore)
{
  AmgStaleness s;
  // before any solve has set the rate, nothing is stale, however long the solve
  EXPECT_FALSE(s.stale_within(1000, 1.0, 0.5));
  s.record(20, 1.0, 1e-6);  // 20 over 6 decades: 10/3 per decade
  // 10 iterations for one decade: 6.67 lost, fewer than a build (10)
  EXPECT_FALSE(s.stale_within(10, 1.0, 0.1));
  // 20 iterations for one decade: 16.7 lost
  EXPECT_TRUE(s.stale_within(20, 1.0, 0.1));
  // a residual that grew counts as no progress: 11 iterations lost
  EXPECT_TRUE(s.stale_within(11, 1.0, 2.0));
  // at the fresh rate a solve goes on whatever its length
  EXPECT_FALSE(s.stale_within(40, 1.0, 1e-12));
}

TEST(AmgStaleness, IterationsLostInEarlierSolvesCountWithinTheNext)
{
  AmgStaleness s;
  s.record(40, 1.0, 1e-10);  // 4 per decade
  s.record(46, 1.0, 1e-10);  // 6 lost
  EXPECT_FALSE(s.stale());
  // 4 more lost in this solve would not stop it alone, but with the 6 before it they are a
  // build's worth (10), and one more iteration tips it
  EXPECT_FALSE(s.stale_within(12, 1.0, 0.01));  // 4 lost: 10 in all, not more
  EXPECT_TRUE(s.stale_within(13, 1.0, 0.01));   // 5 lost: 11
  s.built();                                    // a fresh AMG: its first solve sets the rate
  EXPECT_FALSE(s.stale_within(1000, 1.0, 0.5));
}
