// The adaptive cycles before a study's run (mesh.adaptive_cycles; docs/fe.md "Adaptive
// refinement"): on each mesh a quasi-static push to a marking penetration δ_mark, its F(δ_mark)
// kept, then Kelly's indicator on that state marks the cells to refine — or, with
// mesh.adaptive_target_error, the cycles stop at the first mesh whose extrapolated estimate meets
// it. The quasi-static studies mark at δ_max (the end of their curve), the impact at the
// penetration it is expected to reach (its peak). The sequence F_k(N_k), closed by the final
// mesh's F(δ_mark), gives the run's own error estimate (solve/adaptive_estimate.h).
#pragma once

#include "fe_stage/core/dof_space.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/quasi_static_stepper.h"
#include "fe_stage/solve/study_model.h"

#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  /// The push from 0 to δ in n equal increments (the last exactly δ) [m].
  std::vector<double> equal_steps(double delta, unsigned int n);

  class AdaptiveCycles
  {
  public:
    /// The parts the cycles read: the mesh settings, the mesh and DoF counts.
    struct Parts
    {
      const FeScene &scene;
      const Bodies &bodies;
      const DofSpace &dofs;
      MPI_Comm comm;
    };

    /// delta_mark [m]: the push on each marking mesh; `quantity`: what F(δ_mark) is, for the
    /// log lines (e.g. "F(delta_max)").
    AdaptiveCycles(StudyModel &model, const Parts &parts, double delta_mark,
                   const std::string &quantity);

    /// The push to δ_mark (in mesh.adaptive_increments equal steps) on the current mesh: its
    /// size, F(δ_mark), contact iterations and wall time into `mesh`. False (`message` says
    /// why) when it failed.
    bool push_to_mark(QuasiStaticStepper &stepper, std::string &message, AdaptiveCycle &mesh) const;

    /// From the mesh the model has now (built): the cycles, the sequence F_k(N_k) into
    /// result.adaptive_cycles; the model is left on the final mesh, at rest. False
    /// (result.message set) when a marking push failed.
    bool refine(QuasiStaticStepper &stepper, RunResult &result);

    /// A target error stopped the cycles on a mesh whose marking push is in the sequence: that
    /// is the final mesh, its F(δ_mark) known already.
    bool final_mesh_marked() const { return final_mesh_marked_; }

    /// The final mesh's F(δ_mark) (`final_mesh`: in place of its marking push when
    /// final_mesh_marked()) closes the sequence, and its error estimate goes into the result.
    void close(RunResult &result, const AdaptiveCycle &final_mesh) const;

  private:
    /// The push δ = 0 → δ_mark in mesh.adaptive_increments equal steps (the last exactly δ_mark):
    /// only the state at δ_mark is used, and it hardly depends on the path (μ = 0.1: 1 to 20
    /// increments within 5e-6 of F, docs/fe.md), so the sequence stays comparable with friction.
    std::vector<double> marking_targets() const;

    StudyModel &model_;
    Parts parts_;
    const double delta_mark_;
    const std::string quantity_;
    const unsigned int rank_;
    bool final_mesh_marked_ = false;
  };
}  // namespace clearjoint::fe::detail
