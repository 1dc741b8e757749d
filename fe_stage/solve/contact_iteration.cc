// One load increment (ContactSolve, solve/contact_solve.h): active-set iterations (contact
// lines, assembly, solve, evaluation, normal and Coulomb decisions) until the sets and the slip
// directions settle.
#include "fe_stage/solve/contact_solve.h"

#include "fe_stage/contact/stick_slip_progress.h"
#include "fe_stage/core/step_failure.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace clearjoint::fe::detail
{
  ContactSolve::ContactSolve(const Parts &parts)
    : scene_(parts.scene)
    , plan_(parts.plan)
    , bodies_(parts.bodies)
    , dofs_(parts.dofs)
    , contact_(parts.contact)
    , obstacle_(parts.obstacle)
    , frame_(parts.frame)
    , system_(parts.system)
    , state_(parts.state)
    , solver_(parts.solver)
    , comm_(parts.comm)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
    // only rank 0 logs at the debug level (-v), but the check's maximum is collective: every
    // rank must take part (a two-rank run with -v stopped with MPI_ERR_TRUNCATE without this)
    , check_friction_rows_(
        Utilities::MPI::max(log::level() <= log::Level::debug ? 1 : 0, parts.comm) == 1)
  {}

  /// The condensed system of this iteration: the static part, plus the contact cells condensed
  /// with this iteration's constraints (with the friction rows of slipping nodes), plus the
  /// slip terms of the slipping nodes (c: the complementarity constant [N/m]).
  void ContactSolve::assemble_system(const double delta, const double c)
  {
    ScopedTimer timer(t_assemble_);
    system_.begin_system();
    Vector<double> cell_rhs(dofs_.fe().n_dofs_per_cell());
    contact_.collect_slipping();
    FullMatrix<double> friction_matrix;
    std::vector<types::global_dof_index> friction_dofs;
    for (unsigned int k = 0; k < system_.n_contact_cells(); ++k)
      if (contact_.friction() && friction_cell_matrix(k, friction_matrix, friction_dofs))
        {
          Vector<double> zero(friction_dofs.size());
          system_.add_to_system(constraints_, friction_matrix, zero, friction_dofs);
        }
      else
        {
          cell_rhs = 0.0;
          system_.add_to_system(constraints_, system_.contact_cell_matrix(k), cell_rhs,
                                system_.contact_cell_dofs(k));
        }
    Vector<double> node_rhs;
    for (const unsigned int i : contact_.slipping())
      if (contact_.nodes()[i].owned)  // once per node over all ranks
        {
          friction_node_matrix(contact_.nodes()[i], contact_.tangential_scale() * c, delta,
                               friction_matrix, node_rhs, friction_dofs);
          system_.add_to_system(constraints_, friction_matrix, node_rhs, friction_dofs);
        }
    system_.finish_system(delta, constraints_);
  }

  IncrementRecord ContactSolve::solve_increment(const double delta)
  {
    IncrementRecord rec;
    rec.delta = delta;
    set_obstacle_position(delta);
    dofs_.set_delta(delta);
    const double c = complementarity_constant();
    // ε_g: a penetration below this is round-off, not contact (makes the active set
    // deterministic across rank counts). 1e-9 of the push is far below any physical effect.
    const double eps_g = 1e-9 * scene_.loading.delta_max;
    // Coulomb's slip law holds when |t − μλŵ| ≤ 1e-6 of the largest nodal force at every
    // slipping node: summed over the slipping nodes (tens) that moves F by < 1e-6 (the
    // nodal forces are ~2 % of F), far below the discretisation error, and Newton's quadratic
    // convergence usually lands well below it (1e-7 → 1e-12, docs/fe.md).
    const double slip_tolerance = 1e-6;
    // friction's c_T: the scene's at the start of each increment, lowered while the stick/slip
    // decisions cycle (contact/active_set.cc)
    contact_.reset_tangential_scale();
    // Inexact solves while the sets still move: an iteration whose active or stick set will
    // change again only decides the next sets, so its linear solve stops at a relative residual
    // of 1e-6 instead of solver.tolerance (1e-10): about 40 % fewer Krylov iterations. The
    // first solve after the predictor is such an iteration; an iteration that settles after a
    // loose solve is not accepted but solved again to the full tolerance (from the loose
    // solution, so cheaply), and so is every Newton step on the slip law once the sets have
    // settled. The converged state is therefore the one of exact solves (docs/fe.md).
    const double loose_tolerance = std::max(scene_.solver.tolerance, 1e-6);
    bool loose = !solver_.direct() && scene_.contact.max_iterations > 1;  // (MUMPS: exact anyway)

    // (a stick/slip iteration that cycles lowers c_T at once, contact/stick_slip_progress.h)
    StickSlipProgress progress;
    bool cycles = false;
    unsigned int it = 0;
    for (; it < scene_.contact.max_iterations; ++it)
      {
        if (contact_.soften_tangential_scale(it, cycles))
          {
            if (log::level() <= log::Level::debug)
              log::debug("  delta " + format_value(delta) + " m: the stick/slip decisions " +
                         (cycles ? "cycle" : "have not settled") + " after " + std::to_string(it) +
                         " iterations; c_T now " + format_value(contact_.tangential_scale()) +
                         " c");
            progress.restart();
          }
        build_contact_constraints(delta);
        assemble_system(delta, c);

        constraints_.set_zero(state_.u_owned());  // start from the previous solution
        {
          ScopedTimer timer(t_solve_);
          rec.linear_iterations +=
            solver_.solve(system_.system(), contact_.nonsymmetric(), dofs_.handler(),
                          bodies_.mapping(), state_.u_owned(), system_.rhs(),
                          loose ? loose_tolerance : scene_.solver.tolerance);
        }
        ScopedTimer eval_timer(t_evaluate_);
        constraints_.distribute(state_.u_owned());
        state_.publish();
        evaluate_contact(delta);
        if (contact_.friction() && check_friction_rows_)
          {
            // the friction rows' own check: at a node that slipped in this solve the solved
            // tangential force must be the linearised slip law it was given (round-off)
            double mismatch = 0.0;
            for (const unsigned int i : contact_.slipping())
              if (contact_.nodes()[i].owned)
                {
                  const ContactNode &cn = contact_.nodes()[i];
                  const Tensor<1, dim> t = tangential(contact_.traction(cn), cn.n);
                  const Tensor<2, dim> Q = ContactProblem::tangent_projection(cn) -
                                           outer_product(cn.slip_direction, cn.slip_direction);
                  const Tensor<1, dim> F =
                    scene_.contact.mu * cn.lambda * cn.slip_direction +
                    cn.kappa *
                      (Q * (t - contact_.tangential_scale() * c * contact_.slip_increment(cn)));
                  mismatch = std::max(mismatch, (t - F).norm());
                }
            log::debug("  friction rows: largest |t - F(u)| " +
                       format_value(Utilities::MPI::max(mismatch, comm_)) + " N");
          }
        const auto change = contact_.update_active_set(c, eps_g);
        const bool slip_settled = change.slip_residual <= slip_tolerance * change.force_scale;
        cycles = progress.record(change.slip_residual, slip_settled);
        if (log::level() <= log::Level::debug)
          log::debug("  delta " + format_value(delta) + " m, iteration " + std::to_string(it + 1) +
                     ": " + std::to_string(change.n_changed) +
                     " nodes changed, slip-law residual " + format_value(change.slip_residual) +
                     " N (largest nodal force " + format_value(change.force_scale) + " N)" +
                     (change.changed.empty() ?
                        "" :
                        "; rank " + std::to_string(rank_) + ": " + change.changed));
        if (change.n_changed == 0 && slip_settled && !loose)
          {
            ++it;
            break;
          }
        // the next solve may be loose only while the sets are still changing, and never the
        // last one allowed (a state that settles there must be one of exact solves)
        loose = !solver_.direct() && change.n_changed > 0 && it + 2 < scene_.contact.max_iterations;
        if (it + 1 == scene_.contact.max_iterations)
          throw StepFailure{
            "active set did not settle in " + std::to_string(it + 1) + " iterations (" +
            std::to_string(change.n_changed) + " nodes still changing" +
            (change.changed.empty() ? "" : ", e.g. " + change.changed) +
            (slip_settled ? "" :
                            ", slip-law residual " + format_value(change.slip_residual) + " N") +
            ")"};
      }
    rec.contact_iterations = it;
    record_forces(delta, rec);
    return rec;
  }

  /// (the bordered spin iteration's column: the sets kept, so that the difference to the
  /// increment's own solve is the linearised problem's dependence on the frame alone)
  unsigned int ContactSolve::solve_with_sets_kept(const double delta,
                                                  const TrilinosWrappers::MPI::Vector &guess)
  {
    set_obstacle_position(delta);
    dofs_.set_delta(delta);
    build_contact_constraints(delta);
    assemble_system(delta, complementarity_constant());
    state_.u_owned() = guess;
    constraints_.set_zero(state_.u_owned());
    unsigned int linear_iterations = 0;
    {
      ScopedTimer timer(t_solve_);
      linear_iterations =
        solver_.solve(system_.system(), contact_.nonsymmetric(), dofs_.handler(), bodies_.mapping(),
                      state_.u_owned(), system_.rhs(), scene_.solver.tolerance);
    }
    ScopedTimer eval_timer(t_evaluate_);
    constraints_.distribute(state_.u_owned());
    state_.publish();
    evaluate_contact(delta);
    return linear_iterations;
  }
}  // namespace clearjoint::fe::detail
