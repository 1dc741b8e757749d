#include "common/log.h"

#include <gtest/gtest.h>

#include <thread>

using namespace clearjoint;

TEST(Progress, FractionAndEta)
{
  log::set_level(log::Level::quiet);  // keep test output clean
  log::Progress p("test", 10.0, "steps");
  EXPECT_LT(p.eta_seconds(), 0.0) << "ETA unknown before any progress";
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  p.update(5.0);
  EXPECT_DOUBLE_EQ(p.fraction(), 0.5);
  // Half done after t seconds → about t seconds left (the mean rate).
  EXPECT_NEAR(p.eta_seconds(), p.elapsed_seconds(), 0.01);
  p.update(20.0);
  EXPECT_DOUBLE_EQ(p.fraction(), 1.0) << "fraction is capped at 1";
  log::set_level(log::Level::info);
}

TEST(Log, FormatDuration)
{
  EXPECT_EQ(log::format_duration(1.25), "1.2 s");
  EXPECT_EQ(log::format_duration(125), "2 min 05 s");
  EXPECT_EQ(log::format_duration(3720), "1 h 02 min");
  EXPECT_EQ(log::format_duration(-1), "?");
}

TEST(Log, WarningsAreCounted)
{
  log::set_level(log::Level::quiet);
  const unsigned int before = log::n_warnings();
  log::warning("x");
  EXPECT_EQ(log::n_warnings(), before + 1);
  log::set_level(log::Level::info);
}
