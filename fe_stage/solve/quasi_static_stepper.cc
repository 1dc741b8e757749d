// The quasi-static push (solve/quasi_static_stepper.h).
#include "fe_stage/solve/quasi_static_stepper.h"

#include "fe_stage/core/step_failure.h"
#include "fe_stage/solve/step_controller.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>

#include <algorithm>

namespace clearjoint::fe::detail
{
  QuasiStaticStepper::QuasiStaticStepper(QuasiStaticProblem &problem, const Parts &parts)
    : problem_(problem)
    , parts_(parts)
    , rank_(dealii::Utilities::MPI::this_mpi_process(parts.comm))
  {}

  bool QuasiStaticStepper::push_through(
    const std::vector<double> &targets, std::string &message,
    const std::function<void(unsigned int, IncrementRecord &)> &on_converged)
  {
    const auto &L = parts_.scene.loading;
    problem_.start_from_rest();
    double delta_done = 0.0, delta_previous = 0.0;
    bool have_previous = false;
    TrilinosWrappers::MPI::Vector solution_previous(parts_.dofs.owned(), parts_.comm);
    for (unsigned int inc = 1; inc <= targets.size(); ++inc)
      {
        const double target = targets[inc - 1];
        StepController control(target - delta_done, L.max_cuts, 1);
        IncrementRecord rec;
        unsigned int total_contact_its = 0, total_linear_its = 0;
        while (delta_done < target)
          {
            const double try_delta = std::min(target, delta_done + control.size());
            // keep what converged so far, to restore after a failed attempt
            const Snapshot saved = problem_.save_state();
            try
              {
                if (have_previous && delta_done > delta_previous)
                  predict(try_delta, delta_done, delta_previous, solution_previous);
                rec = solve_state(try_delta, saved.u);
                if (problem_.elastoplastic())
                  problem_.commit_material();  // the last step that may throw: accepted
                for (auto &cn : parts_.contact.nodes())
                  cn.relative_converged = cn.relative;  // friction: slip counts from here
                solution_previous = saved.u;
                delta_previous = delta_done;
                have_previous = true;
                total_contact_its += rec.contact_iterations;
                total_linear_its += rec.linear_iterations;
                delta_done = try_delta;
              }
            catch (const StepFailure &f)
              {
                problem_.restore_state(saved);
                if (!control.cut())
                  {
                    message = "increment " + std::to_string(inc) +
                              " to delta = " + format_value(try_delta) + " m failed after " +
                              std::to_string(control.cuts()) + " cuts: " + f.reason;
                    if (rank_ == 0)
                      log::error("fe_stage: " + message);
                    return false;
                  }
                if (rank_ == 0)
                  log::warning("fe_stage: increment " + std::to_string(inc) +
                               " to delta = " + format_value(try_delta) + " m failed (" + f.reason +
                               "); retrying with step " + format_value(control.size()) + " m");
              }
          }
        rec.contact_iterations = total_contact_its;
        rec.linear_iterations = total_linear_its;
        on_converged(inc, rec);
      }
    return true;
  }

  void QuasiStaticStepper::predict(const double try_delta, const double delta_done,
                                   const double delta_previous,
                                   const TrilinosWrappers::MPI::Vector &u_previous)
  {
    const double ratio = (try_delta - delta_done) / (delta_done - delta_previous);
    parts_.state.u_owned().sadd(1.0 + ratio, -ratio, u_previous);
    parts_.state.publish();
    problem_.evaluate_contact_at(try_delta);
    const double eps_g = 1e-9 * parts_.scene.loading.delta_max;
    for (auto &cn : parts_.contact.nodes())
      if (cn.candidate && cn.gap < -eps_g)
        cn.active = true;
  }

  IncrementRecord QuasiStaticStepper::solve_state(const double delta,
                                                  const TrilinosWrappers::MPI::Vector &u_start)
  {
    IncrementRecord rec;
    if (problem_.elastoplastic())
      {
        const MaterialSolve m =
          parts_.newton.solve(delta, parts_.scene.solver.max_newton_iterations);
        rec = m.record;
        rec.contact_iterations = m.contact_iterations;
        rec.linear_iterations = m.linear_iterations;
      }
    else
      rec = problem_.solve_increment(delta);
    if (parts_.finite_sliding)
      rec = settle_sliding(delta, u_start, rec);
    return rec;
  }

  /// Converged when Σ_m |ΔC_sm| and |Δgap|/δ_max are below 1e-3 at every node: the state is
  /// then in equilibrium with the partners that face it.
  IncrementRecord QuasiStaticStepper::settle_sliding(const double delta,
                                                     const TrilinosWrappers::MPI::Vector &u_start,
                                                     IncrementRecord rec)
  {
    constexpr unsigned int max_searches = 10;
    constexpr double settled = 1e-3;
    unsigned int its = rec.contact_iterations, linear = rec.linear_iterations;
    for (unsigned int search = 1;; ++search)
      {
        const double change = problem_.pair_deformed_surfaces(u_start);
        if (rank_ == 0)
          log::debug("fe_stage: finite sliding: search " + std::to_string(search) +
                     ", coupling moved by " + format_value(change));
        if (change <= settled)
          break;
        if (search == max_searches)
          throw StepFailure{"finite sliding: the contact coupling still moved by " +
                            format_value(change) + " after " + std::to_string(max_searches) +
                            " searches (the surfaces slide too far in one increment)"};
        rec = problem_.solve_increment(delta);
        its += rec.contact_iterations;
        linear += rec.linear_iterations;
        ++n_sliding_resolves_;
      }
    rec.contact_iterations = its;
    rec.linear_iterations = linear;
    return rec;
  }
}  // namespace clearjoint::fe::detail
