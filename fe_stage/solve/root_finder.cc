#include "fe_stage/solve/root_finder.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::fe
{
  namespace
  {
    // Counts every call of g in r, and keeps the secant slope of the last two calls (the
    // local slope near the root once converged: the next step's first guess).
    struct Evaluator
    {
      const std::function<double(double)> &g;
      RootResult &r;
      double operator()(const double x)
      {
        const double x_prev = r.x, g_prev = r.g;
        ++r.evaluations;
        r.x = x;
        r.g = g(x);
        if (r.evaluations > 1 && x != x_prev && std::isfinite(r.g) && std::isfinite(g_prev))
          r.slope = (r.g - g_prev) / (x - x_prev);
        return r.g;
      }
    };

    // |g| below which g is taken as 0, once g has been evaluated at the first point
    double absolute_tolerance(const IncreasingRoot &p, const double g_first)
    {
      return p.g_scale_from_first ? p.g_tolerance * std::max(std::abs(g_first), p.g_scale_floor) :
                                    p.g_tolerance;
    }

    // From two evaluated points a < b: widen to a bracket, then Illinois, to |g| ≤ tol.
    void bracket_and_refine(const IncreasingRoot &p, const double tol, Evaluator &eval,
                            RootResult &r, double a, double ga, double b, double gb)
    {
      // bracket: g increasing, so move the end on the wrong side outward, by the secant's
      // distance to the root times 1.2 (a near-linear g is bracketed in one step out, where
      // doubling took up to three a step in the rolling study's torque balance), at least
      // half and at most 10 times the last width (g flat or curved: no jump far off, no
      // crawling)
      double width = b - a;
      while (ga > 0.0 || gb < 0.0)
        {
          if (r.evaluations >= p.max_evaluations || !std::isfinite(ga) || !std::isfinite(gb))
            {
              r.message = "no sign change of " + p.what + " found in " +
                          std::to_string(r.evaluations) + " evaluations";
              return;
            }
          const double slope = (gb - ga) / (b - a);
          const double to_root = slope > 0.0 ? 1.2 * (ga > 0.0 ? ga : -gb) / slope : 2.0 * width;
          width = std::clamp(to_root, 0.5 * width, 10.0 * width);
          if (ga > 0.0)
            {
              b = a, gb = ga;
              a = b - width;
              ga = eval(a);
              if (std::abs(ga) <= tol)
                {
                  r.converged = true;
                  return;
                }
            }
          else
            {
              a = b, ga = gb;
              b = a + width;
              gb = eval(b);
              if (std::abs(gb) <= tol)
                {
                  r.converged = true;
                  return;
                }
            }
        }
      // Illinois: halve the kept end's value when the same end is kept twice
      int side = 0;
      while (r.evaluations < p.max_evaluations)
        {
          double x = (a * gb - b * ga) / (gb - ga);
          if (!(x > a && x < b))
            x = 0.5 * (a + b);
          const double gx = eval(x);
          if (std::abs(gx) <= tol || b - a <= p.x_tolerance)
            {
              r.converged = true;
              return;
            }
          if (gx < 0.0)
            {
              a = x, ga = gx;
              if (side == -1)
                gb *= 0.5;
              side = -1;
            }
          else
            {
              b = x, gb = gx;
              if (side == +1)
                ga *= 0.5;
              side = +1;
            }
        }
      r.message = p.what + " did not converge in " + std::to_string(p.max_evaluations) +
                  " evaluations (bracket " + format_value(a) + " .. " + format_value(b) +
                  ", |residual| " + format_value(std::abs(r.g)) + ")";
    }
  }  // namespace

  RootResult solve_increasing(const IncreasingRoot &p, double a, double b)
  {
    RootResult r;
    Evaluator eval{p.g, r};
    if (a > b)
      std::swap(a, b);
    if (!(b > a))
      b = a + std::max(p.x_tolerance, 1e-12);
    const double ga = eval(a);
    const double tol = absolute_tolerance(p, ga);
    if (std::abs(ga) <= tol)
      return r.converged = true, r;
    const double gb = eval(b);
    if (std::abs(gb) <= tol)
      return r.converged = true, r;
    bracket_and_refine(p, tol, eval, r, a, ga, b, gb);
    return r;
  }

  RootResult solve_increasing_from(const IncreasingRoot &p, const double x0,
                                   const double slope_guess)
  {
    RootResult r;
    Evaluator eval{p.g, r};
    const double g0 = eval(x0);
    const double tol = absolute_tolerance(p, g0);
    if (std::abs(g0) <= tol)
      return r.converged = true, r;
    // the second point: a Newton step with the guessed slope, at least x_tolerance long; with
    // no usable slope a step of x_tolerance (or 1e-12 of x0's size) toward the root's side
    double step = -g0 / slope_guess;
    if (!std::isfinite(step) || !(slope_guess > 0.0))
      {
        const double least = std::max(p.x_tolerance, 1e-12 * std::max(1.0, std::abs(x0)));
        step = g0 > 0.0 ? -least : least;
      }
    else if (std::abs(step) < p.x_tolerance)
      step = std::copysign(p.x_tolerance, step);
    const double x1 = x0 + step;
    const double g1 = eval(x1);
    if (std::abs(g1) <= tol)
      return r.converged = true, r;
    if (x1 > x0)
      bracket_and_refine(p, tol, eval, r, x0, g0, x1, g1);
    else
      bracket_and_refine(p, tol, eval, r, x1, g1, x0, g0);
    return r;
  }
}  // namespace clearjoint::fe
