// Isotropic linear elasticity (small strain) by Lamé's constants, and the von Mises equivalent
// stress the yield check and the fields use. The static operator is assembled from it; the
// model's material law (material/material_law.h: ElasticLaw, or J2Law with history) names it
// as its elastic part.
#pragma once

#include <deal.II/base/symmetric_tensor.h>

#include <cmath>

namespace clearjoint::fe::detail
{
  struct LinearElastic
  {
    double lambda = 0.0;  // [Pa] Lamé's first parameter
    double mu = 0.0;      // [Pa] shear modulus

    static LinearElastic from_young_poisson(const double E, const double nu)
    {
      return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
    }

    /// σ = λ tr(ε) I + 2μ ε
    dealii::SymmetricTensor<2, 3> stress(const dealii::SymmetricTensor<2, 3> &eps) const
    {
      return lambda * dealii::trace(eps) * dealii::unit_symmetric_tensor<3>() + 2.0 * mu * eps;
    }
  };

  /// σ_vm = √(3/2 s:s), s the deviator of σ.
  inline double von_mises(const dealii::SymmetricTensor<2, 3> &sigma)
  {
    const dealii::SymmetricTensor<2, 3> s = dealii::deviator(sigma);
    return std::sqrt(1.5 * (s * s));
  }
}  // namespace clearjoint::fe::detail
