// One load increment: active-set iterations (contact lines, assembly, solve, evaluation,
// normal and Coulomb decisions) until the sets and the slip directions settle.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  IncrementRecord ContactModel::solve_increment(const double delta)
  {
    IncrementRecord rec;
    rec.delta = delta;
    set_obstacle_position(delta);
    set_fixed_constraints_for(delta);
    const double c = scene_.contact.active_set_scale * scene_.material.E * h_min_;  // [N/m]
    // ε_g: a penetration below this is round-off, not contact (makes the active set
    // deterministic across rank counts). 1e-9 of the push is far below any physical effect.
    const double eps_g = 1e-9 * scene_.loading.delta_max;
    for (auto &cn : nodes_)
      cn.stick_slip_flips = cn.contact_flips = 0;
    double omega = 1.0;
    bool relaxation_history = false;

    unsigned int it = 0;
    for (; it < scene_.contact.max_iterations; ++it)
      {
        build_contact_constraints(delta);
        assemble_system(delta);

        constraints_.set_zero(solution_owned_);  // start from the previous solution
        {
          ScopedTimer timer(t_solve_);
          rec.linear_iterations += solve_linear(solution_owned_, rhs_);
        }
        ScopedTimer eval_timer(t_evaluate_);
        constraints_.distribute(solution_owned_);
        solution_ = solution_owned_;
        evaluate_contact(delta);
        const auto [n_changed, max_direction_change] =
          update_active_set(c, eps_g, omega, relaxation_history);
        // slip directions settled: the friction forces are μλ·e to 1e-5 of μλ (~1e-7 of F,
        // friction being ~0.5 % of it)
        const bool forces_settled = Utilities::MPI::max(max_direction_change, comm_) <= 1e-5;
        if (n_changed == 0 && forces_settled)
          {
            ++it;
            break;
          }
        if (it + 1 == scene_.contact.max_iterations)
          throw StepFailure{"active set did not settle in " + std::to_string(it + 1) +
                            " iterations (" + std::to_string(n_changed) + " nodes still changing" +
                            (forces_settled ? "" : ", slip forces still changing") + ")"};
      }
    rec.contact_iterations = it;
    record_forces(delta, rec);
    return rec;
  }
} // namespace clearjoint::fe::detail
