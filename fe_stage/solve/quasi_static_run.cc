// The quasi-static studies' run (QuasiStaticRun, solve/quasi_static_run.h): the push from 0 to
// δ_max in increments (QuasiStaticStepper, solve/quasi_static_stepper.h), one log line per
// increment (as an Abaqus .sta file) with an ETA, and the yield check of the last converged
// state; before it, the adaptive cycles (mesh.adaptive_cycles: curve, Kelly indicator,
// refinement) and the error estimate from their sequence.
#include "fe_stage/solve/quasi_static_run.h"

#include "fe_stage/solve/adaptive_cycles.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cstdio>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// The recorded curve on the final mesh as the adaptive sequence's last member.
    AdaptiveCycle curve_as_cycle(const RunResult &result)
    {
      AdaptiveCycle last;
      last.n_dofs = result.n_dofs;
      last.n_cells = result.n_cells;
      last.force = result.increments.back().force;
      last.wall_time = result.increments.back().wall_time - result.setup_time;
      for (const auto &r : result.increments)
        last.contact_iterations += r.contact_iterations;
      return last;
    }
  }  // namespace

  QuasiStaticRun::QuasiStaticRun(StudyModel &model, const Parts &parts)
    : model_(model)
    , parts_(parts)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
    , n_ranks_(Utilities::MPI::n_mpi_processes(parts.comm))
  {}

  RunResult QuasiStaticRun::run()
  {
    RunResult result;
    result.n_ranks = n_ranks_;
    const auto &L = parts_.scene.loading;
    const std::vector<double> targets = equal_steps(L.delta_max, L.n_increments);
    QuasiStaticStepper stepper = model_.quasi_static_stepper();
    // the adaptive cycles (none: the mesh built once) mark at δ_max, the curve's end
    AdaptiveCycles cycles(model_, {parts_.scene, parts_.bodies, parts_.dofs, parts_.comm},
                          L.delta_max, "F(delta_max)");
    model_.build_mesh();
    if (!cycles.refine(stepper, result))
      return result;
    // the elastoplastic patch test (scene.cc admits no adaptive cycles with it): the mesh is
    // the curve's, so the points' history is sized for it here
    if (parts_.scene.material.model == Material::Model::elastoplastic)
      model_.init_plasticity();
    model_.record_mesh(result);
    parts_.fields.create_directory();
    const unsigned int n_candidates = Utilities::MPI::sum(
      (unsigned int)std::count_if(parts_.contact.nodes().begin(), parts_.contact.nodes().end(),
                                  [](const ContactNode &c) { return c.owned && c.candidate; }),
      parts_.comm);  // collective: outside the rank-0 branch
    if (rank_ == 0)
      log::info("fe_stage: " + std::to_string(result.n_cells) + " cells, " +
                std::to_string(result.n_dofs) + " DoFs, " + std::to_string(n_candidates) +
                " contact candidate nodes, " + std::to_string(parts_.system.n_contact_cells()) +
                " contact cells (rank 0), " +
                (parts_.solver.direct() ? "direct (MUMPS)" : "CG+AMG") + " solver, setup " +
                log::format_duration(result.setup_time));

    if (parts_.fields.enabled())
      {
        parts_.state.set_zero();
        model_.evaluate_contact_at(0.0);
        parts_.fields.write(0, 0.0);
      }
    // One line per converged increment: what an Abaqus user reads in the .sta file. The ETA
    // prices the remaining push at the cost per metre of the increments after the first: the
    // first carries the AMG setup and the cold active set (3–6× a later increment's cost,
    // which made an ETA taken from it overshoot up to 6-fold; docs/benchmarks.md).
    double first_time = 0.0, first_delta = 0.0;
    auto log_increment = [&](const unsigned int inc, const IncrementRecord &r) {
      if (inc == 1)
        {
          first_time = r.wall_time;
          first_delta = r.delta;
        }
      if (rank_ != 0)
        return;
      std::string eta;
      if (inc == 1 && inc < L.n_increments)
        eta = "  ETA after the next increment";
      else if (inc < L.n_increments)
        {
          const double seconds_per_metre = (r.wall_time - first_time) / (r.delta - first_delta);
          eta = "  ETA " + log::format_duration(seconds_per_metre * (L.delta_max - r.delta));
        }
      char buf[320];
      std::snprintf(buf, sizeof(buf),
                    "fe_stage: increment %u/%u  delta %.4g um  F %.6g N  contact its %u  "
                    "linear its %u  active %u (slip %u)  %s%s",
                    inc, L.n_increments, r.delta * 1e6, r.force, r.contact_iterations,
                    r.linear_iterations, r.n_active, r.n_slip,
                    log::format_duration(r.wall_time).c_str(), eta.c_str());
      log::info(buf);
    };
    const auto record_increment = [&](const unsigned int inc, IncrementRecord &rec) {
      rec.wall_time = model_.elapsed();
      result.increments.push_back(rec);
      if (parts_.options.on_increment)
        parts_.options.on_increment(rec);
      if (parts_.fields.enabled())
        parts_.fields.write(inc, targets[inc - 1]);
      log_increment(inc, rec);
    };
    const bool complete = stepper.push_through(targets, result.message, record_increment);
    if (!complete)
      {
        result.wall_time = model_.elapsed();
        result.field_files = parts_.fields.files(false);
        if (!result.increments.empty() && !model_.elastoplastic())
          {
            result.yield_check = parts_.fields.check_yield(nullptr);
            parts_.fields.log_yield_check(result.yield_check);
          }
        return result;
      }
    result.complete = true;
    if (!result.adaptive_cycles.empty())
      cycles.close(result, curve_as_cycle(result));  // the curve's F(δ_max) closes the sequence
    result.sliding_rebuilds = model_.sliding_rebuilds();
    result.sliding_resolves = stepper.sliding_resolves();
    if (rank_ == 0 && stepper.finite_sliding())
      log::info("fe_stage: finite sliding: the mortar search was redone after every converged "
                "increment; " +
                std::to_string(model_.sliding_rebuilds()) +
                " times its partners needed a new sparsity pattern, " +
                std::to_string(stepper.sliding_resolves()) +
                " increments solved again with the new "
                "coupling");
    if (!model_.elastoplastic())  // (an elastoplastic body yields where it must)
      {
        result.yield_check = parts_.fields.check_yield(nullptr);
        parts_.fields.log_yield_check(result.yield_check);
      }
    result.wall_time = model_.elapsed();
    if (rank_ == 0)
      log::info("fe_stage: time in contact assembly " +
                log::format_duration(parts_.contact_solve.assembly_time()) + ", linear solves " +
                log::format_duration(parts_.contact_solve.solve_time()) + " (" +
                parts_.solver.summary() + "), contact evaluation " +
                log::format_duration(parts_.contact_solve.evaluation_time()));
    result.field_files = parts_.fields.files(true);
    return result;
  }
}  // namespace clearjoint::fe::detail
