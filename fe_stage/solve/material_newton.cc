// The material Newton iteration of an elastoplastic state (the rolling study's states and the
// elastoplastic quasi-static push): the tangent and its load at the current displacement
// (small or finite kinematics), the active-set contact solve of the linearised problem, until
// the correction is negligible; and the commit of a converged state's history.
#include "fe_stage/core/contact_model.h"

#include <cmath>

namespace clearjoint::fe::detail
{
  unsigned int ContactModel::assemble_plastic()
  {
    unsigned int n_plastic_points = 0;
    {
      ScopedTimer timer(t_assemble_);
      n_plastic_points = scene_.material.kinematics == Material::Kinematics::finite ?
                           system_.assemble_finite_tangent(*material_, state_.u()) :
                           system_.assemble_tangent(*material_, state_.u());
    }
    set_contact_load_offsets();
    return n_plastic_points;
  }

  ContactModel::MaterialIteration ContactModel::material_iteration(const double delta)
  {
    MaterialIteration it;
    it.n_plastic_points = assemble_plastic();
    TrilinosWrappers::MPI::Vector before = state_.u_owned();
    it.record = solve_increment(delta);
    before -= state_.u_owned();
    it.correction = before.linfty_norm();
    if (!std::isfinite(it.correction))
      throw StepFailure{"non-finite displacement in the material Newton iteration"};
    return it;
  }

  ContactModel::MaterialSolve ContactModel::solve_material_state(const double delta,
                                                                 const unsigned int max_it)
  {
    MaterialSolve ms;
    const double tolerance = material_tolerance();
    double last_correction = 0.0;
    unsigned int growths = 0;
    for (unsigned int k = 0;; ++k)
      {
        const MaterialIteration it = material_iteration(delta);
        ms.record = it.record;
        ms.contact_iterations += it.record.contact_iterations;
        ms.linear_iterations += it.record.linear_iterations;
        ms.newton_iterations = k + 1;
        const double correction = it.correction;
        if (log::level() <= log::Level::debug && rank_ == 0)
          log::debug("  material Newton iteration " + std::to_string(k + 1) + ": correction " +
                     format_value(correction) + " m, " + std::to_string(it.n_plastic_points) +
                     " quadrature points yielding, contact force " + format_value(it.record.force) +
                     " N");
        if (correction <= tolerance)
          break;
        // diverging (the correction grew in each of the last three iterations): give up at
        // once, so that the step is cut instead of running out its iterations
        growths = k > 0 && correction > last_correction ? growths + 1 : 0;
        last_correction = correction;
        if (growths >= 3)
          throw StepFailure{"the material Newton iteration diverges (the correction grew in "
                            "three iterations running, to " +
                            format_value(correction) + " m)"};
        if (k + 1 >= max_it)
          throw StepFailure{"the material Newton iteration did not converge in " +
                            std::to_string(max_it) + " iterations (last correction " +
                            format_value(correction) + " m)"};
      }
    return ms;
  }

  /// The last assembly left trial states at the last Newton iterate, not at the converged
  /// displacement: evaluate every point there again, then make it the point's history.
  void ContactModel::commit_material()
  {
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    const unsigned int n_q = quadrature.size();
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    const bool finite = scene_.material.kinematics == Material::Kinematics::finite;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(state_.u(), grad_u);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const bool converged =
                finite ? material_->evaluate_finite(first + q, grad_u[q]).converged :
                         material_->evaluate(first + q, symmetrize(grad_u[q])).converged;
              if (!converged)  // (nothing committed yet: the step can still be cut)
                throw StepFailure{"the material law failed at a quadrature point of the "
                                  "converged state"};
            }
        }
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int q = 0; q < n_q; ++q)
          material_->commit(std::size_t(cell->active_cell_index()) * n_q + q);
  }
}  // namespace clearjoint::fe::detail
