#include "fe_stage/solve/rolling_kinematics.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::fe::rolling
{
  Vec3 rotate_z(const Vec3 &v, const double angle)
  {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]};
  }

  double Motion::delta(const double t) const
  {
    return delta_max * std::clamp(t / ramp_time, 0.0, 1.0);
  }

  Vec3 Motion::centre_fixed(const double t) const { return {0.0, -c_r - delta(t), 0.0}; }

  Vec3 Motion::centre_frame(const double t) const { return rotate_z(centre_fixed(t), -phi(t)); }

  Vec3 journal_surface_step(const Vec3 &c0, const Vec3 &c1, const double R_J, const Vec3 &n,
                            const double delta_psi)
  {
    const Vec3 before = rotate_z(n, -delta_psi);
    Vec3 d;
    for (int k = 0; k < 3; ++k)
      d[k] = (c1[k] + R_J * n[k]) - (c0[k] + R_J * before[k]);
    return d;
  }

  double paper_angle(const Vec3 &U, const double R)
  {
    const double u = std::sqrt(U[0] * U[0] + U[1] * U[1]);  // Eq. 4: the x–y components
    return 2.0 * std::asin(std::min(1.0, 0.5 * u / R));      // Eq. 5 / 6
  }

  SlipStages slip_stages(const std::vector<double> &t, const std::vector<double> &v,
                         const double fall_fraction, const double settle_band)
  {
    SlipStages s;
    const std::size_t n = std::min(t.size(), v.size());
    if (n < 3)
      return s;
    std::size_t i_max = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(v[i]) > std::abs(v[i_max]))
        i_max = i;
    s.v_max = std::abs(v[i_max]);
    s.v_final = v[n - 1];
    if (!(s.v_max > 0.0))
      return s;
    // stage (i) ends where the relative speed first falls below fall_fraction of its largest
    // value; if it never does before the end, the stages are not located (the run ended in
    // gross slip, or the slip speed only wanders about its level)
    std::size_t i_fall = n;
    for (std::size_t i = i_max; i < n; ++i)
      if (std::abs(v[i]) < fall_fraction * s.v_max)
        {
          i_fall = i;
          break;
        }
    if (i_fall == n)
      return s;
    // stage (iii) starts after the last step outside the band about the final speed
    std::size_t i_settle = i_fall;
    for (std::size_t i = i_fall; i < n; ++i)
      if (std::abs(v[i] - s.v_final) > settle_band * s.v_max)
        i_settle = i + 1;
    s.end_of_slip = t[i_fall];
    s.settled = t[std::min(i_settle, n - 1)];
    s.found = true;
    return s;
  }

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

    // From two evaluated points a < b: widen to a bracket, then Illinois.
    void bracket_and_refine(Evaluator &eval, RootResult &r, double a, double ga, double b,
                            double gb, const double g_tolerance, const double x_tolerance,
                            const unsigned int max_evaluations)
    {
      // bracket: g increasing, so move the end on the wrong side outward, by the secant's
      // distance to the root times 1.2 (a near-linear g is bracketed in one step out, where
      // doubling took up to three a step in the rolling study's torque balance), at least
      // half and at most 10 times the last width (g flat or curved: no jump far off, no
      // crawling)
      double width = b - a;
      while (ga > 0.0 || gb < 0.0)
        {
          if (r.evaluations >= max_evaluations || !std::isfinite(ga) || !std::isfinite(gb))
            {
              r.message = "no sign change of the torque balance found in " +
                          std::to_string(r.evaluations) + " evaluations";
              return;
            }
          const double slope = (gb - ga) / (b - a);
          const double to_root = slope > 0.0 ? 1.2 * (ga > 0.0 ? ga : -gb) / slope
                                             : 2.0 * width;
          width = std::clamp(to_root, 0.5 * width, 10.0 * width);
          if (ga > 0.0)
            {
              b = a, gb = ga;
              a = b - width;
              ga = eval(a);
              if (std::abs(ga) <= g_tolerance)
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
              if (std::abs(gb) <= g_tolerance)
                {
                  r.converged = true;
                  return;
                }
            }
        }
      // Illinois: halve the kept end's value when the same end is kept twice
      int side = 0;
      while (r.evaluations < max_evaluations)
        {
          double x = (a * gb - b * ga) / (gb - ga);
          if (!(x > a && x < b))
            x = 0.5 * (a + b);
          const double gx = eval(x);
          if (std::abs(gx) <= g_tolerance || b - a <= x_tolerance)
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
      r.message = "the torque balance did not converge in " + std::to_string(max_evaluations) +
                  " evaluations (|residual| " + std::to_string(std::abs(r.g)) + ")";
    }
  } // namespace

  RootResult solve_increasing(const std::function<double(double)> &g, double a, double b,
                              const double g_tolerance, const double x_tolerance,
                              const unsigned int max_evaluations)
  {
    RootResult r;
    Evaluator eval{g, r};
    if (a > b)
      std::swap(a, b);
    if (!(b > a))
      b = a + std::max(x_tolerance, 1e-12);
    const double ga = eval(a);
    if (std::abs(ga) <= g_tolerance)
      return r.converged = true, r;
    const double gb = eval(b);
    if (std::abs(gb) <= g_tolerance)
      return r.converged = true, r;
    bracket_and_refine(eval, r, a, ga, b, gb, g_tolerance, x_tolerance, max_evaluations);
    return r;
  }

  RootResult solve_increasing_from(const std::function<double(double)> &g, const double x0,
                                   const double slope_guess, const double g_tolerance,
                                   const double x_tolerance, const unsigned int max_evaluations)
  {
    RootResult r;
    Evaluator eval{g, r};
    const double g0 = eval(x0);
    if (std::abs(g0) <= g_tolerance)
      return r.converged = true, r;
    // the second point: a Newton step with the guessed slope (at least x_tolerance long)
    double step = -g0 / slope_guess;
    const double least = std::max(x_tolerance, 1e-12);
    if (!std::isfinite(step) || !(slope_guess > 0.0))
      step = g0 > 0.0 ? -least : least;
    else if (std::abs(step) < least)
      step = std::copysign(least, step);
    const double x1 = x0 + step;
    const double g1 = eval(x1);
    if (std::abs(g1) <= g_tolerance)
      return r.converged = true, r;
    if (x1 > x0)
      bracket_and_refine(eval, r, x0, g0, x1, g1, g_tolerance, x_tolerance, max_evaluations);
    else
      bracket_and_refine(eval, r, x1, g1, x0, g0, g_tolerance, x_tolerance, max_evaluations);
    return r;
  }
} // namespace clearjoint::fe::rolling
