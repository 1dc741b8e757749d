// Where the generated deformable journal sits. The journal is meshed aligned (axis e_z through
// (0, −c_r, 0), touching the bore at its bottom) and then placed rigidly: turned by θ about the
// x-axis through its centre and moved so that the centre lies at (0, centre_y, centre_z). Its
// axis is then a = (0, sin θ, cos θ), as the misalignment study's rigid tilted cylinder.
// No deal.II: unit-tested in tests/unit/fe/journal_pose_test.cc.
#pragma once

#include <array>
#include <cmath>

namespace clearjoint::fe
{
  struct JournalPose
  {
    using Vec = std::array<double, 3>;
    double tilt = 0.0;              // [rad] θ, about +x
    double aligned_centre_y = 0.0;  // [m] the centre's y as meshed (−c_r)
    double centre_y = 0.0;          // [m] the centre's y as placed
    double centre_z = 0.0;          // [m] the centre's z as placed (an axial offset)

    /// R v: e_x stays, e_y → (0, cos θ, −sin θ), e_z → (0, sin θ, cos θ).
    Vec rotate(const Vec &v) const
    {
      const double c = std::cos(tilt), s = std::sin(tilt);
      return {v[0], c * v[1] + s * v[2], -s * v[1] + c * v[2]};
    }
    /// Rᵀ v.
    Vec rotate_back(const Vec &v) const
    {
      const double c = std::cos(tilt), s = std::sin(tilt);
      return {v[0], c * v[1] - s * v[2], s * v[1] + c * v[2]};
    }
    /// A point of the aligned journal as meshed → where it sits.
    Vec to_world(const Vec &local) const
    {
      const Vec r = rotate({local[0], local[1] - aligned_centre_y, local[2]});
      return {r[0], r[1] + centre_y, r[2] + centre_z};
    }
    /// The inverse of to_world.
    Vec to_local(const Vec &world) const
    {
      const Vec r = rotate_back({world[0], world[1] - centre_y, world[2] - centre_z});
      return {r[0], r[1] + aligned_centre_y, r[2]};
    }
    bool identity() const { return tilt == 0.0 && centre_y == aligned_centre_y && centre_z == 0.0; }
  };
}  // namespace clearjoint::fe
