// The MBD half of the impact check (issue 12 item 4): one impact of a rigid mass m at v_in
// against a contact law, m δ̈ = −F(δ, δ̇), δ(0) = 0, δ̇(0) = v_in > 0, until the mass leaves
// (δ back to 0, moving away). F = F_el(δ)·(1 + χ(c_e) δ̇/δ̇⁻) with F_el = K δ^n from a law file
// and the hysteresis damping models of laws/damping.h; δ̇⁻ = v_in. This is what an MBD contact
// model does with one impact of the journal on the bearing, with the bearing rigid and massless
// — the FE impact study does the same impact with the bearing's elasticity and inertia.
//
// Integration: classical Runge–Kutta (4th order) with a fixed step of 1/20000 of the undamped
// contact duration's closed form, the separation located inside its step by cubic Hermite
// interpolation of δ(t). Checked against the closed forms of the undamped impact (δ_max, the
// contact duration for any n, restitution 1) in tests/verification/mbd/single_impact_test.cc.
//
// Units: SI (m, s, kg, N).
#pragma once

#include "laws/damping.h"
#include "laws/power_law.h"

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  struct SingleImpact
  {
    double mass = 0.0;       ///< [kg] > 0
    double velocity = 0.0;   ///< [m/s] approach speed at first touch, > 0
    laws::PowerLaw law;      ///< F_el = K δ^n
    laws::DampingModel damping = laws::DampingModel::none;
    double restitution = 1.0;  ///< [1] the damping model's c_e in (0, 1]
  };

  struct ImpactSample
  {
    double time, delta, delta_rate, force;  ///< [s], [m], [m/s], [N]
  };

  struct SingleImpactResult
  {
    double peak_force = 0.0;        ///< [N]
    double time_of_peak = 0.0;      ///< [s]
    double delta_max = 0.0;         ///< [m]
    double contact_duration = 0.0;  ///< [s] from first touch to separation
    double velocity_out = 0.0;      ///< [m/s] speed away at separation
    double restitution = 0.0;       ///< [1] v_out / v_in
    unsigned int steps = 0;
    std::vector<ImpactSample> history;  ///< every 100th step (and the ends), if asked for
  };

  /// The undamped impact's closed forms: δ_max = ((n+1) m v² / (2K))^(1/(n+1)) [m] and the
  /// contact duration 2 (δ_max/v) √π Γ(1 + 1/(n+1)) / Γ(1/2 + 1/(n+1)) [s] (π √(m/K) for n = 1).
  double undamped_delta_max(double mass, double velocity, const laws::PowerLaw &law);
  double undamped_contact_duration(double mass, double velocity, const laws::PowerLaw &law);

  /// Simulates the impact. Throws InputError (field names "mass", "velocity", "K", "n",
  /// "restitution") for values outside their ranges, NumericalError if the mass has not left
  /// after 50 closed-form durations (a damping that holds it: cannot happen for c_e > 0).
  SingleImpactResult simulate_single_impact(const SingleImpact &impact, bool keep_history = false);

  /// The c_e in (0, 1] of `impact.damping` for which the impact's restitution v_out/v_in is
  /// `target` (bisection, 60 halvings: c_e to 1e-15; the restitution grows with c_e). Throws
  /// InputError if the target is outside (0, 1] or the model cannot reach it (Lankarani–
  /// Nikravesh and Hunt–Crossley bound χ, so low restitutions are out of their reach), naming
  /// the model and the lowest restitution it reaches.
  double fit_restitution_coefficient(SingleImpact impact, double target);
} // namespace clearjoint::mbd
