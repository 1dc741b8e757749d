// J2 plasticity (material/j2_plasticity.h: radial return, consistent tangent, the hardening
// table) as the FE model's MaterialLaw, with the history of every quadrature point. deal.II value
// types on this side, Eigen inside the return map.
#pragma once

#include "fe_stage/material/finite_j2.h"
#include "fe_stage/material/j2_plasticity.h"
#include "fe_stage/material/material_law.h"

#include <vector>

namespace clearjoint::fe::detail
{
  class J2Law : public MaterialLaw
  {
  public:
    /// `elastic`: the same E, ν as Lamé's λ, μ (the fields' and the yield check's law).
    J2Law(J2Plasticity law, const LinearElastic &elastic);

    const LinearElastic &elastic() const override { return elastic_; }
    dealii::SymmetricTensor<4, 3> elastic_tangent() const override { return elastic_tangent_; }
    bool has_history() const override { return true; }
    void resize(std::size_t n_points) override;
    MaterialResponse evaluate(std::size_t point, const dealii::SymmetricTensor<2, 3> &eps) override;
    FiniteResponse evaluate_finite(std::size_t point, const dealii::Tensor<2, 3> &grad_u) override;
    void commit(std::size_t point) override { history_[point].commit(); }
    dealii::SymmetricTensor<2, 3> plastic_strain(std::size_t point,
                                                 bool trial = false) const override;
    double equivalent_plastic_strain(std::size_t point, bool trial = false) const override;
    double elastic_energy(std::size_t point,
                          const dealii::SymmetricTensor<2, 3> &eps) const override;
    void write_history(RestartWriter &out) const override;
    void read_history(RestartReader &in) override;

  private:
    J2Plasticity law_;
    FiniteJ2 finite_;  // the same law in the logarithmic strain space
    LinearElastic elastic_;
    dealii::SymmetricTensor<4, 3> elastic_tangent_;  // the law's own K 1⊗1 + 2G I_dev
    std::vector<J2History> history_;
  };
}  // namespace clearjoint::fe::detail
