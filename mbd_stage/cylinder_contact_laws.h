// Elastic laws for a journal inside a bearing (internal cylinders), SPEC §4. SI throughout:
// lengths m, forces N, moduli Pa. ΔR = R_B − R_J is the radial clearance, L the contact length
// (the journal length L_J), 1/E* = (1 − ν_B²)/E_B + (1 − ν_J²)/E_J.
//
//  Hertz (as used with Lankarani–Nikravesh):  F = K·δ^{3/2},  K = (4/3)·E*·√(R_B·R_J/ΔR)
//  Johnson (1985), implicit:  δ = F/(π·L·E*)·[ln(4π·L·E*·ΔR/F) − 1]
//  Pereira et al. (2011), internal contact, evaluated in mm, N, N/mm² as fitted:
//      F = (a·ΔR + b)·L·E*·δ^n / ΔR,   n = Y·ΔR^{−0.005},
//      Y = 1.51·[ln(1000·ΔR)]^{−0.151}  for 0.005 ≤ ΔR < 0.34955 mm,
//      Y = 0.0151·ΔR + 1.151            for 0.34955 ≤ ΔR ≤ 10.1 mm,
//      a = 0.965, b = 0.0965 (defaults; see docs/mbd.md for their source and caveats)
#pragma once

#include "laws/power_law.h"

#include <cstdint>

namespace clearjoint::mbd
{
  /// [Pa] E* from 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (E in Pa, ν in 1).
  double effective_modulus(double E1, double nu1, double E2, double nu2);

  /// Hertz's law for the bearing/journal pair (radii in m, E* in Pa): n = 3/2.
  laws::PowerLaw hertz_cylinder_law(double R_B, double R_J, double E_star);

  struct PereiraParameters
  {
    double a = 0.965;   ///< [1] coefficient of ΔR (ΔR in mm)
    double b = 0.0965;  ///< [mm] constant term
    double exponent_of_clearance = -0.005;  ///< [1] n = Y·ΔR_mm^this
  };
  /// [1] Pereira's Y(ΔR) for ΔR in mm; throws InputError outside [0.005, 10.1] mm.
  double pereira_Y(double delta_R_mm);
  /// Pereira's law converted to SI: F = K·δ^n with K in N/m^n.
  laws::PowerLaw pereira_law(double R_B, double R_J, double L, double E_star,
                             const PereiraParameters &p);

  /// Johnson's implicit law for internal cylinders, solved for F on the branch through the
  /// origin. δ(F) rises from 0 to its peak δ_peak = 4ΔR/e² at F_peak = 4π·L·E*·ΔR/e²; beyond
  /// it the relation has no physical meaning.
  class JohnsonLaw
  {
  public:
    JohnsonLaw() = default;
    JohnsonLaw(double delta_R, double L, double E_star);

    /// [m] δ(F) in closed form, F in N (0 ≤ F ≤ F_peak).
    double penetration(double force) const;
    /// [N] F(δ) on the branch through the origin; δ ≤ 0 → 0. For δ > δ_peak returns F_peak
    /// and sets *beyond_peak (if given).
    double force(double delta, bool *beyond_peak = nullptr) const;
    /// [J] ∫₀^δ F dδ' = F·δ − F²/(πLE*)·[ln(A/F)/2 − 1/4], A = 4πLE*ΔR; linear beyond δ_peak.
    double energy(double delta) const;
    double peak_force() const { return F_peak_; }   ///< [N]
    double peak_delta() const { return delta_peak_; }  ///< [m]

  private:
    double dR_ = 0.0, L_ = 0.0, E_ = 0.0, F_peak_ = 0.0, delta_peak_ = 0.0;
  };
} // namespace clearjoint::mbd
