// The quasi-static studies' run (radial, misalignment, Hertz, patch): the adaptive cycles
// (mesh.adaptive_cycles: a push on each mesh, Kelly's indicator, refinement — or a target
// error), then the curve from 0 to δ_max in increments on the last mesh (QuasiStaticStepper),
// one log line per increment (as an Abaqus .sta file) with an ETA, the adaptive sequence's
// error estimate and the yield check of the last converged state. solve/quasi_static_run.cc
// says how.
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/results/field_output.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/contact_solve.h"
#include "fe_stage/solve/linear_solver.h"
#include "fe_stage/solve/quasi_static_stepper.h"
#include "fe_stage/solve/study_model.h"

namespace clearjoint::fe::detail
{
  class QuasiStaticRun
  {
  public:
    /// The parts the run reads (for its records and log lines), u (set to zero for the first
    /// fields) and the fields.
    struct Parts
    {
      const FeScene &scene;
      const RunOptions &options;
      const Bodies &bodies;
      const DofSpace &dofs;
      const ContactProblem &contact;
      const Assembler &system;
      const SystemSolver &solver;
      const ContactSolve &contact_solve;
      State &state;
      FieldOutput &fields;
      MPI_Comm comm;
    };

    QuasiStaticRun(StudyModel &model, const Parts &parts);

    /// The whole study; a run that stops early has result.message set and complete false.
    RunResult run();

  private:
    StudyModel &model_;
    Parts parts_;
    const unsigned int rank_, n_ranks_;
  };
}  // namespace clearjoint::fe::detail
