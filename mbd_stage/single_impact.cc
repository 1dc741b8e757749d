#include "mbd_stage/single_impact.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::mbd
{
  namespace
  {
    void check(const SingleImpact &s)
    {
      if (!(std::isfinite(s.mass) && s.mass > 0.0))
        throw InputError("", "mass", format_value(s.mass), "(0, inf) kg");
      if (!(std::isfinite(s.velocity) && s.velocity > 0.0))
        throw InputError("", "velocity", format_value(s.velocity), "(0, inf) m/s");
      if (!(std::isfinite(s.law.K) && s.law.K > 0.0))
        throw InputError("", "K", format_value(s.law.K), "(0, inf) N/m^n");
      if (!(std::isfinite(s.law.n) && s.law.n > 0.0))
        throw InputError("", "n", format_value(s.law.n), "(0, inf)");
    }
  } // namespace

  double undamped_delta_max(const double mass, const double velocity, const laws::PowerLaw &law)
  {
    const double n = law.n;
    return std::pow((n + 1.0) * mass * velocity * velocity / (2.0 * law.K), 1.0 / (n + 1.0));
  }

  double undamped_contact_duration(const double mass, const double velocity,
                                   const laws::PowerLaw &law)
  {
    // t_c = 2 ∫₀^δmax dδ / √(v² − 2Kδ^(n+1)/((n+1)m)) = 2 (δmax/v) ∫₀¹ dx/√(1 − x^(n+1))
    const double a = 1.0 / (law.n + 1.0);
    const double integral =
      std::sqrt(M_PI) * std::exp(std::lgamma(1.0 + a) - std::lgamma(0.5 + a));
    return 2.0 * undamped_delta_max(mass, velocity, law) / velocity * integral;
  }

  SingleImpactResult simulate_single_impact(const SingleImpact &s, const bool keep_history)
  {
    check(s);
    const double chi = laws::hysteresis_factor(s.damping, s.restitution);
    const double v0 = s.velocity;
    auto force = [&](const double d, const double r) {
      if (d <= 0.0)
        return 0.0;
      return laws::damped_force(s.law.force(d), chi, r, v0);
    };
    // state (δ, δ̇); δ̈ = −F/m
    auto accel = [&](const double d, const double r) { return -force(d, r) / s.mass; };
    const double t_ref = undamped_contact_duration(s.mass, v0, s.law);
    const double h = t_ref / 20000.0;
    const unsigned long max_steps = 50ul * 20000ul;
    SingleImpactResult out;
    double t = 0.0, d = 0.0, r = v0;
    if (keep_history)
      out.history.push_back({0.0, 0.0, v0, 0.0});
    for (unsigned long k = 0; k < max_steps; ++k)
      {
        const double k1d = r, k1r = accel(d, r);
        const double k2d = r + 0.5 * h * k1r, k2r = accel(d + 0.5 * h * k1d, r + 0.5 * h * k1r);
        const double k3d = r + 0.5 * h * k2r, k3r = accel(d + 0.5 * h * k2d, r + 0.5 * h * k2r);
        const double k4d = r + h * k3r, k4r = accel(d + h * k3d, r + h * k3r);
        const double d_new = d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        const double r_new = r + h / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r);
        ++out.steps;
        if (d_new <= 0.0 && r_new < 0.0 && k > 0)
          {
            // separation inside this step: the root of the cubic Hermite interpolant of δ(t)
            // on [t, t + h] (δ, δ̇ at both ends), by bisection on θ ∈ (0, 1]
            auto hermite = [&](const double th) {
              const double h00 = 2 * th * th * th - 3 * th * th + 1, h10 = th * th * th - 2 * th * th + th;
              const double h01 = -2 * th * th * th + 3 * th * th, h11 = th * th * th - th * th;
              return h00 * d + h10 * h * r + h01 * d_new + h11 * h * r_new;
            };
            double lo = 0.0, hi = 1.0;
            for (int i = 0; i < 60; ++i)
              (hermite(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
            const double th = 0.5 * (lo + hi);
            out.contact_duration = t + th * h;
            // δ̇ there: the derivative of the interpolant
            const double dh00 = 6 * th * th - 6 * th, dh10 = 3 * th * th - 4 * th + 1;
            const double dh01 = -6 * th * th + 6 * th, dh11 = 3 * th * th - 2 * th;
            const double rate = (dh00 * d + dh10 * h * r + dh01 * d_new + dh11 * h * r_new) / h;
            out.velocity_out = -rate;
            out.restitution = out.velocity_out / v0;
            if (keep_history)
              out.history.push_back({out.contact_duration, 0.0, rate, 0.0});
            return out;
          }
        t += h;
        d = d_new;
        r = r_new;
        const double F = force(d, r);
        if (F > out.peak_force)
          {
            out.peak_force = F;
            out.time_of_peak = t;
          }
        out.delta_max = std::max(out.delta_max, d);
        if (keep_history && k % 100 == 99)
          out.history.push_back({t, d, r, F});
      }
    throw NumericalError("single impact: the mass has not left the contact after " +
                         format_value(50.0 * t_ref) + " s (50 undamped contact durations)");
  }

  double fit_restitution_coefficient(SingleImpact s, const double target)
  {
    if (!(target > 0.0 && target <= 1.0))
      throw InputError("", "restitution (target)", format_value(target), "(0, 1]");
    const std::string model = laws::to_string(s.damping);
    if (s.damping == laws::DampingModel::none)
      throw InputError("", "damping", model, "a damping model", "'none' has no c_e to fit");
    auto e_of = [&](const double c) {
      s.restitution = c;
      return simulate_single_impact(s).restitution;
    };
    double lo = 1e-3, hi = 1.0;
    const double e_lo = e_of(lo);
    if (target < e_lo)
      throw InputError("", "restitution (target)", format_value(target),
                       "[" + format_value(e_lo) + ", 1] for damping " + model,
                       "the model's damping factor is bounded: with c_e = 0.001 its impact "
                       "still returns " + format_value(e_lo) + " of the speed");
    for (int i = 0; i < 60 && hi - lo > 1e-15; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        (e_of(mid) < target ? lo : hi) = mid;
      }
    return 0.5 * (lo + hi);
  }
} // namespace clearjoint::mbd
