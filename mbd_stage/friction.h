// Regularised Coulomb friction (the paper's Eqs. 9–11 with Ambrósio's dynamic correction):
//   F_f = −μ·c_d(‖v_T‖)·F_n·v_T/‖v_T‖,
//   c_d = 0 for ‖v_T‖ ≤ v0,  (‖v_T‖ − v0)/(v1 − v0) for v0 < ‖v_T‖ < v1,  1 for ‖v_T‖ ≥ v1.
// The force is continuous everywhere, zero at v_T = 0, and never larger than μ·F_n.
#pragma once

#include "mbd_stage/euler_parameters.h"

namespace clearjoint::mbd
{
  struct CoulombFriction
  {
    double mu = 0.0;   ///< [1] coefficient of kinetic friction
    double v0 = 1e-4;  ///< [m/s] below this tangential speed no friction (c_d = 0)
    double v1 = 1e-3;  ///< [m/s] full friction from this speed on (c_d = 1)

    /// [1] Ambrósio's c_d for a tangential speed [m/s].
    double correction(double speed) const;
    /// [N] the friction force on the body whose velocity relative to the other is v_T [m/s]
    /// (tangential), under a normal force F_n [N] ≥ 0.
    Vector3 force(double normal_force, const Vector3 &v_T) const;
  };
} // namespace clearjoint::mbd
