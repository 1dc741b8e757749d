// Hysteresis damping of a contact force (SPEC §4). Every model here has the form
//
//     F = F_el(δ) · [1 + χ(c_e) · δ̇ / δ̇⁻]
//
// with δ̇ the penetration rate (> 0 approaching), δ̇⁻ the rate at the start of the impact, and
// χ depending on the coefficient of restitution c_e:
//   Lankarani–Nikravesh (1990):  χ = 3(1 − c_e²)/4
//   Hunt–Crossley (1975):        χ = 3(1 − c_e)/2
//   Flores et al. (2011):        χ = 8(1 − c_e)/(5·c_e)
//   Gonthier et al. (2004):      χ = (1 − c_e²)/c_e
//   none:                        χ = 0
// The scene always names the model: there is no silent default.
#pragma once

#include <string>
#include <vector>

namespace clearjoint::laws
{
  enum class DampingModel
  {
    none,
    lankarani_nikravesh,
    hunt_crossley,
    flores,
    gonthier,
  };

  /// Names as written in scene files.
  DampingModel parse_damping_model(const std::string &name);
  std::string to_string(DampingModel model);
  std::vector<std::string> damping_model_names();

  /// χ(c_e) [1] for c_e in (0, 1]; throws InputError naming "restitution" otherwise.
  double hysteresis_factor(DampingModel model, double restitution);

  /// [N] F_el·(1 + χ·δ̇/δ̇⁻), never negative (a contact pushes, it never pulls: with strong
  /// damping the bracket can turn negative near separation, and the force is then 0).
  /// delta_dot_impact (δ̇⁻) must be > 0; F_el in N; rates in m/s.
  double damped_force(double elastic_force, double chi, double delta_dot,
                      double delta_dot_impact);

  /// [N] the dissipative part alone, F_el·χ·δ̇/δ̇⁻ (before the no-pull limit), for the
  /// bookkeeping of damping work.
  double damping_force(double elastic_force, double chi, double delta_dot,
                       double delta_dot_impact);
} // namespace clearjoint::laws
