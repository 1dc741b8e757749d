// The end-of-run summary (issue 14, item 5): impacts of both kinds, peak force, energy drift,
// the range counter as a warning and the floor counter only when non-zero, the output place.
#include "mbd_stage/run_summary.h"

#include <gtest/gtest.h>

#include <string>

using namespace clearjoint::mbd;

namespace
{
  nlohmann::json summary(const long n_range, const long n_floored, const long n_beyond = 0)
  {
    nlohmann::json s;
    s["scene"] = "demo";
    s["status"] = "complete";
    s["t_reached"] = {{"value", 0.1}};
    s["duration"] = {{"value", 0.1}};
    s["wall_time"] = {{"value", 0.25}};
    s["step_statistics"] = {{"n_steps", 3000}, {"n_rhs_evaluations", 20000}};
    s["integrator"] = {{"method", "dopri5"}, {"rtol", 1e-11}};
    s["peaks"] = {{"contact_force_max", 3147.1}, {"contact_force_max_time", 0.00213},
                  {"first_impact_peak_force", 3147.1}, {"penetration_max", 9.7e-6}};
    s["energy"] = {{"E0", 2.5231}, {"max_relative_balance_error", 4.9e-9},
                   {"W_friction", -0.012}, {"W_damping", -0.008}, {"W_drivers", 0.0}};
    nlohmann::json cj;
    cj["name"] = "rod_slider";
    cj["n_impacts"] = {{"radial", 44}, {"axial_pos", 1}, {"axial_neg", 3}};
    cj["peak_normal_force"] = {{"value", 3659.9}};
    cj["law_out_of_range_accepted_steps"] = n_range;
    cj["normal_model"] = {{"out_of_range", {{"policy", "extend"}, {"max_delta_accepted", 6e-5}}}};
    cj["impact_velocity_floor"] = {
      {"radial", 1e-4}, {"axial", 1e-4},
      {"n_onsets_floored", {{"radial", n_floored}, {"axial_pos", 0}, {"axial_neg", 0}}}};
    cj["depth_guard"] = {
      {"allowance", 5e-5},
      {"max_delta_any_stage", {{"radial", 6.2e-5}, {"axial_pos", 0.0}, {"axial_neg", 1e-5}}},
      {"n_evaluations_beyond_allowance",
       {{"radial", n_beyond}, {"axial_pos", 0}, {"axial_neg", 0}}}};
    s["clearance_joints"] = nlohmann::json::array({cj});
    return s;
  }

  std::string join(const std::vector<std::string> &v)
  {
    std::string out;
    for (const auto &l : v)
      out += l + "\n";
    return out;
  }
} // namespace

TEST(RunSummary, ImpactsForcesEnergyAndOutputs)
{
  const RunSummaryLines l = make_run_summary(summary(0, 0), "out/x", false);
  const std::string text = join(l.info);
  EXPECT_NE(text.find("demo: complete"), std::string::npos) << text;
  EXPECT_NE(text.find("44 radial impacts, 4 face impacts (+1/-3)"), std::string::npos) << text;
  EXPECT_NE(text.find("peak normal force 3659.9 N"), std::string::npos) << text;
  EXPECT_NE(text.find("balance error max 4.9e-09"), std::string::npos) << text;
  EXPECT_NE(text.find("out/x/{timeseries.csv, summary.json, manifest.json}"), std::string::npos)
    << text;
  // Zero counters are not printed.
  EXPECT_TRUE(l.warnings.empty());
  EXPECT_EQ(text.find("floor"), std::string::npos) << text;
}

TEST(RunSummary, NonZeroCountersArePrinted)
{
  const RunSummaryLines l = make_run_summary(summary(7, 2), "out/x", true);
  ASSERT_EQ(l.warnings.size(), 1u);
  EXPECT_NE(l.warnings[0].find("7 accepted steps"), std::string::npos) << l.warnings[0];
  EXPECT_NE(l.warnings[0].find("0.06 mm"), std::string::npos) << l.warnings[0];
  const std::string text = join(l.info);
  EXPECT_NE(text.find("used at 2 of 48 onsets"), std::string::npos) << text;
  EXPECT_NE(text.find("plots/}"), std::string::npos) << text;
}

TEST(RunSummary, EvaluationsBeyondTheDepthGuardAreAWarning)
{
  // Issue 14 item 2: the explicit methods' depth guard bounds the step size; where it falls
  // short the run says so at the end.
  const RunSummaryLines l = make_run_summary(summary(0, 0, 5), "out/x", false);
  ASSERT_EQ(l.warnings.size(), 1u);
  EXPECT_NE(l.warnings[0].find("5 force evaluations"), std::string::npos) << l.warnings[0];
  EXPECT_NE(l.warnings[0].find("50 um"), std::string::npos) << l.warnings[0];
  EXPECT_NE(l.warnings[0].find("deepest 62 um"), std::string::npos) << l.warnings[0];
}
