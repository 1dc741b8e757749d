// Euler parameters e = (e0, e1, e2, e3) of a body's orientation (Nikravesh, "Computer-Aided
// Analysis of Mechanical Systems", §6; the paper's Table 2 gives them per body).
//   A(e) = (2e0² − 1)·I + 2·(ē·ēᵀ + e0·ẽ)          rotation body → ground, ē = (e1, e2, e3)
//   ė = ½·Lᵀ(e)·ω'  with L = [−ē, −ẽ + e0·I]        ω' the angular velocity in body axes
// The kinematic relation keeps ‖e‖ constant exactly; the integrator does not, so the system adds
// a small stabilising term and reports ‖e‖ − 1.
#pragma once

#include <Eigen/Dense>

namespace clearjoint::mbd
{
  using Vector3 = Eigen::Vector3d;
  using Vector4 = Eigen::Vector4d;
  using Matrix3 = Eigen::Matrix3d;

  /// Skew-symmetric matrix ã with ã·b = a × b.
  inline Matrix3 skew(const Vector3 &a)
  {
    Matrix3 m;
    m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return m;
  }

  /// Rotation matrix A (body → ground) of the Euler parameters e (normalised first).
  Matrix3 rotation_matrix(const Vector4 &e);

  /// ė [1/s] from e and the body-frame angular velocity w_B [rad/s].
  Vector4 euler_parameter_rate(const Vector4 &e, const Vector3 &w_B);

  /// Euler parameters of a rotation by `angle` [rad] about the unit `axis`.
  Vector4 euler_parameters_from_axis_angle(const Vector3 &axis, double angle);

  /// Euler parameters of a rotation matrix (Shepperd's method, e0 ≥ 0).
  Vector4 euler_parameters_from_rotation(const Matrix3 &A);
} // namespace clearjoint::mbd
