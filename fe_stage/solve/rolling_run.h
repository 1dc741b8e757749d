// The rolling study's run (paper §3.4, docs/fe.md "Rolling study"): the turning frame at rest,
// time steps over the push ramp — each the bearing turned to φ = ω_B t, the journal pushed to
// δ(t) and its spin γ̇ from its torque balance (SpinStepper) — and what each converged step
// records (forces, torques, energies, the paper's Eqs. 4–8), then the end state (strain
// profile, slip stages). solve/rolling_run.cc says how.
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/results/field_output.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/rolling_kinematics.h"
#include "fe_stage/solve/spin_stepper.h"
#include "fe_stage/solve/study_model.h"
#include "fe_stage/study_plan.h"

#include <vector>

namespace clearjoint::fe::detail
{
  class RollingRun
  {
  public:
    /// The parts the run reads, and the two it moves: the journal frame (set at rest, its
    /// turn committed after each step) and the contact nodes (their converged reference).
    struct Parts
    {
      const FeScene &scene;
      const StudyPlan &plan;
      const RunOptions &options;
      const Bodies &bodies;
      const DofSpace &dofs;
      ContactProblem &contact;
      const State &state;
      JournalFrame &frame;
      FieldOutput &fields;
      MPI_Comm comm;
    };

    RollingRun(StudyModel &model, const Parts &parts);

    /// The whole study; a run that stops early has result.message set and complete false.
    RunResult run();

  private:
    /// The turning frame at rest, the mesh, DoFs and material history; the run's sizes.
    void begin(RunResult &result);
    /// The end state (the strains across the contact zone), the slip stages, the solver's
    /// summary; the result closed.
    void finish(RunResult &result, const SpinStepper &stepper, const rolling::Motion &motion);

    StudyModel &model_;
    Parts parts_;
    const unsigned int rank_, n_ranks_;
  };
}  // namespace clearjoint::fe::detail
