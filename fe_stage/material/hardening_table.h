// Isotropic hardening of a von Mises material given as a table of (equivalent plastic strain,
// yield stress) points, linear between points: σ_y(ε_p). SPEC §2 (rolling study) and issue 13
// item 1; the scene's `material.hardening` block. No deal.II here (FE_DESIGN §3.7): the table
// and its checks compile in seconds and are unit-tested in tests/unit/fe.
//
// Units: ε_p is dimensionless [-], σ_y in Pa.
//
// Beyond the last point the table is extended along its last segment (linear extrapolation,
// the slope of the last two points). A one-point table is perfectly plastic (slope 0). Note
// that Abaqus's *PLASTIC holds σ_y constant beyond the last point instead; the `Beyond`
// option selects that behaviour where a scene wants Abaqus's convention.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  struct HardeningPoint
  {
    double eps_p;    ///< equivalent plastic strain [-], ≥ 0
    double sigma_y;  ///< yield stress at eps_p [Pa], > 0
  };

  class HardeningTable
  {
  public:
    /// What σ_y does beyond the last point.
    enum class Beyond
    {
      extend_last_segment,  ///< linear extrapolation with the last segment's slope (default)
      hold_last,            ///< σ_y stays at the last value (Abaqus *PLASTIC convention)
    };

    /// Checks the table and throws clearjoint::InputError naming `key_path` (e.g.
    /// "material.hardening"), the offending entry as key_path[i][0] (strain) or [i][1]
    /// (stress), its value and the allowed range. `file` is the scene file for the message (may
    /// be empty). Rules: at least one point; every value finite; the first strain exactly 0;
    /// strains strictly increasing; stresses > 0 and non-decreasing.
    HardeningTable(std::vector<HardeningPoint> points, const std::string &key_path,
                   const std::string &file = "", Beyond beyond = Beyond::extend_last_segment);

    /// SPEC §2 default: σ_y = 168.2 + 280.25·ε_p MPa at ε_p = 0, 0.1, …, 1.0 (11 points,
    /// 168.2 MPa to 448.45 MPa).
    static HardeningTable spec_default();

    /// σ_y(ε_p) [Pa]. ε_p < 0 is outside the model (the equivalent plastic strain never
    /// decreases from 0) and throws std::invalid_argument; NaN throws too.
    double yield_stress(double eps_p) const;

    /// dσ_y/dε_p [Pa] of the segment that holds ε_p; at a table point, the segment to its
    /// right (plastic loading moves ε_p to the right). Beyond the table: the last segment's
    /// slope (extend_last_segment) or 0 (hold_last).
    double slope(double eps_p) const;

    /// Index k of the segment [ε_k, ε_{k+1}) that holds ε_p; n_points() − 1 means "beyond
    /// the last point" (the extrapolated tail).
    std::size_t segment(double eps_p) const;

    /// Strain where segment k ends: ε_{k+1}, or +∞ for the tail k = n_points() − 1.
    double segment_end(std::size_t k) const;

    std::size_t n_points() const { return points_.size(); }
    const std::vector<HardeningPoint> &points() const { return points_; }
    Beyond beyond() const { return beyond_; }

  private:
    std::vector<HardeningPoint> points_;
    Beyond beyond_;
    double tail_slope_;  ///< [Pa] slope beyond the last point
  };
}  // namespace clearjoint::fe
