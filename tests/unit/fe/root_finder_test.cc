// The steppers' one root finder (fe_stage/solve/root_finder.h): convergence on closed-form
// functions, the budget and the failure messages, the bracket grown from a narrow start and the
// Newton-started variant.
#include "fe_stage/solve/root_finder.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::fe;

namespace
{
  IncreasingRoot problem(std::function<double(double)> g, double g_tol, double x_tol,
                         unsigned int max_evaluations)
  {
    return {std::move(g), g_tol, x_tol, max_evaluations, "the test function"};
  }
} // namespace

TEST(RootFinder, BracketsAndConvergesOrSaysWhy)
{
  // an increasing cubic with its root outside the first bracket
  const auto g = [](double x) { return x * x * x + x - 30.0; };  // root 3
  const RootResult r = solve_increasing(problem(g, 1e-12, 1e-14, 100), 0.0, 1.0);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.x, 3.0, 1e-12);
  EXPECT_LE(std::abs(r.g), 1e-12);
  EXPECT_LT(r.evaluations, 40u);  // bracket in ~3 steps out, Illinois superlinear after
  // the root below the bracket
  const RootResult lo =
    solve_increasing(problem([](double x) { return x + 5.0; }, 1e-12, 1e-14, 100), 0.0, 1.0);
  ASSERT_TRUE(lo.converged);
  EXPECT_NEAR(lo.x, -5.0, 1e-12);
  // no root: a failure that says so and names the function, within the budget
  const RootResult none =
    solve_increasing(problem([](double) { return 1.0; }, 1e-12, 1e-14, 20), 0.0, 1.0);
  EXPECT_FALSE(none.converged);
  EXPECT_LE(none.evaluations, 20u);
  EXPECT_NE(none.message.find("no sign change of the test function"), std::string::npos)
    << none.message;
  // a root inside the bracket that the budget does not reach: says so, with the bracket
  const RootResult slow = solve_increasing(
    problem([](double x) { return std::atan(1e3 * (x - 0.3)); }, 1e-15, 0.0, 4), 0.0, 1.0);
  EXPECT_FALSE(slow.converged);
  EXPECT_EQ(slow.evaluations, 4u);
  EXPECT_NE(slow.message.find("did not converge in 4 evaluations"), std::string::npos)
    << slow.message;
  // a root a little outside a narrow bracket (the journal's spin from one step to the next):
  // the secant's step (capped at 10 widths) brackets a near-linear g in one step out, then
  // regula falsi: 7 evaluations; doubling the width took 9 (three steps out)
  const auto gq = [](double x) { return x - 10.0 + 1e-3 * x * x; };
  const double root = (-1.0 + std::sqrt(1.0 + 4e-2)) / 2e-3;
  const RootResult near = solve_increasing(problem(gq, 1e-10, 1e-14, 100), 9.0, 9.1);
  ASSERT_TRUE(near.converged) << near.message;
  EXPECT_NEAR(near.x, root, 1e-9);
  EXPECT_LE(near.evaluations, 7u);
}

TEST(RootFinder, FromOnePointAndASlopeGuess)
{
  // the Newton step lands next to the root of a near-linear g, the reported slope is g's near
  // the root, and a wrong slope guess (ten times too steep or too flat) still ends at the root
  // through the bracket
  const auto gq = [](double x) { return x - 10.0 + 1e-3 * x * x; };
  const double root = (-1.0 + std::sqrt(1.0 + 4e-2)) / 2e-3;
  const RootResult from = solve_increasing_from(problem(gq, 1e-10, 1e-14, 100), 9.0, 1.018);
  ASSERT_TRUE(from.converged) << from.message;
  EXPECT_NEAR(from.x, root, 1e-9);
  EXPECT_LE(from.evaluations, 4u);  // the two points, then one or two secants
  EXPECT_NEAR(from.slope, 1.0 + 2e-3 * root, 1e-3);  // secant of the last two: g'(root)
  for (const double guess : {10.18, 0.1018})
    {
      const RootResult off = solve_increasing_from(problem(gq, 1e-10, 1e-14, 100), 9.0, guess);
      ASSERT_TRUE(off.converged) << off.message;
      EXPECT_NEAR(off.x, root, 1e-9);
    }
  // the impact study's use: g = k (x − x̂) + f(x) with f ≥ 0 growing, the second point the
  // step with the known part k of the slope (a bracket by construction), no x tolerance: the
  // root to |g| ≤ 1e-9 of the scale, also where the step is far below 1e-12 in x's units
  const double k = 1e9, x_hat = 2e-6;
  const auto g_impact = [&](double x) { return k * (x - x_hat) + 3e14 * x * x; };
  const RootResult imp = solve_increasing_from(problem(g_impact, 1e-9 * 1e3, 0.0, 60), x_hat, k);
  ASSERT_TRUE(imp.converged) << imp.message;
  EXPECT_LE(std::abs(g_impact(imp.x)), 1e-9 * 1e3);
  EXPECT_LT(imp.x, x_hat);
}
