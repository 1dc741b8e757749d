// Ideal joints as holonomic constraints Φ(q, t) = 0 in absolute coordinates (Nikravesh §7,
// Haug §9), built from three primitives of kinematics.h: point coincidence (3 equations),
// "dot-1" a_i·a_j = 0 and "dot-2" a_i·d_ij = 0. A joint is defined like an Adams marker pair: a
// point and an axis in the ground frame at the initial configuration, converted to each body's
// frame there, so Φ(q0) = 0 by construction.
//   revolute       point coincidence + axis_i ⟂ h1_j, axis_i ⟂ h2_j                (5)
//   spherical      point coincidence                                              (3)
//   translational  h1_i ⟂ axis_j, h2_i ⟂ axis_j, h1_i ⟂ h2_j, h1_i ⟂ d, h2_i ⟂ d   (5)
//   fixed          point coincidence + the three angular equations above          (6)
// The constant-speed driver rotates body j relative to body i about a revolute joint's axis:
//   Φ = sin(θ_rel − θ(t)) = (h1_j·h2_i)·cos θ(t) − (h1_j·h1_i)·sin θ(t),  θ(t) = ω·t.
#pragma once

#include "mbd_stage/kinematics.h"

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  enum class JointType
  {
    revolute,
    translational,
    spherical,
    fixed,
  };
  JointType parse_joint_type(const std::string &name);
  std::string to_string(JointType type);

  /// One scalar constraint equation, ready for the acceleration-level system
  /// D·u̇ = γ − 2α·Φ̇ − β²·Φ (Baumgarte), with Φ̇ = D·u + Φ_t.
  struct ConstraintRow
  {
    double phi = 0.0;        ///< Φ (m or 1)
    double phi_t = 0.0;      ///< ∂Φ/∂t
    double gamma = 0.0;      ///< everything of Φ̈ not in D·u̇, negated
    Eigen::RowVectorXd D;    ///< ∂Φ̇/∂u
  };

  class Joint
  {
  public:
    /// point_G [m] and axis_G [1] in the ground frame at the initial configuration `k0`.
    Joint(std::string name, JointType type, int body_i, int body_j, const Vector3 &point_G,
          const Vector3 &axis_G, const KinematicsView &k0);

    int n_equations() const;
    /// Appends this joint's rows at time t.
    void evaluate(const KinematicsView &k, std::vector<ConstraintRow> &rows) const;

    const std::string &name() const { return name_; }
    JointType type() const { return type_; }
    int body_i() const { return body_i_; }
    int body_j() const { return body_j_; }

    // Marker vectors in the body frames (used by drivers).
    Vector3 axis_i, axis_j, h1_i, h1_j, h2_i, h2_j, s_i, s_j;

  private:
    std::string name_;
    JointType type_;
    int body_i_, body_j_;
  };

  /// Drives body j relative to body i about a revolute joint at constant angular speed.
  class Driver
  {
  public:
    /// speed [rad/s]; the joint must be revolute.
    Driver(std::string name, const Joint &joint, double speed);
    void evaluate(const KinematicsView &k, double t, std::vector<ConstraintRow> &rows) const;
    const std::string &name() const { return name_; }
    double speed() const { return speed_; }
    const Joint &joint() const { return *joint_; }

  private:
    std::string name_;
    const Joint *joint_;
    double speed_;
  };

  /// Two unit vectors h1, h2 with (axis, h1, h2) right-handed and orthonormal.
  void make_perpendiculars(const Vector3 &axis, Vector3 &h1, Vector3 &h2);
} // namespace clearjoint::mbd
