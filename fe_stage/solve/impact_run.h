// The impact study's run (paper §3.2): the quasi-static reference curve that sets the contact
// period and Δt, the HHT-α time steps to the separation (HhtStepper), and what it records —
// each step, the peak, the separation, the summary and the yield check at the peak.
// solve/impact_run.cc says what each phase does.
#pragma once

#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
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
      const Bodies &bodies;
      const DofSpace &dofs;
      State &state;
      FieldOutput &fields;
      MPI_Comm comm;
    };

    ImpactRun(StudyModel &model, const Parts &parts);

    /// The whole study; a run that stops early has result.message set and complete false.
    RunResult run();

  private:
    /// The base mesh, the journal's mass and the integrator's α, β, γ (returned).
    HhtAlpha begin(RunResult &result);
    /// mesh.adaptive_cycles > 0: the base mesh refined where the impact is expected to peak
    /// (solve/adaptive_cycles.h, marked at the expected δ_max), the sequence's error estimate
    /// into the result; the model left on the final mesh, at rest. False: result.message says
    /// why.
    bool adapt_mesh(RunResult &result);
    /// The run's mesh into the result and its log line.
    void describe_mesh(RunResult &result) const;
    /// The static probe (a push to 2 % of loading.delta_max) and the penetration a linear
    /// contact of that stiffness reaches from ½ m_J v², δ = v √(m_J δ_probe / F_probe) [m].
    /// False: result.message says why.
    bool expected_penetration(QuasiStaticStepper &stepper, RunResult &result,
                              double &delta_estimate);
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
