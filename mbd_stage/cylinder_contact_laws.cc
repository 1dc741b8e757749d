#include "mbd_stage/cylinder_contact_laws.h"

#include "common/error.h"
#include "common/units.h"

#include <cmath>

namespace clearjoint::mbd
{
  double effective_modulus(const double E1, const double nu1, const double E2, const double nu2)
  {
    return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
  }

  laws::PowerLaw hertz_cylinder_law(const double R_B, const double R_J, const double E_star)
  {
    // SPEC §4: K = (4/3)·E*·√(R_B·R_J/(R_B − R_J)), n = 3/2 (Lankarani–Nikravesh 1990 form).
    return {(4.0 / 3.0) * E_star * std::sqrt(R_B * R_J / (R_B - R_J)), 1.5};
  }

  double pereira_Y(const double dR)
  {
    if (dR >= 0.005 && dR < 0.34955)
      return 1.51 * std::pow(std::log(1000.0 * dR), -0.151);
    if (dR >= 0.34955 && dR <= 10.1)
      return 0.0151 * dR + 1.151;
    throw InputError("", "pereira.delta_R", format_value(dR) + " mm", "[0.005, 10.1] mm",
                     "Pereira et al. fitted Y(ΔR) only on this range");
  }

  laws::PowerLaw pereira_law(const double R_B, const double R_J, const double L,
                             const double E_star, const PereiraParameters &p)
  {
    // Pereira et al. (2011): evaluated with lengths in mm and E* in N/mm², then converted.
    const double dR = units::to_mm(R_B - R_J), L_mm = units::to_mm(L), E_mm = E_star / units::MPa;
    const double n = pereira_Y(dR) * std::pow(dR, p.exponent_of_clearance);
    const double K_mm = (p.a * dR + p.b) * L_mm * E_mm / dR;  // N/mm^n
    return {units::power_law_K_mm_to_SI(K_mm, n), n};
  }

  JohnsonLaw::JohnsonLaw(const double delta_R, const double L, const double E_star)
    : dR_(delta_R)
    , L_(L)
    , E_(E_star)
  {
    if (!(delta_R > 0.0 && L > 0.0 && E_star > 0.0))
      throw InputError("", "johnson", "ΔR=" + format_value(delta_R) + " L=" + format_value(L),
                       "ΔR > 0 m, L > 0 m, E* > 0 Pa");
    F_peak_ = 4.0 * units::pi * L * E_star * delta_R / std::exp(2.0);
    delta_peak_ = 4.0 * delta_R / std::exp(2.0);
  }

  double JohnsonLaw::penetration(const double F) const
  {
    if (F <= 0.0)
      return 0.0;
    const double x = F / (units::pi * L_ * E_);  // [m]
    return x * (std::log(4.0 * dR_ / x) - 1.0);
  }

  double JohnsonLaw::force(const double delta, bool *beyond_peak) const
  {
    if (beyond_peak)
      *beyond_peak = false;
    if (delta <= 0.0)
      return 0.0;
    if (delta >= delta_peak_)
    {
      if (beyond_peak)
        *beyond_peak = delta > delta_peak_;
      return F_peak_;
    }
    // With x = F/(πLE*) and x = 4ΔR·e^{−(1+u)}, δ = x(ln(4ΔR/x) − 1) becomes
    // g(u) = u − ln u + c = 0 with c = ln(e·δ/(4ΔR)) ≤ −1, on the branch u ≥ 1 (the branch
    // through the origin: u → ∞ as δ → 0). g is convex and increasing for u > 1, so Newton from
    // a point right of the root, u0 = 2(−c) + 2 (g(u0) > 0), decreases monotonically to it.
    const double c = std::log(std::exp(1.0) * delta / (4.0 * dR_));
    double u = 2.0 * (-c) + 2.0;
    for (int it = 0; it < 100; ++it)
    {
      const double g = u - std::log(u) + c, dg = 1.0 - 1.0 / u;
      if (dg <= 0.0)
        break;  // at the peak (u = 1)
      const double step = g / dg;
      u = std::max(1.0, u - step);
      if (std::abs(step) <= 1e-15 * u)
        break;
    }
    const double x = 4.0 * dR_ * std::exp(-(1.0 + u));
    return units::pi * L_ * E_ * x;
  }

  double JohnsonLaw::energy(const double delta) const
  {
    if (delta <= 0.0)
      return 0.0;
    const double d = std::min(delta, delta_peak_);
    const double F = force(d);
    const double piLE = units::pi * L_ * E_, A = 4.0 * piLE * dR_;
    // ∫₀^δ F dδ' = F·δ − ∫₀^F δ(F') dF'  (integration by parts),
    // ∫₀^F δ dF' = F²/(πLE*)·[ln(A/F)/2 − 1/4].
    const double e = F * d - F * F / piLE * (0.5 * std::log(A / F) - 0.25);
    return e + (delta > delta_peak_ ? F_peak_ * (delta - delta_peak_) : 0.0);
  }
} // namespace clearjoint::mbd
