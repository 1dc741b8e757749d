// Linear-elastic stiffness: the static part once (cells without contact nodes), and the system
// of one active-set iteration (contact cells condensed with the iteration's constraints).
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  void ContactModel::assemble_static()
  {
    const unsigned int p = fe_->degree;
    const QGauss<dim> quadrature(p + 1);
    FEValues<dim> fe_values(*mapping_, *fe_, quadrature, update_gradients | update_JxW_values);
    const unsigned int n_dofs = fe_->n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n_dofs, n_dofs);
    Vector<double> cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dofs(n_dofs);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(n_dofs);
    std::vector<double> div(n_dofs);

    for (const auto &cell : dof_handler_.active_cell_iterators())
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
                    (material_.lambda * div[i] * div[j] + 2.0 * material_.mu * (eps[i] * eps[j])) * JxW;
            }
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = 0; j < i; ++j)
              cell_matrix(i, j) = cell_matrix(j, i);
          cell->get_dof_indices(dofs);
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
              fixed_constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs,
                                                            A_static_, rhs_static_unit_);
            }
        }
    K_.compress(VectorOperation::add);
    A_static_.compress(VectorOperation::add);
    rhs_static_unit_.compress(VectorOperation::add);  // from the journal load at δ = 1
  }

  /// The condensed system of this iteration: the static part, plus the contact cells condensed
  /// with this iteration's constraints (with the friction rows of slipping nodes), plus the
  /// slip terms of the slipping nodes (c: the complementarity constant [N/m]).
  void ContactModel::assemble_system(const double delta, const double c)
  {
    ScopedTimer timer(t_assemble_);
    A_.copy_from(A_static_);
    rhs_ = 0.0;  // the static part δ·rhs_static_unit_ is added after compress(): adding
                 // into a vector whose last operation was an assignment is collective
    Vector<double> cell_rhs(fe_->n_dofs_per_cell());
    slipping_.clear();
    if (friction_)
      for (unsigned int i = 0; i < nodes_.size(); ++i)
        if (nodes_[i].candidate && nodes_[i].active && !nodes_[i].stick)
          slipping_[nodes_[i].dofs[0]] = i;
    nonsymmetric_ = Utilities::MPI::max(slipping_.empty() ? 0u : 1u, comm_) > 0;
    FullMatrix<double> friction_matrix;
    std::vector<types::global_dof_index> friction_dofs;
    for (unsigned int k = 0; k < contact_cell_matrices_.size(); ++k)
      if (friction_ && friction_cell_matrix(k, friction_matrix, friction_dofs))
        {
          Vector<double> zero(friction_dofs.size());
          constraints_.distribute_local_to_global(friction_matrix, zero, friction_dofs, A_,
                                                  rhs_);
        }
      else
        {
          cell_rhs = 0.0;
          constraints_.distribute_local_to_global(contact_cell_matrices_[k], cell_rhs,
                                                  contact_cell_dofs_[k], A_, rhs_);
        }
    Vector<double> node_rhs;
    for (const auto &[x_dof, i] : slipping_)
      if (nodes_[i].owned)  // once per node over all ranks
        {
          friction_node_matrix(nodes_[i], scene_.contact.tangential_scale * c, delta,
                               friction_matrix, node_rhs, friction_dofs);
          constraints_.distribute_local_to_global(friction_matrix, node_rhs, friction_dofs, A_,
                                                  rhs_);
        }
    A_.compress(VectorOperation::add);
    rhs_.compress(VectorOperation::add);
    rhs_.add(delta, rhs_static_unit_);
  }

} // namespace clearjoint::fe::detail
