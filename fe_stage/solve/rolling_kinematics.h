// The rolling study's kinematics (paper §3.4), no deal.II: the prescribed motion (the bearing's
// spin φ = ω_B t, the journal's push δ(t)), the co-rotating frame in which the bearing is
// computed, the rigid journal's surface motion seen from that frame, the paper's Eqs. 4–8 and the
// slip stages (the torque balance's root finder is solve/root_finder.h). Unit-tested in
// tests/unit/fe/rolling_kinematics_test.cc.
//
// Frame: the fixed frame has the axes of SPEC §2 (bearing axis z, push along −y). The bearing
// turns by φ(t) about +z; its co-rotating frame is the fixed one turned by φ, so a bearing
// material point X (frame coordinates) is at R(φ)·(X + u) in the fixed frame, u the small
// deformation. A rigid spin gives u = 0 and hence no strain, exactly (docs/fe.md).
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace clearjoint::fe::rolling
{
  using Vec3 = std::array<double, 3>;

  /// R(angle)·v: rotation about +z.
  Vec3 rotate_z(const Vec3 &v, double angle);

  struct Motion
  {
    double omega_B = 0.0;         // [rad/s]
    double ramp_time = 0.0;       // [s]
    double delta_max = 0.0;       // [m]
    double c_r = 0.0;             // [m] the journal's axis at y = −c_r at first touch
    double R_B = 0.0, R_J = 0.0;  // [m]

    double phi(double t) const { return omega_B * t; }  ///< [rad] bearing angle
    double delta(double t) const;                       ///< [m] push beyond first touch
    /// [m] the journal's axis in the fixed frame: (0, −c_r − δ(t), 0).
    Vec3 centre_fixed(double t) const;
    /// [m] the same in the bearing's co-rotating frame: R(−φ)·centre_fixed.
    Vec3 centre_frame(double t) const;
    /// [m] distance from the bearing's axis of the journal's surface point deepest in the
    /// bore: c_r + δ + R_J = R_B + δ. The journal is rigid and the contact closes the gap, so
    /// the bore's material there is at this radius too and moves at ω_B (R_B + δ).
    double contact_radius(double t) const { return R_B + delta(t); }
    /// [rad/s] the journal's spin of rolling without slip at that point:
    /// γ̇ R_J = ω_B (R_B + δ).
    double rolling_rate(double t) const { return omega_B * contact_radius(t) / R_J; }
    /// [m/s] the relative speed of the surfaces at that point, bore minus journal:
    /// ω_B (R_B + δ) − γ̇ R_J (0: rolling without slip).
    double slip_speed(double t, double gamma_rate) const
    {
      return omega_B * contact_radius(t) - gamma_rate * R_J;
    }
    /// A spin more than `runaway_factor` times the rolling rate, in either sense: the torque
    /// balance has no root near rolling any more, and the steps after it would record a
    /// journal whirling at hundreds of rad/s while its surface slides at metres per second
    /// (μ = 5 on the coarse ring: the spin fell from 13 rad/s at t = 0.15 s to −1 100 rad/s at
    /// t = 0.1608 s in steps cut down to 7.6 µs, until a step failed to converge at all). The paper's case at
    /// μ = 0.3 ends at 0.89 (rigid journal) to 1.00 (deformable) of the rolling rate.
    static constexpr double runaway_factor = 10.0;
    bool spin_ran_away(double t, double gamma_rate) const
    {
      return std::abs(gamma_rate) > runaway_factor * std::abs(rolling_rate(t));
    }
  };

  /// Displacement, over a step, of the rigid journal's surface point that faces the frame
  /// direction `n` (unit, from the journal's axis outward) at the step's end: the point is at
  /// c1 + R_J n at the end and came from c0 + R_J R(−Δψ) n, Δψ = Δγ − Δφ the journal's turn
  /// relative to the frame. [m], frame coordinates.
  Vec3 journal_surface_step(const Vec3 &c0, const Vec3 &c1, double R_J, const Vec3 &n,
                            double delta_psi);

  /// Paper Eqs. 4–5 (and 6 with R = R_J): the angle a point on a circle of radius R has turned
  /// through, from the length of its displacement U: 2 asin(|U|/2R) [rad] (|U| ≤ 2R; valid
  /// up to half a turn).
  double paper_angle(const Vec3 &U, double R);

  /// Eqs. 5–6 past half a turn: the chord gives the turned angle only up to its sign and
  /// modulo a turn (2 asin(|U|/2R) ∈ [0, π] folds back once the point has turned more than π,
  /// at γ ≈ 3.3 rad in the paper's case). With the sense of the turn (`positive`: the point's
  /// sin θ ≥ 0 about its own centre, from its start and end radii), θ ≡ ±chord (mod 2π); of
  /// those angles the one nearest `previous` (the last step's unwrapped angle, 0 at the start).
  /// Exact while a step turns the point by less than π — any usable time step. [rad]
  double unwrap_paper_angle(double chord, bool positive, double previous);

  /// The three slip stages of the paper (§3.4) located on the relative surface speed
  /// v(t) = ω_B R_B − γ̇ R_J of the converged steps: (i) slip, from the start until the speed
  /// first falls below `fall_fraction` of its largest value; (ii) the fall, until it stays
  /// within `settle_band` (of that largest value) of its final value; (iii) the stable rest.
  struct SlipStages
  {
    bool found = false;        // false: fewer than 3 steps, no slip at all, or the relative
                               //   speed never fell below the fraction before the end
    double v_max = 0.0;        // [m/s] largest relative speed
    double end_of_slip = 0.0;  // [s] end of stage (i)
    double settled = 0.0;      // [s] start of stage (iii)
    double v_final = 0.0;      // [m/s] relative speed at the end
  };
  SlipStages slip_stages(const std::vector<double> &t, const std::vector<double> &v,
                         double fall_fraction = 0.5, double settle_band = 0.05);

}  // namespace clearjoint::fe::rolling
