// The impact study's run (paper §3.2): the quasi-static reference curve that sets the contact
// period and Δt, the HHT-α time steps to the separation (HhtStepper), and what it records —
// each step, the peak, the separation, the summary and the yield check at the peak.
// solve/impact_run.cc says what each phase does.
#pragma once

#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/results/field_output.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/hht_stepper.h"
#include "fe_stage/solve/study_model.h"
#include "fe_stage/study_plan.h"

#include <deal.II/lac/trilinos_vector.h>

namespace clearjoint::fe::detail
{
  class ImpactRun
  {
  public:
    /// The parts the run reads: the scene and its plan, the run's options (the per-step
    /// callbacks), the DoF space, u (set to the peak's for the yield check) and the fields.
    struct Parts
    {
      const FeScene &scene;
      const StudyPlan &plan;
      const RunOptions &options;
      const DofSpace &dofs;
      State &state;
      FieldOutput &fields;
      MPI_Comm comm;
    };

    ImpactRun(StudyModel &model, const Parts &parts);

    /// The whole study; a run that stops early has result.message set and complete false.
    RunResult run();

  private:
    /// The mesh, the journal's mass and the integrator's α, β, γ (returned).
    HhtAlpha begin(RunResult &result);
    /// The static probe and the quasi-static reference curve, with the contact period and Δt
    /// they set. False: result.message says why, result.wall_time is set.
    bool compute_reference(RunResult &result);
    /// The time steps to the separation or the end time, keeping the displacement at the peak
    /// force. False: result.message says why.
    bool march(RunResult &result, HhtStepper &stepper, TrilinosWrappers::MPI::Vector &u_peak,
               bool &have_peak);
    /// The summary, and the yield check at the peak (u_peak, when there was one).
    void finish(RunResult &result, const HhtStepper &stepper,
                const TrilinosWrappers::MPI::Vector *u_peak);
    /// [s] impact.end_time, or 4 T_c (twice a linear contact's duration).
    double end_time(double contact_period) const;

    StudyModel &model_;
    Parts parts_;
    const unsigned int rank_, n_ranks_;
  };
}  // namespace clearjoint::fe::detail
