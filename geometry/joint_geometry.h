// The dimensions of a revolute joint with clearance (SPEC §2, paper Eqs. 1–3), in metres.
// The journal follows from the bearing and the clearances: R_J = R_B − c_r (Eq. 1),
// L_J = L_B − 2·c_a (Eq. 2, journal axially centred). No deal.II here.
#pragma once

#include <optional>
#include <string>

namespace clearjoint::geometry
{
  struct JointGeometry
  {
    double R_B = 10e-3;  ///< bearing inner radius [m]
    double t_B = 4e-3;   ///< bearing wall thickness [m] (outer radius R_B + t_B)
    double L_B = 20e-3;  ///< bearing length [m]
    double c_r = 0.5e-3; ///< radial clearance [m]
    double c_a = 1e-3;   ///< axial clearance per side [m]

    double R_J() const { return R_B - c_r; } ///< journal radius, Eq. 1
    double L_J() const { return L_B - 2.0 * c_a; } ///< journal length, Eq. 2

    /// Builds the geometry from journal dimensions instead of clearances
    /// (c_r = R_B − R_J, c_a = (L_B − L_J)/2) and validates it, so a journal larger than the
    /// bearing is reported as such.
    static JointGeometry from_journal(double R_B, double t_B, double L_B, double R_J, double L_J,
                                      const std::string &file = "",
                                      const std::string &key_prefix = "geometry");

    /// Throws InputError naming `file` and `<key_prefix>.<field>` with the valid range when a
    /// value is not finite, a length is not positive, c_r ≤ 0, c_r ≥ R_B (journal radius ≤ 0),
    /// c_a ≤ 0 (L_J ≥ L_B) or c_a ≥ L_B/2 (journal length ≤ 0).
    void validate(const std::string &file = "", const std::string &key_prefix = "geometry") const;
  };

  /// The largest tilt [rad] of the axially centred journal in the bearing, the smallest
  /// positive root of the paper's Eq. 3
  ///   f(θ) = c_r + R_J(1 − cos θ) − (L_J/2)·sin θ = 0.
  /// Meaning: tilted about its centre in a plane through the axis, the journal rim corner sits
  /// at the radial distance g(θ) = R_J cos θ + (L_J/2) sin θ from the bearing axis, and Eq. 3 is
  /// g(θ) = R_B: two diagonally opposite rim points touch the bearing. g grows from R_J at θ = 0
  /// to its maximum, the half-diagonal D = √(R_J² + L_J²/4), at θ* = atan(L_J/(2R_J)), so f
  /// falls monotonically on [0, θ*]. The first root in (0, θ*] is the physical one (the jammed
  /// journal); the second root, beyond θ*, would need the journal to pass through the bearing
  /// wall. No root exists when D < R_B (a journal short enough to turn over inside the bearing):
  /// then std::nullopt. The geometry is validated first.
  /// Numerics: safeguarded Newton on the bracket [0, θ*] (bisection whenever a Newton step
  /// leaves the bracket), at most 200 iterations, to |Δθ| ≤ 1e-15 rad.
  std::optional<double> theta_max(const JointGeometry &geometry);

  /// Throws InputError when θ < 0 or θ > θ_max (the message states θ and the computed θ_max in
  /// degrees and the geometry it came from). θ_max itself is accepted (it is one of the
  /// misalignment study's angles). When Eq. 3 has no root, θ must lie in [0°, 90°).
  void check_tilt(const JointGeometry &geometry, double theta_rad, const std::string &file = "",
                  const std::string &key_path = "theta");

  double degrees(double radians);
  double radians(double degrees);
} // namespace clearjoint::geometry
