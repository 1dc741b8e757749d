// The operator's assembly: the static part once per mesh (cells without contact nodes), the
// dynamic operator, and the condensed system of one active-set iteration (core/assembler.h).
#include "fe_stage/core/assembler.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/sparsity_tools.h>

namespace clearjoint::fe::detail
{
  Assembler::Assembler(const FeScene &scene, const Bodies &bodies, const DofSpace &dofs,
                       MPI_Comm comm)
    : scene_(scene)
    , bodies_(bodies)
    , dofs_(dofs)
    , comm_(comm)
  {}

  void Assembler::reinit(const DynamicSparsityPattern &dsp)
  {
    // the pattern made once, from the DynamicSparsityPattern, and copied to the other two
    // (making each from it took ~1.8 s at 238 k DoFs, 49 M entries; a copy a fraction of that)
    K_.reinit(dofs_.owned(), dofs_.owned(), dsp, comm_);
    A_static_.reinit(K_);
    A_.reinit(K_);
    rhs_.reinit(dofs_.owned(), comm_);
    rhs_static_unit_.reinit(dofs_.owned(), comm_);
  }

  void Assembler::set_contact_cells(std::vector<int> cell_of, const unsigned int n)
  {
    contact_cell_of_ = std::move(cell_of);
    contact_cell_matrices_.resize(n);
    contact_cell_dofs_.resize(n);
  }

  unsigned int Assembler::n_q_points() const { return QGauss<dim>(dofs_.fe().degree + 1).size(); }

  /// Quasi-static (and tangent, before any yielding): the stiffness K; dynamic: c_m M + c_k K,
  /// with M and K also kept apart for the step's right-hand side and the energies.
  void Assembler::assemble_static(const LinearElastic &C,
                                  const std::set<types::global_dof_index> &surface_dofs)
  {
    const bool dynamic = kind_ == Operator::dynamic;
    const unsigned int p = dofs_.fe().degree;
    const QGauss<dim> quadrature(p + 1);
    FEValues<dim> fe_values(bodies_.mapping(), dofs_.fe(), quadrature,
                            update_gradients | update_JxW_values |
                              (dynamic ? update_values : update_default));
    const unsigned int n_dofs = dofs_.fe().n_dofs_per_cell();
    const double c_m = dynamic ? c_mass_ : 0.0;
    const double c_k = dynamic ? c_stiffness_ : 1.0;
    const double rho = scene_.material.rho;
    FullMatrix<double> cell_matrix(n_dofs, n_dofs), cell_mass(n_dofs, n_dofs);
    Vector<double> cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dofs(n_dofs);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(n_dofs);
    std::vector<double> div(n_dofs);

    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0.0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  eps[i] = fe_values[u].symmetric_gradient(i, q);
                  div[i] = trace(eps[i]);
                }
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                for (unsigned int j = i; j < n_dofs; ++j)
                  cell_matrix(i, j) +=
                    (C.lambda * div[i] * div[j] + 2.0 * C.mu * (eps[i] * eps[j])) * JxW;
            }
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = 0; j < i; ++j)
              cell_matrix(i, j) = cell_matrix(j, i);
          cell->get_dof_indices(dofs);
          if (dynamic)
            {
              // consistent mass: ρ φ_i·φ_j (a vector element: only equal components couple)
              cell_mass = 0.0;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const unsigned int ci = dofs_.fe().system_to_component_index(i).first;
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      if (dofs_.fe().system_to_component_index(j).first == ci)
                        cell_mass(i, j) += rho * fe_values.shape_value(i, q) *
                                           fe_values.shape_value(j, q) * fe_values.JxW(q);
                  }
              if (scene_.impact.mass != Impact::Mass::consistent)
                lump_and_redistribute(cell_mass, dofs, surface_dofs);
              elastic_.K.add(dofs, cell_matrix);
              M_.add(dofs, cell_mass);
              cell_matrix *= c_k;
              cell_matrix.add(c_m, cell_mass);
            }
          K_.add(dofs, cell_matrix);
          const int k = contact_cell_of_[cell->active_cell_index()];
          if (k >= 0)
            {
              contact_cell_matrices_[k] = cell_matrix;
              contact_cell_dofs_[k] = dofs;
            }
          else
            {
              cell_rhs = 0.0;
              dofs_.fixed().distribute_local_to_global(cell_matrix, cell_rhs, dofs, A_static_,
                                                       rhs_static_unit_);
            }
        }
    K_.compress(VectorOperation::add);
    if (dynamic)
      {
        elastic_.K.compress(VectorOperation::add);
        M_.compress(VectorOperation::add);
      }
    A_static_.compress(VectorOperation::add);
    rhs_static_unit_.compress(VectorOperation::add);  // from the journal load at δ = 1
  }

  void Assembler::place_tangent_cell_matrix(const unsigned int active_cell_index,
                                            const std::vector<types::global_dof_index> &dofs,
                                            const FullMatrix<double> &D,
                                            const ContactCellUpdate update)
  {
    K_.add(dofs, D);
    const int k = contact_cell_of_[active_cell_index];
    if (k < 0)
      dofs_.fixed().distribute_local_to_global(D, dofs, A_static_);
    else if (update == ContactCellUpdate::replace)
      contact_cell_matrices_[k] = D;
    else
      contact_cell_matrices_[k].add(1.0, D);
  }

  void Assembler::begin_system()
  {
    A_.copy_from(A_static_);
    rhs_ = 0.0;  // the static part δ·rhs_static_unit_ is added after compress(): adding
                 // into a vector whose last operation was an assignment is collective
  }

  void Assembler::add_to_system(const AffineConstraints<double> &constraints,
                                const FullMatrix<double> &matrix, const Vector<double> &rhs,
                                const std::vector<types::global_dof_index> &dofs)
  {
    constraints.distribute_local_to_global(matrix, rhs, dofs, A_, rhs_);
  }

  /// Then the known load b, condensed: rhs += C^T b, a constrained DoF's entry of b moved to
  /// its masters with the constraint's coefficients (as distribute_local_to_global does with a
  /// cell vector). Every rank moves the entries of the lines of the DoFs it owns.
  void Assembler::finish_system(const double delta, const AffineConstraints<double> &constraints)
  {
    A_.compress(VectorOperation::add);
    rhs_.compress(VectorOperation::add);
    rhs_.add(delta, rhs_static_unit_);
    if (!has_load())
      return;
    const TrilinosWrappers::MPI::Vector moved = dofs_.moved_to_masters(constraints, load_);
    rhs_ += load_;
    rhs_ += moved;
  }

  /// Row-sum lumping of a cell's consistent mass (positive for Lagrange Q1 and Q2: the tensor
  /// products of 1D row sums), then, per displacement component, the mass of the contact
  /// surface's DoFs moved to the cell's other DoFs in proportion to theirs (total mass kept).
  /// Massless contact nodes are the mass redistribution of Khenous, Laborde and Renard (Eur. J.
  /// Mech. A 27, 2008): with mass on the nodes whose displacement the contact prescribes, each
  /// closing node receives an impulse over one time step, so the contact force oscillates and
  /// its peak keeps growing as Δt falls (measured from T_c/20 to T_c/160: docs/fe.md); without
  /// it the semi-discrete problem is well posed and the force converges with Δt.
  void Assembler::lump_and_redistribute(FullMatrix<double> &cell_mass,
                                        const std::vector<types::global_dof_index> &dofs,
                                        const std::set<types::global_dof_index> &surface) const
  {
    const unsigned int n = cell_mass.m();
    std::vector<double> m(n, 0.0);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        m[i] += cell_mass(i, j);
    if (!surface.empty())
      for (unsigned int c = 0; c < dim; ++c)
        {
          double total = 0.0, moved = 0.0;
          for (unsigned int i = 0; i < n; ++i)
            if (dofs_.fe().system_to_component_index(i).first == c)
              {
                total += m[i];
                if (surface.count(dofs[i]))
                  moved += m[i];
              }
          if (moved <= 0.0 || moved >= total)
            continue;  // no surface DoF in the cell (or only: keep its mass where it is)
          for (unsigned int i = 0; i < n; ++i)
            if (dofs_.fe().system_to_component_index(i).first == c)
              m[i] = surface.count(dofs[i]) ? 0.0 : m[i] * total / (total - moved);
        }
    cell_mass = 0.0;
    for (unsigned int i = 0; i < n; ++i)
      cell_mass(i, i) = m[i];
  }

  void Assembler::set_dynamic_operator(const double c_mass, const double c_stiffness,
                                       const LinearElastic &C,
                                       const std::set<types::global_dof_index> &massless)
  {
    kind_ = Operator::dynamic;
    c_mass_ = c_mass;
    c_stiffness_ = c_stiffness;
    for (auto *m : {&K_, &A_static_})
      *m = 0.0;
    M_.reinit(K_);  // K_'s pattern (a new setup may have changed it)
    elastic_.K.reinit(K_);
    load_.reinit(dofs_.owned(), comm_);
    M_ = 0.0;
    elastic_.K = 0.0;
    rhs_static_unit_ = 0.0;
    assemble_static(C, massless);
  }

}  // namespace clearjoint::fe::detail
