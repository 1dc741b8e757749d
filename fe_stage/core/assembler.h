// The discrete operator and its assembly (FE_DESIGN §4.1): the unconstrained operator whose
// residual gives the reactions and contact forces, its condensed part over the cells without
// contact nodes (assembled once per mesh), the contact cells' matrices kept apart (each
// active-set iteration condenses them with its own constraints), the one cache of the elastic
// operator, the mass, the step's known load, and the condensed system of one iteration.
//
// What the operator means depends on the study, and only this class knows it (kind()):
//   - stiffness: K, the quasi-static studies;
//   - dynamic:   c_m M + c_k K (HHT-α, the impact study); K and M are kept apart for the
//                step's right-hand side and the energies;
//   - tangent:   the consistent tangent K_t(u) of an elastoplastic material (the rolling
//                study), with the load b = K_t u − f_int(u) of the linearisation.
// In the last two the residual K u − b of the operator is again the constraint forces, so the
// contact machinery runs unchanged on them.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"

#include <deal.II/base/index_set.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <set>
#include <vector>

namespace clearjoint::fe::detail
{
  class Assembler
  {
  public:
    enum class Operator
    {
      stiffness,  ///< K
      dynamic,    ///< c_m M + c_k K
      tangent     ///< K_t(u) of an elastoplastic material
    };

    Assembler(const FeScene &scene, const Bodies &bodies, const DofSpace &dofs, MPI_Comm comm);

    /// Matrices on the sparsity pattern `dsp` (every active set must condense into it) and the
    /// vectors on the DoF space, after every change of the mesh or the pattern (collective).
    void reinit(const DynamicSparsityPattern &dsp);
    /// The cells that hold contact nodes: `cell_of[active cell index]` is their index in
    /// 0..n−1, or −1. Their matrices are kept apart from the condensed static part.
    void set_contact_cells(std::vector<int> cell_of, unsigned int n);

    /// The operator of kind() once per mesh (and per time-step size): the unconstrained
    /// operator, the condensed part of the cells without contact nodes, the contact cells'
    /// matrices; dynamic: K and M apart too. `massless` (dynamic only): DoFs whose lumped mass
    /// moves to the rest of their cell (lump_and_redistribute). Collective.
    void assemble_static(const LinearElastic &C, const std::set<types::global_dof_index> &massless);
    /// The operator becomes c_m M + c_k K (HHT-α's coefficients for a step size), assembled
    /// again with the mass; the load is set to zero.
    void set_dynamic_operator(double c_mass, double c_stiffness, const LinearElastic &C,
                              const std::set<types::global_dof_index> &massless);
    /// The operator becomes an elastoplastic tangent: the elastic operator assembled last is
    /// kept (every tangent starts from it). Throws NumericalError if a fixed constraint is
    /// inhomogeneous (the linearisation's load does not carry prescribed displacements).
    void use_tangent();
    /// After a new sparsity pattern (finite sliding's rebuild): the freshly assembled elastic
    /// operator becomes the cache every tangent starts from.
    void keep_elastic_operator();
    /// The tangent K_t(u) and the load b = K_t u − f_int(u) at the ghosted displacement u,
    /// revisiting only the cells with plastic strain (the others keep the elastic cache).
    /// The material's trial states are written. Returns how many quadrature points yield.
    /// Throws StepFailure if the return mapping fails at a point. Collective.
    unsigned int assemble_tangent(MaterialLaw &material, const TrilinosWrappers::MPI::Vector &u);
    /// The same in finite kinematics (total Lagrangian, core/finite_strain_assembly.cc): every
    /// cell again — the geometric stiffness changes wherever the body deforms — from the first
    /// Piola stress P(F) and A = dP/dF at F = I + ∇u: K_t = ∫ ∇N : A : ∇N dV, f_int = ∫ P : ∇N
    /// dV and b = K_t u − f_int. Throws StepFailure where a point's law fails (det F ≤ 0, the
    /// return map). Collective.
    unsigned int assemble_finite_tangent(MaterialLaw &material,
                                         const TrilinosWrappers::MPI::Vector &u);

    /// One active-set iteration's condensed system: start from the static part, add cell and
    /// node contributions condensed with the iteration's `constraints`, then finish: the load
    /// of the push δ, and (dynamic, tangent) the known load moved onto its masters.
    void begin_system();
    void add_to_system(const AffineConstraints<double> &constraints,
                       const FullMatrix<double> &matrix, const Vector<double> &rhs,
                       const std::vector<types::global_dof_index> &dofs);
    void finish_system(double delta, const AffineConstraints<double> &constraints);

    Operator kind() const { return kind_; }
    /// Whether the residual is K u − b (dynamic, tangent) rather than K u.
    bool has_load() const { return kind_ != Operator::stiffness; }
    /// The unconstrained operator (reactions, contact forces): K, c_m M + c_k K or K_t.
    const TrilinosWrappers::SparseMatrix &operator_matrix() const { return K_; }
    /// The elastic stiffness K (dynamic and tangent; the stiffness operator itself otherwise).
    const TrilinosWrappers::SparseMatrix &elastic_stiffness() const
    {
      return kind_ == Operator::stiffness ? K_ : elastic_.K;
    }
    const TrilinosWrappers::SparseMatrix &mass() const { return M_; }
    /// The step's known load b (owned): HHT-α's c_m M û + α(K u_n − λ_n), or the tangent's.
    TrilinosWrappers::MPI::Vector &load() { return load_; }
    const TrilinosWrappers::MPI::Vector &load() const { return load_; }
    /// The condensed system of this iteration and its right-hand side.
    const TrilinosWrappers::SparseMatrix &system() const { return A_; }
    const TrilinosWrappers::MPI::Vector &rhs() const { return rhs_; }

    unsigned int n_contact_cells() const { return contact_cell_matrices_.size(); }
    const FullMatrix<double> &contact_cell_matrix(const unsigned int k) const
    {
      return contact_cell_matrices_[k];
    }
    const std::vector<types::global_dof_index> &contact_cell_dofs(const unsigned int k) const
    {
      return contact_cell_dofs_[k];
    }
    /// Quadrature points per cell: a material point is cell · n_q_points() + q.
    unsigned int n_q_points() const;

  private:
    /// How a tangent's cell matrix D enters a contact cell's cached matrix: it replaces it
    /// (finite strain: D is the whole tangent) or is added to it (small strain: D is the
    /// plastic correction K_t − K_el to the elastic cache).
    enum class ContactCellUpdate
    {
      replace,
      add
    };
    /// A tangent's cell matrix D into the operator K_, and into the contact cell's cached
    /// matrix (`update`; its contact rows are added per iteration) or else, condensed with
    /// the fixed constraints, into the static part A_static_.
    void place_tangent_cell_matrix(unsigned int active_cell_index,
                                   const std::vector<types::global_dof_index> &dofs,
                                   const FullMatrix<double> &D, ContactCellUpdate update);
    void lump_and_redistribute(FullMatrix<double> &cell_mass,
                               const std::vector<types::global_dof_index> &dofs,
                               const std::set<types::global_dof_index> &surface) const;

    const FeScene &scene_;
    const Bodies &bodies_;
    const DofSpace &dofs_;
    MPI_Comm comm_;

    Operator kind_ = Operator::stiffness;
    double c_mass_ = 0.0, c_stiffness_ = 1.0;  // the dynamic operator's coefficients

    TrilinosWrappers::SparseMatrix K_;               // the operator, unconstrained
    TrilinosWrappers::SparseMatrix M_;               // mass, unconstrained (dynamic)
    TrilinosWrappers::SparseMatrix A_static_;        // condensed, cells without contact nodes
    TrilinosWrappers::SparseMatrix A_;               // condensed system of this iteration
    TrilinosWrappers::MPI::Vector rhs_static_unit_;  // static cells' right-hand side at δ = 1
    TrilinosWrappers::MPI::Vector load_;             // owned: the known part of the step's rhs
    TrilinosWrappers::MPI::Vector rhs_;

    std::vector<int> contact_cell_of_;  // active_cell_index → index or −1
    std::vector<FullMatrix<double>> contact_cell_matrices_;
    std::vector<std::vector<types::global_dof_index>> contact_cell_dofs_;

    /// The elastic operator where the operator is something else: dynamic, its K (assembled
    /// with the operator); tangent, the elastic K, condensed static part and contact cells
    /// (every tangent assembly starts from them).
    struct ElasticCache
    {
      TrilinosWrappers::SparseMatrix K;         // unconstrained
      TrilinosWrappers::SparseMatrix A_static;  // condensed, cells without contact nodes
      std::vector<FullMatrix<double>> contact_cells;
    } elastic_;
  };
}  // namespace clearjoint::fe::detail
