// Units and conversions. Everything inside clearjoint is SI (m, N, Pa, kg, s, rad); these
// constants convert at the edges (input files, the paper's mm/N laws, reports).
#pragma once

#include <cmath>

namespace clearjoint::units
{
  inline constexpr double mm  = 1.0e-3;   // [m] one millimetre
  inline constexpr double um  = 1.0e-6;   // [m] one micrometre
  inline constexpr double GPa = 1.0e9;    // [Pa]
  inline constexpr double MPa = 1.0e6;    // [Pa]
  inline constexpr double pi  = 3.14159265358979323846;
  inline constexpr double deg = pi / 180.0;  // [rad] one degree

  inline constexpr double to_mm(const double length_m) { return length_m / mm; }
  inline constexpr double to_deg(const double angle_rad) { return angle_rad / deg; }

  /// A power law F = K·δ^n quoted with δ in mm and F in N has, with δ in m, the coefficient
  /// K_SI = K_mm · 1000^n  [N/m^n]. Check (SPEC §1): 338240 N/mm^1.0114 → 3.6595e8 N/m^1.0114.
  inline double power_law_K_mm_to_SI(const double K_mm, const double n)
  {
    return K_mm * std::pow(1.0 / mm, n);
  }
  inline double power_law_K_SI_to_mm(const double K_SI, const double n)
  {
    return K_SI * std::pow(mm, n);
  }
} // namespace clearjoint::units
