#include "mbd_stage/friction.h"

namespace clearjoint::mbd
{
  double CoulombFriction::correction(const double speed) const
  {
    if (speed <= v0)
      return 0.0;
    if (speed >= v1)
      return 1.0;
    return (speed - v0) / (v1 - v0);
  }

  Vector3 CoulombFriction::force(const double F_n, const Vector3 &v_T) const
  {
    const double s = v_T.norm();
    if (mu == 0.0 || F_n <= 0.0 || s <= v0)
      return Vector3::Zero();
    return -mu * correction(s) * F_n * v_T / s;
  }
} // namespace clearjoint::mbd
