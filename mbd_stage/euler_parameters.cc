#include "mbd_stage/euler_parameters.h"

#include <cmath>

namespace clearjoint::mbd
{
  Matrix3 rotation_matrix(const Vector4 &e_in)
  {
    const Vector4 e = e_in / e_in.norm();
    const double e0 = e[0];
    const Vector3 ev(e[1], e[2], e[3]);
    return (2.0 * e0 * e0 - 1.0) * Matrix3::Identity() +
           2.0 * (ev * ev.transpose() + e0 * skew(ev));
  }

  Vector4 euler_parameter_rate(const Vector4 &e, const Vector3 &w)
  {
    // ė = ½·Lᵀ·ω' = ½·[−ē·ω' ; e0·ω' + ē × ω']  (quaternion product e ⊗ (0, ω')/2)
    const Vector3 ev(e[1], e[2], e[3]);
    Vector4 r;
    r[0] = -0.5 * ev.dot(w);
    r.tail<3>() = 0.5 * (e[0] * w + ev.cross(w));
    return r;
  }

  Vector4 euler_parameters_from_axis_angle(const Vector3 &axis, const double angle)
  {
    const Vector3 a = axis.normalized();
    Vector4 e;
    e[0] = std::cos(0.5 * angle);
    e.tail<3>() = std::sin(0.5 * angle) * a;
    return e;
  }

  Vector4 euler_parameters_from_rotation(const Matrix3 &A)
  {
    const Eigen::Quaterniond q(A);
    Vector4 e(q.w(), q.x(), q.y(), q.z());
    if (e[0] < 0.0)
      e = -e;
    return e / e.norm();
  }
} // namespace clearjoint::mbd
