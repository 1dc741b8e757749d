// Finite kinematics (material.kinematics: finite; issue 30, FE_DESIGN §4.2): the total-
// Lagrangian tangent and internal force, in the slot of the elastoplastic tangent (core/
// plastic_assembly.cc). Each material Newton iteration linearises the internal force about the
// current displacement u_k,
//     f_int(u) ≈ f_int(u_k) + K_t (u − u_k) = K_t u − b_k,   b_k = K_t u_k − f_int(u_k),
// with, on the reference configuration (deal.II step-44's kinematics),
//     f_int,a = ∫ P(F) : ∇N_a dV,   K_t,ab = ∫ ∇N_a : A : ∇N_b dV,   A = dP/dF,
// F = I + ∇u, so that the active-set contact solve runs unchanged on the linearised problem.
// A carries the geometric stiffness (δ_ik S_JL) beside the material part. The vector-valued
// shape function of DoF a is e_c ⊗ φ_a (one component c), so ∇N_a : A : ∇N_b is
// ∇φ_a · A_{c_a · c_b ·} ∇φ_b: nine products per pair instead of 81.
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/step_failure.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace clearjoint::fe::detail
{
  unsigned int Assembler::assemble_finite_tangent(MaterialLaw &material,
                                                  const TrilinosWrappers::MPI::Vector &solution)
  {
    unsigned int n_plastic_points = 0;
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    const unsigned int n_q = quadrature.size();
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature,
                     update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    const unsigned int n = dofs_.fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    std::vector<unsigned int> component(n);
    for (unsigned int i = 0; i < n; ++i)
      component[i] = dofs_.fe().system_to_component_index(i).first;
    Vector<double> u_cell(n), f_cell(n), b_cell(n);
    FullMatrix<double> D(n, n);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<Tensor<1, dim>> grad_phi(n);

    K_ = 0.0;
    A_static_ = 0.0;
    load_ = 0.0;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(solution, grad_u);
          cell->get_dof_indices(dofs);
          cell->get_dof_values(solution, u_cell);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
          D = 0.0;
          f_cell = 0.0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const FiniteResponse r = material.evaluate_finite(first + q, grad_u[q]);
              if (!r.converged)
                throw StepFailure{"the finite-strain law failed at a quadrature point: " +
                                  r.reason};
              n_plastic_points += r.yielding ? 1 : 0;
              const double JxW = fv.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                grad_phi[i] = fv.shape_grad_component(i, q, component[i]);
              for (unsigned int i = 0; i < n; ++i)
                {
                  const unsigned int ci = component[i];
                  double f = 0.0;
                  for (unsigned int J = 0; J < dim; ++J)
                    f += r.stress[ci][J] * grad_phi[i][J];
                  f_cell(i) += f * JxW;
                  for (unsigned int j = 0; j < n; ++j)
                    {
                      const unsigned int cj = component[j];
                      double k = 0.0;
                      for (unsigned int J = 0; J < dim; ++J)
                        for (unsigned int L = 0; L < dim; ++L)
                          k += grad_phi[i][J] * r.tangent[ci][J][cj][L] * grad_phi[j][L];
                      D(i, j) += k * JxW;
                    }
                }
            }
          D.vmult(b_cell, u_cell);  // b = K_t u − f_int
          b_cell -= f_cell;
          load_.add(dofs, b_cell);
          place_tangent_cell_matrix(cell->active_cell_index(), dofs, D, ContactCellUpdate::replace);
        }
    K_.compress(VectorOperation::add);
    A_static_.compress(VectorOperation::add);
    load_.compress(VectorOperation::add);
    return Utilities::MPI::sum(n_plastic_points, comm_);
  }
}  // namespace clearjoint::fe::detail
