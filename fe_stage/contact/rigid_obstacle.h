// Rigid obstacles of the contact problems — the rigid journal (aligned or tilted cylinder), the
// Hertz sphere and the patch test's plane — as gap functions. No deal.II: unit-tested against
// closed forms in tests/unit/fe/rigid_obstacle_test.cc.
#pragma once

#include <array>
#include <limits>

namespace clearjoint::fe
{
  using Vec3 = std::array<double, 3>;

  /// A rigid obstacle moved by δ along −y. gap() returns the signed distance g0 of a reference
  /// point X from the obstacle surface (> 0 outside) and the unit normal n pointing from the
  /// obstacle toward X, so that the linearised gap of the displaced point is ĝ = g0 + n·u.
  struct RigidObstacle
  {
    /// cylinder: the aligned journal (axis z; bearing nodes beyond its ends never touch);
    /// tilted_cylinder: the journal of the misalignment study, a finite cylinder whose axis
    /// a = (0, sin θ, cos θ) lies in the y–z plane, with rims (its end circles) as edges.
    enum class Kind
    {
      cylinder,
      tilted_cylinder,
      sphere,
      plane
    } kind = Kind::cylinder;
    double radius = 0.0;  // [m] cylinder / sphere radius
    double offset = 0.0;  // [m] cylinders: centre at y = −offset − δ; sphere: y = radius − δ
    double half_length = std::numeric_limits<double>::infinity();  // [m] cylinder half length
    double tilt = 0.0;                                             // [rad] tilted_cylinder: θ
    /// [rad] cylinder: the obstacle seen from a frame turned by this angle about +z (the
    /// rolling study's co-rotating bearing frame): its axis at R(−frame_angle)·(0, −offset − δ)
    double frame_angle = 0.0;

    /// Returns false if X can never touch the obstacle (beyond the aligned cylinder's end).
    bool gap(const Vec3 &X, double delta, double &g0, Vec3 &n) const;
  };
}  // namespace clearjoint::fe
