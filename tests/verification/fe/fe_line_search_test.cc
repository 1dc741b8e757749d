// The material Newton iteration's line search (solver.line_search, solve/material_newton.cc).
// The scene is the paper's rolling case (§3.4: μ = 0.3, the SPEC hardening, the bearing turning
// at 12.56 rad/s) over its first four steps at 64 steps to 1 mm: 15.6 µm of push and 2.8° of
// turn a step. There the plastic zone grows fast; points switch between the elastic and the
// plastic tangent (1/740 of it) and full Newton steps overshoot: the corrections grew ×2 an
// iteration and the first step was cut twice (measured, docs/fe.md "The line search").
#include "fe_test_util.h"

#include <cmath>
#include <cstdio>

using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  const std::string paper_rolling_start =
    "study: rolling\n"
    "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
    "loading: {delta_max: 6.25e-5}\n"
    "material: {kinematics: small}\n"
    "rolling: {n_steps: 4, ramp_time: 0.015625}\n";

  unsigned int total(const RunResult &r, unsigned int RollingStepRecord::*count)
  {
    unsigned int n = 0;
    for (const auto &s : r.rolling_steps)
      n += s.*count;
    return n;
  }
}  // namespace

TEST(FeRolling, LineSearchTakesTheStepsThatFullNewtonStepsMustCut)
{
  const RunResult searched = run(scene(paper_rolling_start));
  ASSERT_TRUE(searched.complete) << searched.message;
  const RunResult full = run(scene(paper_rolling_start + "solver: {line_search: false}\n"));
  ASSERT_TRUE(full.complete) << full.message;
  const auto &a = searched.rolling_steps.back(), &b = full.rolling_steps.back();
  std::printf("line search: %zu steps, %u cuts, %u Newton iterations, %u rejected trial points, "
              "F %.6g N, wall %.1f s; full steps: %zu steps, %u cuts, %u Newton iterations, "
              "F %.6g N, wall %.1f s\n",
              searched.rolling_steps.size(), total(searched, &RollingStepRecord::cuts),
              total(searched, &RollingStepRecord::newton_iterations),
              total(searched, &RollingStepRecord::line_search_steps), a.force_normal,
              searched.wall_time, full.rolling_steps.size(), total(full, &RollingStepRecord::cuts),
              total(full, &RollingStepRecord::newton_iterations), b.force_normal, full.wall_time);
  // the premise: without the search these steps are cut
  EXPECT_GT(total(full, &RollingStepRecord::cuts), 0u);
  EXPECT_EQ(total(full, &RollingStepRecord::line_search_steps), 0u);
  // with it, no cut, and the search did shorten steps
  EXPECT_EQ(total(searched, &RollingStepRecord::cuts), 0u);
  EXPECT_GT(total(searched, &RollingStepRecord::line_search_steps), 0u);
  // The same state at the end: the two differ only in where the first step was cut (the
  // plastic history follows the path; measured 0.21 % in F, 0.12 % in ε_p max)
  EXPECT_NEAR(a.force_normal / b.force_normal, 1.0, 1e-2);
  EXPECT_NEAR(a.max_plastic_strain / b.max_plastic_strain, 1.0, 1e-2);
  EXPECT_NEAR(a.gamma_rate / b.gamma_rate, 1.0, 1e-3);  // rolling with a little slip
}
