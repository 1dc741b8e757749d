// The adaptive cycles before a study's run (AdaptiveCycles, solve/adaptive_cycles.h): a push
// to δ_mark on each mesh, F(δ_mark) kept, Kelly's indicator, refinement; a target error may
// stop them early; the final mesh's F(δ_mark) closes the sequence and its estimate.
#include "fe_stage/solve/adaptive_cycles.h"

#include "fe_stage/solve/adaptive_estimate.h"

#include "common/error.h"
#include "common/log.h"

#include <deal.II/base/mpi.h>

#include <cstdio>

namespace clearjoint::fe::detail
{
  AdaptiveCycles::AdaptiveCycles(StudyModel &model, const Parts &parts, const double delta_mark,
                                 const std::string &quantity)
    : model_(model)
    , parts_(parts)
    , delta_mark_(delta_mark)
    , quantity_(quantity)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
  {}

  std::vector<double> equal_steps(const double delta, const unsigned int n)
  {
    std::vector<double> t;
    for (unsigned int inc = 1; inc <= n; ++inc)
      t.push_back(inc == n ? delta : inc * (delta / n));
    return t;
  }

  std::vector<double> AdaptiveCycles::marking_targets() const
  {
    return equal_steps(delta_mark_, parts_.scene.mesh.adaptive_increments);
  }

  bool AdaptiveCycles::push_to_mark(QuasiStaticStepper &stepper, std::string &message,
                                    AdaptiveCycle &mesh) const
  {
    const double t0 = model_.elapsed();
    mesh = AdaptiveCycle{};
    mesh.n_dofs = parts_.dofs.handler().n_dofs();
    mesh.n_cells = parts_.bodies.triangulation().n_global_active_cells();
    if (!stepper.push_through(marking_targets(), message, [&](unsigned int, IncrementRecord &r) {
          mesh.force = r.force;
          mesh.contact_iterations += r.contact_iterations;
        }))
      return false;
    mesh.wall_time = model_.elapsed() - t0;
    return true;
  }

  bool AdaptiveCycles::refine(QuasiStaticStepper &stepper, RunResult &result)
  {
    const unsigned int n_cycles = parts_.scene.mesh.adaptive_cycles;
    const double target = parts_.scene.mesh.adaptive_target_error;
    for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
      {
        AdaptiveCycle c;
        if (!push_to_mark(stepper, result.message, c))
          {
            result.message = "adaptive cycle " + std::to_string(cycle + 1) + ": " + result.message;
            result.wall_time = model_.elapsed();
            return false;
          }
        result.adaptive_cycles.push_back(c);
        if (rank_ == 0)
          {
            char buf[240];
            std::snprintf(buf, sizeof(buf),
                          "fe_stage: adaptive cycle %u/%u  %lu cells  %lu DoFs  %s %.8g N  "
                          "contact its %u  %s",
                          cycle + 1, n_cycles, c.n_cells, c.n_dofs, quantity_.c_str(), c.force,
                          c.contact_iterations, log::format_duration(c.wall_time).c_str());
            log::info(buf);
          }
        if (target > 0.0)
          {
            const AdaptiveEstimate e =
              estimate_adaptive_error(result.adaptive_cycles, parts_.dofs.fe().degree);
            if (rank_ == 0 && e.error >= 0.0)
              log::info("fe_stage: estimated error of " + quantity_ + " " +
                        format_value(100.0 * e.error) + " %, target " +
                        format_value(100.0 * target) + " %; method: " + e.method);
            if (adaptive_target_met(e, target))
              {
                final_mesh_marked_ = true;
                break;
              }
          }
        model_.refine_mesh();
      }
    model_.start_from_rest();
    return true;
  }

  void AdaptiveCycles::close(RunResult &result, const AdaptiveCycle &final_mesh) const
  {
    const double target = parts_.scene.mesh.adaptive_target_error;
    if (final_mesh_marked_)
      result.adaptive_cycles.back() = final_mesh;
    else
      result.adaptive_cycles.push_back(final_mesh);
    const AdaptiveEstimate e =
      estimate_adaptive_error(result.adaptive_cycles, parts_.dofs.fe().degree);
    result.adaptive_error = e.error;
    result.adaptive_error_method = e.method;
    result.adaptive_order = e.order;
    result.adaptive_extrapolated_force = e.extrapolated_force;
    result.adaptive_target_reached = adaptive_target_met(e, target);
    if (rank_ == 0 && result.adaptive_error >= 0.0)
      log::info("fe_stage: estimated error of " + quantity_ + " on the final mesh " +
                format_value(100.0 * result.adaptive_error) +
                " %; method: " + result.adaptive_error_method);
    if (rank_ == 0 && target > 0.0 && !result.adaptive_target_reached)
      log::warning("fe_stage: the target error " + format_value(100.0 * target) +
                   " % (mesh.adaptive_target_error) was not reached in " +
                   std::to_string(parts_.scene.mesh.adaptive_cycles) +
                   " cycles (mesh.adaptive_cycles, the most allowed): the run is on the last "
                   "mesh, with the estimate above");
  }
}  // namespace clearjoint::fe::detail
