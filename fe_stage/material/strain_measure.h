// The strain the material law reads at a point, from the displacement gradient ∇u: with small
// kinematics ε = sym ∇u; with finite kinematics the Hencky strain E = ½ ln(FᵀF), F = I + ∇u.
// The J2 law in the logarithmic strain space (material/finite_j2.h) is the small-strain law on
// E, so what the model derives from ε — the stored energy ½(ε − ε_p):ℂ:(ε − ε_p), the largest
// principal strain, the stress ℂ:(ε − ε_p) of the fields and the strain profiles — is, with E in
// its place, the finite-strain one (the stress then the rotated Kirchhoff stress T, which the
// yield function acts on; the Cauchy stress is T/J up to the rotation).
#pragma once

#include "fe_stage/material/log_strain.h"

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <limits>

namespace clearjoint::fe::detail
{
  /// ε = sym ∇u (finite = false) or the Hencky strain ½ ln(FᵀF) (finite = true), computed from
  /// E_GL = ½(∇u + ∇uᵀ + ∇uᵀ∇u) so that small strains keep their digits. A gradient whose F
  /// is not invertible (det F ≤ 0) gives NaN entries.
  inline dealii::SymmetricTensor<2, 3> strain_measure(const dealii::Tensor<2, 3> &grad_u,
                                                      const bool finite)
  {
    if (!finite)
      return dealii::symmetrize(grad_u);
    Eigen::Matrix3d H;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        H(i, j) = grad_u[i][j];
    dealii::SymmetricTensor<2, 3> e;
    if (!((Eigen::Matrix3d::Identity() + H).determinant() > 0.0))
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            e[i][j] = std::numeric_limits<double>::quiet_NaN();
        return e;
      }
    const LogStrain log_strain = compute_log_strain(0.5 * (H + H.transpose() + H.transpose() * H));
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        e[i][j] = log_strain.valid ? 0.5 * (log_strain.hencky(i, j) + log_strain.hencky(j, i)) :
                                     std::numeric_limits<double>::quiet_NaN();
    return e;
  }
}  // namespace clearjoint::fe::detail
