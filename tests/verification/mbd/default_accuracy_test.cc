// The shipped integrator defaults against a tight run (issue 14, item 1; SPEC §5 raised
// targets): on the paper's 0.1 s scenes the slider velocity within 1e-4 m/s over 0–20 ms and
// the first-impact peak force within 0.1 % of a run at rtol 1e-12. Checked on the FE law with
// damping (the example) and the energy check (the most sensitive at rtol 1e-10, where
// a 1.7e-10 s shift of its second impact grew to 8e-4 m/s by 15 ms). Measured 2026-11-23 at
// the defaults (rtol 1e-11): 4.2e-6 and 5.7e-6 m/s (docs/benchmarks.md).
#include "scene_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace clearjoint;
using namespace clearjoint::mbd;
using namespace clearjoint::mbd::testing;

TEST(DefaultAccuracy, SliderVelocityAndFirstImpactPeakAgainstRtol1e12)
{
  for (const char *name : {"slider_crank_fe_law_damped", "slider_crank_energy_check"})
  {
    nlohmann::json d = load_scene(name);
    d["duration"] = 0.02;  // s: the SPEC's window (several impacts; later the motion is chaotic)
    const SimulationResult def = run(d);
    d["integrator"]["rtol"] = 1e-12;
    d["integrator"]["atol_position"] = 1e-14;  // m
    d["integrator"]["atol_velocity"] = 1e-11;  // m/s
    const SimulationResult tight = run(d);
    ASSERT_TRUE(def.complete && tight.complete) << name;
    const auto v = def.column("slider_velocity"), v_ref = tight.column("slider_velocity");
    ASSERT_EQ(v.size(), v_ref.size()) << name;  // the same output grid
    ASSERT_GT(v.size(), 2000u);
    double err = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i)
      err = std::max(err, std::abs(v[i] - v_ref[i]));
    EXPECT_LT(err, 1e-4) << name;  // m/s, the requirement itself
    ASSERT_GT(tight.first_impact_peak_force, 1000.0) << name;
    EXPECT_NEAR(def.first_impact_peak_force / tight.first_impact_peak_force, 1.0, 1e-3) << name;
  }
}
