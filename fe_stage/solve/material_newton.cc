// The material Newton iteration (solve/material_newton.h).
#include "fe_stage/solve/material_newton.h"

#include "fe_stage/core/step_failure.h"

#include "common/error.h"
#include "common/log.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::fe::detail
{
  MaterialNewton::MaterialNewton(MaterialProblem &problem, const Parts &parts)
    : problem_(problem)
    , parts_(parts)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
  {}

  MaterialIteration MaterialNewton::iterate(
    const double delta, const bool line_search,
    const std::function<void(const TrilinosWrappers::MPI::Vector &u_start)> &after_solve)
  {
    MaterialIteration it;
    if (tangent_current_ && [&] {
          TrilinosWrappers::MPI::Vector moved = parts_.state.u_owned();
          moved -= u_at_tangent_;
          return moved.linfty_norm() == 0.0;
        }())
      {
        problem_.set_contact_load_offsets();  // (the contact nodes may have been paired again)
        it.n_plastic_points = n_plastic_at_tangent_;
      }
    else
      it.n_plastic_points = problem_.assemble_plastic();
    tangent_current_ = false;
    TrilinosWrappers::MPI::Vector r_start;
    if (line_search)
      r_start = interior_forces();
    const TrilinosWrappers::MPI::Vector u_start = parts_.state.u_owned();
    it.record = problem_.solve_increment(delta);
    if (after_solve)
      after_solve(u_start);
    TrilinosWrappers::MPI::Vector step = parts_.state.u_owned();
    step -= u_start;
    it.correction = step.linfty_norm();
    if (!std::isfinite(it.correction))
      throw StepFailure{"non-finite displacement in the material Newton iteration"};
    if (line_search && it.correction > tolerance())
      {
        // g(0) < 0 for a Newton step (d·r = −d·K_t d); not a descent direction (a contact
        // solve that moved the active set): the full step, as without a search
        const double g0 = r_start * step;
        if (g0 < 0.0)
          search_line(it, g0, u_start, step);
      }
    return it;
  }

  /// The line search (Crisfield's, on the energy along the step; Abaqus/Standard's is of this
  /// kind): the elastoplastic bodies' incremental potential Π (J2 with associated flow has
  /// one) along u + s d has the slope g(s) = d · r(u + s d), r the interior out-of-balance
  /// force. The full step is taken when it brings |g| below ½|g(0)| or still descends; else s
  /// is found by regula falsi on g over the bracket, at most four more evaluations, s ≥ 0.05.
  /// Why: where points switch between plastic and elastic (a plastic tangent ~1/740 of the
  /// elastic one with the SPEC hardening) the full step overshoots; on the paper's 1 mm case
  /// the corrections then grew ×2 an iteration and the step was cut (docs/fe.md). Each
  /// evaluation assembles the tangent at u + s d: the accepted one's is the next iteration's.
  void MaterialNewton::search_line(MaterialIteration &it, const double g0,
                                   const TrilinosWrappers::MPI::Vector &u_start,
                                   const TrilinosWrappers::MPI::Vector &step)
  {
    constexpr unsigned int max_reductions = 4;
    constexpr double accept = 0.5, s_min = 0.05;
    // the bracket [s_lo, s_hi] of g's root (g(s_lo) < 0 < g(s_hi)): the first rejection is
    // the full step's, where g > 0
    double s_lo = 0.0, g_lo = g0, s_hi = 1.0, g_hi = 0.0;
    double s = 1.0;
    for (unsigned int reductions = 0;; ++reductions)
      {
        const unsigned int n_plastic = problem_.assemble_plastic();
        const double g = interior_forces() * step;
        if (log::level() <= log::Level::debug && rank_ == 0)
          log::debug("  line search: step length " + format_value(s) + ", slope " +
                     format_value(g) + " J (at 0: " + format_value(g0) + " J)");
        if (std::abs(g) <= accept * std::abs(g0) || (s == 1.0 && g < 0.0) ||
            reductions == max_reductions || s == s_min)
          {
            tangent_current_ = true;
            u_at_tangent_ = parts_.state.u_owned();
            n_plastic_at_tangent_ = n_plastic;
            it.n_plastic_points = n_plastic;
            it.step_length = s;
            return;
          }
        ++it.line_search_steps;
        if (g < 0.0)
          s_lo = s, g_lo = g;
        else
          s_hi = s, g_hi = g;
        // the root of g's secant over the bracket, kept inside its middle 80 %
        const double width = s_hi - s_lo;
        const double root = s_lo - g_lo * (s_hi - s_lo) / (g_hi - g_lo);
        s = std::max(std::clamp(root, s_lo + 0.1 * width, s_lo + 0.9 * width), s_min);
        parts_.state.u_owned() = u_start;
        parts_.state.u_owned().add(s, step);
        parts_.state.publish();
      }
  }

  TrilinosWrappers::MPI::Vector MaterialNewton::interior_forces() const
  {
    TrilinosWrappers::MPI::Vector r(parts_.dofs.owned(), parts_.comm);
    parts_.system.operator_matrix().vmult(r, parts_.state.u_owned());
    r -= parts_.system.load();
    parts_.dofs.condense_hanging(r);
    for (const auto &line : parts_.dofs.fixed().get_lines())
      if (parts_.dofs.owned().is_element(line.index))
        r[line.index] = 0.0;
    for (const auto &cn : parts_.contact.nodes())
      {
        for (const auto d : cn.dofs)
          if (parts_.dofs.owned().is_element(d))
            r[d] = 0.0;
        for (const auto &p : cn.partners)
          for (const auto d : p.dofs)
            if (parts_.dofs.owned().is_element(d))
              r[d] = 0.0;
      }
    r.compress(VectorOperation::insert);
    return r;
  }

  MaterialSolve MaterialNewton::solve(const double delta, const unsigned int max_it)
  {
    MaterialSolve ms;
    const double tolerance = this->tolerance();
    double last_correction = 0.0;
    unsigned int growths = 0;
    for (unsigned int k = 0;; ++k)
      {
        const MaterialIteration it = iterate(delta, k > 0 && parts_.scene.solver.line_search);
        ms.record = it.record;
        ms.line_search_steps += it.line_search_steps;
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

}  // namespace clearjoint::fe::detail
