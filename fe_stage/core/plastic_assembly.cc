// Elastoplastic bodies (study rolling): the material law with history (material/material_law.h;
// J2 with its hardening table) at every quadrature point, inside the contact model's linear
// machinery. Each
// material Newton iteration linearises the internal force about the current displacement u_k,
//     f_int(u) ≈ f_int(u_k) + K_t (u − u_k) = K_t u − b_k,   b_k = K_t u_k − f_int(u_k),
// so the operator becomes the consistent tangent K_t and b_k the known load (the slot the
// impact study uses for its dynamic load): the active-set contact solve then runs unchanged on
// the linearised problem. K_t differs from the elastic stiffness only at the quadrature points
// that yield in this step, and b_k = (K_t − K_el) u_k + Σ Bᵀ C ε_p only in cells with plastic
// strain, so the elastic matrices are assembled once and only those cells are revisited.
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/step_failure.h"

#include "common/error.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <string>

namespace clearjoint::fe::detail
{
  void Assembler::use_tangent()
  {
    kind_ = Operator::tangent;
    keep_elastic_operator();
    load_.reinit(dofs_.owned(), comm_);
    for (const auto &line : dofs_.fixed().get_lines())
      if (line.inhomogeneity != 0.0)
        throw NumericalError("fe_stage: the elastoplastic assembly needs homogeneous supports "
                             "(a rigid journal, or a deformable one clamped in its own frame); "
                             "DoF " +
                             std::to_string(line.index) + " is prescribed");
  }

  /// The elastic operator, kept: every assembly starts from it.
  void Assembler::keep_elastic_operator()
  {
    elastic_.K.reinit(K_);
    elastic_.K.copy_from(K_);
    elastic_.A_static.reinit(A_static_);
    elastic_.A_static.copy_from(A_static_);
    elastic_.contact_cells = contact_cell_matrices_;
  }

  /// K_ = K_t(u), the condensed static part and the contact cells' matrices the same, and the
  /// load b = K_t u − f_int(u). Trial states are written (the committed ones are the last
  /// converged step's).
  unsigned int Assembler::assemble_tangent(MaterialLaw &material,
                                           const TrilinosWrappers::MPI::Vector &solution)
  {
    unsigned int n_plastic_points = 0;
    const unsigned int n_q = n_q_points();
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature,
                     update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    const unsigned int n = dofs_.fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double> u_cell(n), b_cell(n);
    FullMatrix<double> D(n, n);
    std::vector<SymmetricTensor<2, dim>> eps(n_q), B(n);
    const SymmetricTensor<4, dim> C_el = material.elastic_tangent();

    K_.copy_from(elastic_.K);
    A_static_.copy_from(elastic_.A_static);
    contact_cell_matrices_ = elastic_.contact_cells;
    load_ = 0.0;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_symmetric_gradients(solution, eps);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
          bool yields = false, has_plastic_strain = false;
          std::vector<MaterialResponse> resp(n_q);
          for (unsigned int q = 0; q < n_q; ++q)
            {
              resp[q] = material.evaluate(first + q, eps[q]);
              if (!resp[q].converged)
                throw StepFailure{"the return mapping did not converge at a quadrature point"};
              yields = yields || resp[q].yielding;
              has_plastic_strain =
                has_plastic_strain || material.equivalent_plastic_strain(first + q, true) > 0.0;
              n_plastic_points += resp[q].yielding ? 1 : 0;
            }
          if (!yields && !has_plastic_strain)
            continue;  // elastic: its share of K_el and of b (zero) is already there
          cell->get_dof_indices(dofs);
          cell->get_dof_values(solution, u_cell);
          D = 0.0;
          b_cell = 0.0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              for (unsigned int i = 0; i < n; ++i)
                B[i] = fv[u].symmetric_gradient(i, q);
              const double JxW = fv.JxW(q);
              // Σ Bᵀ C_el ε_p: the plastic strain's share of K_el u − f_int
              const SymmetricTensor<2, dim> s_p = C_el * material.plastic_strain(first + q, true);
              for (unsigned int i = 0; i < n; ++i)
                b_cell(i) += (B[i] * s_p) * JxW;
              if (!resp[q].yielding)
                continue;
              const SymmetricTensor<4, dim> dC = resp[q].tangent - C_el;
              for (unsigned int j = 0; j < n; ++j)
                {
                  const SymmetricTensor<2, dim> dCB = dC * B[j];
                  for (unsigned int i = 0; i < n; ++i)
                    D(i, j) += (B[i] * dCB) * JxW;
                }
            }
          D.vmult_add(b_cell, u_cell);  // + (K_t − K_el) u
          load_.add(dofs, b_cell);
          if (!yields)
            continue;
          place_tangent_cell_matrix(cell->active_cell_index(), dofs, D, ContactCellUpdate::add);
        }
    K_.compress(VectorOperation::add);
    A_static_.compress(VectorOperation::add);
    load_.compress(VectorOperation::add);
    return Utilities::MPI::sum(n_plastic_points, comm_);
  }
}  // namespace clearjoint::fe::detail
