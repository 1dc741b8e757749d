// Kinematic expressions of vectors and points attached to bodies, with everything the
// constraint and contact code needs: value, rate, the Jacobian with respect to the generalised
// velocities u = [v_G, ω'_B] of each body, and the velocity-quadratic part of the acceleration
// (so that d²x/dt² = J·u̇ + quad). Absolute coordinates: body b owns columns 6b..6b+5 of u.
#pragma once

#include "mbd_stage/euler_parameters.h"

#include <array>

namespace clearjoint::mbd
{
  /// Index used for the ground (fixed, not part of the state).
  inline constexpr int ground_index = -1;

  /// Pose and velocity of one body.
  struct BodyKinematics
  {
    Vector3 r = Vector3::Zero();      ///< [m] centre of mass, ground frame
    Vector4 e = Vector4(1, 0, 0, 0);  ///< [1] Euler parameters (as integrated)
    Matrix3 A = Matrix3::Identity();  ///< [1] rotation body → ground (from normalised e)
    Vector3 v = Vector3::Zero();      ///< [m/s] velocity of the centre of mass, ground frame
    Vector3 w_B = Vector3::Zero();    ///< [rad/s] angular velocity, body frame
    Vector3 w_G() const { return A * w_B; }  ///< [rad/s] angular velocity, ground frame
    /// [m/s] velocity of the material point at p_G (ground frame position).
    Vector3 point_velocity(const Vector3 &p_G) const { return v + w_G().cross(p_G - r); }
  };

  /// The kinematics of body `index`, or of the ground for ground_index.
  class KinematicsView
  {
  public:
    explicit KinematicsView(const std::vector<BodyKinematics> *bodies) : bodies_(bodies) {}
    const BodyKinematics &operator[](int index) const
    {
      return index == ground_index ? ground_ : (*bodies_)[static_cast<std::size_t>(index)];
    }
    int n_bodies() const { return static_cast<int>(bodies_->size()); }

  private:
    const std::vector<BodyKinematics> *bodies_;
    BodyKinematics ground_;
  };

  struct KinSlot
  {
    int body = ground_index;
    Matrix3 J_v = Matrix3::Zero();  ///< ∂x/∂v_G of that body
    Matrix3 J_w = Matrix3::Zero();  ///< ∂x/∂ω'_B of that body
  };

  /// A vector-valued kinematic expression x(q) depending on at most two bodies.
  struct KinVec
  {
    Vector3 value = Vector3::Zero();  ///< x
    Vector3 rate = Vector3::Zero();   ///< dx/dt
    Vector3 quad = Vector3::Zero();   ///< d²x/dt² − J·u̇
    std::array<KinSlot, 2> slots;
    int n_slots = 0;
  };

  /// The body-fixed vector a_B (body frame) seen in the ground frame: A·a_B.
  KinVec body_vector(const KinematicsView &k, int body, const Vector3 &a_B);
  /// The body-fixed point s_B (body frame, from the centre of mass): r + A·s_B.
  KinVec body_point(const KinematicsView &k, int body, const Vector3 &s_B);
  /// a − b (at most two distinct bodies in total).
  KinVec operator-(const KinVec &a, const KinVec &b);

  /// A scalar kinematic expression with its dense Jacobian row (length 6·n_bodies).
  struct KinScalar
  {
    double value = 0.0, rate = 0.0, quad = 0.0;
    Eigen::RowVectorXd row;
  };
  /// a · b
  KinScalar dot(const KinVec &a, const KinVec &b, int n_bodies);
  /// Component `axis` (0, 1, 2) of a.
  KinScalar component(const KinVec &a, int axis, int n_bodies);
} // namespace clearjoint::mbd
