// The one root finder of fe_stage's steppers: the root of an increasing scalar function g whose
// every evaluation is a whole FE solve (the impact study's journal position, the rolling
// study's journal spin), so evaluations are few and counted. No deal.II; unit-tested in
// tests/unit/fe/root_finder_test.cc.
//
// Method: bracket (from two points, moving the end on the wrong side outward by the secant's
// distance to the root, ×1.2, between ½ and 10 widths), then the Illinois variant of regula
// falsi (the end kept twice in a row has its value halved), bisection where round-off puts the
// secant outside the bracket. The model's state after a call is that of the last evaluation,
// which is RootResult::x: callers rely on it.
#pragma once

#include <functional>
#include <string>

namespace clearjoint::fe
{
  struct RootResult
  {
    bool converged = false;
    double x = 0.0, g = 0.0;  // the last evaluation
    double slope = 0.0;       // the secant slope of the last two evaluations (0: one only)
    unsigned int evaluations = 0;
    std::string message;  // why it did not converge (names `what`)
  };

  /// What to find: g increasing in x; converged when |g| ≤ g_tolerance or the bracket is
  /// narrower than x_tolerance (0: |g| alone decides); at most max_evaluations calls of g in
  /// all. `what` names g in the failure message ("the journal's torque balance").
  /// With g_scale_from_first, g_tolerance is relative: to max(|g(first point)|, g_scale_floor),
  /// for a g whose scale is known only once it has been evaluated (the impact study's force).
  struct IncreasingRoot
  {
    std::function<double(double)> g;
    double g_tolerance = 0.0;
    double x_tolerance = 0.0;
    unsigned int max_evaluations = 50;
    std::string what = "g";
    bool g_scale_from_first = false;
    double g_scale_floor = 0.0;
  };

  /// From the two points a and b (any order; equal: b = a + max(x_tolerance, 1e-12)).
  RootResult solve_increasing(const IncreasingRoot &problem, double a, double b);

  /// From one point x0 and a guess of g's slope there (> 0; e.g. the last solve's `slope`
  /// when g changes little between calls, or a known part of g's slope): the second point is
  /// the Newton step x0 − g(x0)/slope_guess, at least x_tolerance long; then as above.
  RootResult solve_increasing_from(const IncreasingRoot &problem, double x0, double slope_guess);
}  // namespace clearjoint::fe
