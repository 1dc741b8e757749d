// The shipped integrator defaults against a tight run (issue 14, item 1; SPEC §5 raised
// targets): on each of the paper's 0.1 s scenes with a clearance joint, the slider velocity
// within 1e-4 m/s over 0–20 ms and the first-impact peak force within 0.1 % of a run at
// rtol 1e-12. Measured 2026-11-26 at the defaults (rtol 1e-11, the state at every contact event
// recomputed by a DP5 step): 1.2e-6 to 1.1e-5 m/s and peaks within 3e-6 (docs/benchmarks.md,
// `mbd_benchmark ... accuracy`); with the tolerances perturbed by one ulp (a different step
// sequence) up to 1.7e-5 m/s (Johnson). Before the event states were recomputed, the
// frictionless FE scene was 2.2e-4 m/s off at 19 ms: this test failed there.
#include "scene_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace clearjoint;
using namespace clearjoint::mbd;
using namespace clearjoint::mbd::testing;

TEST(DefaultAccuracy, SliderVelocityAndFirstImpactPeakAgainstRtol1e12)
{
  for (const char *name :
       {"slider_crank_fe_law_damped", "slider_crank_energy_check", "slider_crank_fe_law",
        "slider_crank_fe_law_frictionless", "slider_crank_johnson",
        "slider_crank_lankarani_nikravesh", "slider_crank_pereira", "slider_crank_tilted_1deg"})
  {
    nlohmann::json d = load_scene(name);
    // The scene as shipped (0.1 s): its step sequence is the one an analyst gets. (A 0.02 s run
    // takes other steps: before the event states were recomputed it passed where the 0.1 s run
    // failed.)
    const SimulationResult def = run(d);
    d["integrator"]["rtol"] = 1e-12;
    d["integrator"]["atol_position"] = 1e-14;  // m
    d["integrator"]["atol_velocity"] = 1e-11;  // m/s
    const SimulationResult tight = run(d);
    ASSERT_TRUE(def.complete && tight.complete) << name;
    const auto v = def.column("slider_velocity"), v_ref = tight.column("slider_velocity");
    ASSERT_EQ(v.size(), v_ref.size()) << name;  // the same output grid
    ASSERT_GT(v.size(), 10000u);  // rows every 1e-5 s
    const auto t = def.column("t");
    double err = 0.0;  // over 0–20 ms, the SPEC's window (several impacts; later the motion
    for (std::size_t i = 0; i < v.size() && t[i] <= 0.02 + 1e-12; ++i)  // is chaotic)
      err = std::max(err, std::abs(v[i] - v_ref[i]));
    EXPECT_LT(err, 1e-4) << name;  // m/s, the requirement itself
    ASSERT_GT(tight.first_impact_peak_force, 1000.0) << name;
    EXPECT_NEAR(def.first_impact_peak_force / tight.first_impact_peak_force, 1.0, 1e-3) << name;
  }
}
