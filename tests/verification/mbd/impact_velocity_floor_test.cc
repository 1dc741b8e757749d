// The floor of the impact velocity δ̇⁻ (issue 14, item 3): a scene parameter
// (normal.min_impact_velocity, m/s, default 1e-4) whose use the summary counts per contact.
#include "scene_fixture.h"

#include <gtest/gtest.h>

using namespace clearjoint;
using namespace clearjoint::mbd;
using namespace clearjoint::mbd::testing;

TEST(ImpactVelocityFloor, CountedWhenActiveAndSilentAtTheDefault)
{
  // The damped FE scene's onsets fall in a bouncing series down to 6.6e-4 m/s (measured): the
  // default floor (1e-4 m/s) never acts, one of 1e-2 m/s acts on the slow end of the series.
  nlohmann::json d = load_scene("slider_crank_fe_law_damped");
  d["clearance_joints"][0]["normal"].erase("min_impact_velocity");  // the reader's default
  const SimulationResult def = run(d);
  ASSERT_TRUE(def.complete) << def.failure;
  const nlohmann::json &f0 = def.summary["clearance_joints"][0]["impact_velocity_floor"];
  EXPECT_DOUBLE_EQ(f0["radial"].get<double>(), 1e-4);
  EXPECT_EQ(f0["n_onsets_floored"]["radial"].get<long>(), 0);
  long slow = 0;  // onsets slower than 1e-2 m/s, from the event list
  for (const ContactEvent &e : def.events)
    slow += e.onset && e.contact == 0 && e.delta_dot < 1e-2 ? 1 : 0;
  ASSERT_GT(slow, 0);

  d["clearance_joints"][0]["normal"]["min_impact_velocity"] = 1e-2;
  const SimulationResult high = run(d);
  ASSERT_TRUE(high.complete) << high.failure;
  const nlohmann::json &f1 = high.summary["clearance_joints"][0]["impact_velocity_floor"];
  EXPECT_DOUBLE_EQ(f1["radial"].get<double>(), 1e-2);
  // The motion differs once the floor acts, so the series is not the same: count from the
  // run's own events.
  long slow_high = 0;
  for (const ContactEvent &e : high.events)
    slow_high += e.onset && e.contact == 0 && e.delta_dot < 1e-2 ? 1 : 0;
  EXPECT_GT(slow_high, 0);
  EXPECT_EQ(f1["n_onsets_floored"]["radial"].get<long>(), slow_high);
}
