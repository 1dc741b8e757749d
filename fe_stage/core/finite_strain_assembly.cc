// Finite kinematics (material.kinematics: finite; issue 30, FE_DESIGN §4.2): the total-
// Lagrangian tangent and internal force, in the slot of the elastoplastic tangent (core/
// plastic_assembly.cc). Each material Newton iteration linearises the internal force about the
// current displacement u_k,
//     f_int(u) ≈ f_int(u_k) + K_t (u − u_k) = K_t u − b_k,   b_k = K_t u_k − f_int(u_k),
// with, on the reference configuration (deal.II step-44's kinematics),
//     f_int,a = ∫ P(F) : ∇N_a dV,   K_t,ab = ∫ ∇N_a : A : ∇N_b dV,   A = dP/dF,
// F = I + ∇u, so that the active-set contact solve runs unchanged on the linearised problem.
// A carries the geometric stiffness (δ_ik S_JL) beside the material part. The vector-valued
// shape function of DoF a is e_c ⊗ φ_s (one component c of the scalar shape function s), so
// ∇N_a : A : ∇N_b is ∇φ_s · A_{c · c' ·} ∇φ_s'. The 3 × 3 block of every pair of scalar shape
// functions (s, s') is computed at once: first T_s'[i][J][k] = A_iJkL ∂_L φ_s' for each s', then
// the block ∂_J φ_s T_s'[i][J][k]. For FE_Q(2)^3 (27 scalar functions) that is ~26 k products a
// quadrature point where the pair-by-pair sum of DoFs took ~59 k, with the fourth-order
// tensor read 27 times instead of 6 561. A is major-symmetric (A_iJkL = A_kLiJ: the geometric
// part δ_ik S_JL with S symmetric, and F ℂ F with ℂ the symmetric algorithmic tangent of this
// associative law, material/finite_j2.h), so block (s', s) is block (s, s') transposed: only
// s' ≥ s are summed, into a per-cell array laid out by blocks, and D is filled from it once a
// cell (half the products, and no indexed FullMatrix access at every quadrature point; ~8 % of
// the fast rolling case's CPU, docs/benchmarks.md). A law without that symmetry would need the
// full sum again: FiniteAssembly.TangentIsTheDerivativeOfTheInternalForce would fail on it.
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/step_failure.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <array>

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
    // the cell DoF of each (scalar shape function, component): FESystem of dim equal scalar
    // elements
    const unsigned int n_scalar = n / dim;
    std::vector<std::array<unsigned int, dim>> dof_of(n_scalar);
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto [c, s] = dofs_.fe().system_to_component_index(i);
        dof_of[s][c] = i;
      }
    std::vector<types::global_dof_index> dofs(n);
    Vector<double> u_cell(n), f_cell(n), b_cell(n);
    FullMatrix<double> D(n, n);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<Tensor<1, dim>> grad_phi(n_scalar);  // ∇φ_s at the point
    std::vector<Tensor<3, dim>> T(n_scalar);         // T_s[i][J][k] = A_iJkL ∂_L φ_s
    // the cell's blocks (s, s2 ≥ s): block[(s * n_scalar + s2) * 9 + 3 i + k] = D(s_i, s2_k)
    std::vector<double> block(n_scalar * n_scalar * dim * dim);

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
          std::fill(block.begin(), block.end(), 0.0);
          f_cell = 0.0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const FiniteResponse r = material.evaluate_finite(first + q, grad_u[q]);
              if (!r.converged)
                throw StepFailure{"the finite-strain law failed at a quadrature point: " +
                                  r.reason};
              n_plastic_points += r.yielding ? 1 : 0;
              const double JxW = fv.JxW(q);
              for (unsigned int s = 0; s < n_scalar; ++s)
                grad_phi[s] = fv.shape_grad_component(dof_of[s][0], q, 0);
              for (unsigned int s = 0; s < n_scalar; ++s)
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int J = 0; J < dim; ++J)
                    for (unsigned int k = 0; k < dim; ++k)
                      {
                        double t = 0.0;
                        for (unsigned int L = 0; L < dim; ++L)
                          t += r.tangent[i][J][k][L] * grad_phi[s][L];
                        T[s][i][J][k] = t * JxW;
                      }
              for (unsigned int s = 0; s < n_scalar; ++s)
                {
                  const Tensor<1, dim> &g = grad_phi[s];
                  for (unsigned int i = 0; i < dim; ++i)
                    f_cell(dof_of[s][i]) += (r.stress[i] * g) * JxW;
                  for (unsigned int s2 = s; s2 < n_scalar; ++s2)
                    {
                      double *b = &block[(s * n_scalar + s2) * dim * dim];
                      for (unsigned int i = 0; i < dim; ++i)
                        for (unsigned int k = 0; k < dim; ++k)
                          for (unsigned int J = 0; J < dim; ++J)
                            b[dim * i + k] += g[J] * T[s2][i][J][k];
                    }
                }
            }
          for (unsigned int s = 0; s < n_scalar; ++s)
            for (unsigned int s2 = s; s2 < n_scalar; ++s2)
              {
                const double *b = &block[(s * n_scalar + s2) * dim * dim];
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int k = 0; k < dim; ++k)
                    {
                      D(dof_of[s][i], dof_of[s2][k]) = b[dim * i + k];
                      D(dof_of[s2][k], dof_of[s][i]) = b[dim * i + k];
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
