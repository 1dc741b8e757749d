// The bodies' material as the FE model sees it: at each quadrature point, the stress and the
// consistent tangent from the strain, and the point's history (trial and committed states)
// where the law has one. Two implementations: ElasticLaw (below: Lamé's law of
// material/linear_elastic.h, no history) and J2Law (material/j2_law.h: J2 plasticity with its
// hardening table). The model keeps
// one MaterialLaw; which one is the study's choice (make_material).
//
// Points are numbered active_cell_index · n_q + q (resize() sizes the history for a mesh).
// evaluate() writes the trial state only; commit() makes it the point's history after a
// converged step; a failed step simply evaluates again from the committed state.
//
// Two kinematics (material.kinematics): small strain, evaluate() from ε = sym ∇u; finite strain
// (FE_DESIGN §4.2), evaluate_finite() from the displacement gradient ∇u = F − I, giving the
// first Piola stress and its derivative dP/dF for a total-Lagrangian assembly. Only the J2 law
// has the finite one (the scene allows finite with it only).
#pragma once

#include "fe_stage/core/restart_stream.h"
#include "fe_stage/material/linear_elastic.h"

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

namespace clearjoint::fe
{
  struct FeScene;
}

namespace clearjoint::fe::detail
{
  struct MaterialResponse
  {
    dealii::SymmetricTensor<2, 3> stress;  ///< σ [Pa]
    /// dσ/dε [Pa]; only set where `yielding` (elsewhere the elastic tangent holds)
    dealii::SymmetricTensor<4, 3> tangent;
    bool yielding = false;      ///< the point yields in this step (tangent ≠ elastic)
    bool converged = true;      ///< false: the local return did not converge (cut the step)
    double plastic_work = 0.0;  ///< [J/m³] σ : Δε_p of the step
  };

  /// A point's response to a displacement gradient (finite kinematics).
  struct FiniteResponse
  {
    dealii::Tensor<2, 3> stress;   ///< first Piola–Kirchhoff P = F S [Pa]
    dealii::Tensor<4, 3> tangent;  ///< A_iJkL = dP_iJ/dF_kL [Pa]: δ_ik S_JL + F_iI ℂ_IJKL F_kK
    bool yielding = false;         ///< the point yields in this step
    bool converged = true;         ///< false: see `reason` (cut the step)
    std::string reason;
    double plastic_work = 0.0;  ///< [J/m³ of reference volume] in this step
  };

  class MaterialLaw
  {
  public:
    virtual ~MaterialLaw() = default;

    /// The elastic law: the static operator, the yield check and the fields' stress C(ε − ε_p)
    /// are built from it (one elastic cache).
    virtual const LinearElastic &elastic() const = 0;

    /// C = dσ/dε of the elastic law [Pa] (the tangent of a point that does not yield).
    virtual dealii::SymmetricTensor<4, 3> elastic_tangent() const = 0;

    /// Whether the law has a history (elastoplastic): the model then assembles the tangent
    /// about the current state and commits after each converged step.
    virtual bool has_history() const = 0;

    /// Sizes the history for n_points quadrature points, all in the virgin state.
    virtual void resize(std::size_t n_points) = 0;

    /// The trial response at `point` for the total strain `eps` [-], from its committed state.
    virtual MaterialResponse evaluate(std::size_t point,
                                      const dealii::SymmetricTensor<2, 3> &eps) = 0;
    /// Trial → committed at `point`.
    /// Finite kinematics: P and dP/dF at the displacement gradient ∇u (trial state written
    /// as evaluate() does).
    virtual FiniteResponse evaluate_finite(std::size_t point,
                                           const dealii::Tensor<2, 3> &grad_u) = 0;
    virtual void commit(std::size_t point) = 0;

    /// The plastic strain [-] of the point's trial or committed state (0: elastic law).
    virtual dealii::SymmetricTensor<2, 3> plastic_strain(std::size_t point,
                                                         bool trial = false) const = 0;
    /// The equivalent plastic strain α [-] of the trial or committed state.
    virtual double equivalent_plastic_strain(std::size_t point, bool trial = false) const = 0;
    /// Elastic strain energy per volume ½(ε − ε_p):C:(ε − ε_p) [J/m³] at the committed state.
    virtual double elastic_energy(std::size_t point,
                                  const dealii::SymmetricTensor<2, 3> &eps) const = 0;

    /// Every point's committed history into a restart file, and back into a history sized
    /// for the same mesh (its trial states the committed ones). The reader fails, naming the
    /// file, when the sizes differ.
    virtual void write_history(RestartWriter &out) const = 0;
    virtual void read_history(RestartReader &in) = 0;
  };

  /// The linear-elastic law as a MaterialLaw (no history).
  class ElasticLaw : public MaterialLaw
  {
  public:
    explicit ElasticLaw(const LinearElastic &law)
      : law_(law)
    {}
    const LinearElastic &elastic() const override { return law_; }
    dealii::SymmetricTensor<4, 3> elastic_tangent() const override
    {
      const auto I = dealii::unit_symmetric_tensor<3>();
      return law_.lambda * dealii::outer_product(I, I) +
             2.0 * law_.mu * dealii::identity_tensor<3>();
    }
    bool has_history() const override { return false; }
    void resize(std::size_t) override {}
    MaterialResponse evaluate(std::size_t, const dealii::SymmetricTensor<2, 3> &eps) override
    {
      MaterialResponse r;
      r.stress = law_.stress(eps);
      return r;
    }
    FiniteResponse evaluate_finite(std::size_t, const dealii::Tensor<2, 3> &) override
    {
      // scene validation allows material.kinematics finite with the J2 law only
      throw std::logic_error("fe_stage: finite kinematics needs the J2 law");
    }
    void commit(std::size_t) override {}
    dealii::SymmetricTensor<2, 3> plastic_strain(std::size_t, bool) const override { return {}; }
    double equivalent_plastic_strain(std::size_t, bool) const override { return 0.0; }
    double elastic_energy(std::size_t, const dealii::SymmetricTensor<2, 3> &eps) const override
    {
      return 0.5 * (law_.stress(eps) * eps);
    }
    void write_history(RestartWriter &out) const override { out.put<std::uint64_t>(0); }
    void read_history(RestartReader &in) override
    {
      if (in.get<std::uint64_t>() != 0)
        in.damaged("a material history where the elastic law has none");
    }

  private:
    LinearElastic law_;
  };

  /// The scene's material: J2 with the scene's hardening table where `elastoplastic` (the
  /// rolling study), else linear elastic (material.E, material.nu).
  std::unique_ptr<MaterialLaw> make_material(const FeScene &scene, bool elastoplastic);
}  // namespace clearjoint::fe::detail
