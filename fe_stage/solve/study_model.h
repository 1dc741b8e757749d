// The model as a study's run sees it (issue 29: a study is its own object, not a member of the
// model). A run owns its phases and what it records; it is given the parts it reads — the
// scene, its plan, the run's options, the DoF space, the state u, the fields — and asks the
// model, through StudyModel, for what only the whole model can do: build the mesh and all that
// depends on it, free a deformable journal, make a stepper over the model's parts, place the
// contact at a push, commit the material. Model implements it; run() chooses the
// study's run in one place.
#pragma once

#include "fe_stage/core/restart_stream.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/material/material_state.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/hht_stepper.h"
#include "fe_stage/solve/quasi_static_stepper.h"
#include "fe_stage/solve/rolling_kinematics.h"
#include "fe_stage/solve/spin_stepper.h"

#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  class StudyModel
  {
  public:
    /// The bodies meshed, and everything that depends on the mesh: DoFs, constraints, contact
    /// nodes and their partners, matrices.
    virtual void build_mesh() = 0;
    /// One adaptive cycle: Kelly's indicator on the converged solution marks the fraction
    /// mesh.adaptive_fraction of the cells with the largest indicators, p4est refines them,
    /// and everything that depends on the mesh is built again.
    virtual void refine_mesh() = 0;
    /// A deformable journal pushed so far at its end faces or axis becomes free (the impact
    /// study's time steps): the constraints and matrices are rebuilt without its loaded set.
    virtual void free_journal() = 0;
    /// The run's mesh sizes and set-up time into `result`.
    virtual void record_mesh(RunResult &result) const = 0;
    /// The quasi-static push over the model's parts.
    virtual QuasiStaticStepper quasi_static_stepper() = 0;
    /// HHT-α time steps over the model's parts (HhtStepper's constructor says the arguments).
    virtual HhtStepper hht_stepper(const HhtAlpha &hht, double dt_nominal, unsigned int max_cuts,
                                   double m_J, double velocity, bool deformable_journal) = 0;
    /// The spin stepper of the rolling study over the model's parts (SpinStepper's
    /// constructor says the arguments).
    virtual SpinStepper spin_stepper(const rolling::Motion &motion, double t_end,
                                     unsigned int n_steps, unsigned int max_cuts,
                                     double inertia) = 0;
    /// Zero displacement, no contact, every node sticking with no slip history.
    virtual void start_from_rest() = 0;
    /// The obstacle at the push δ and the contact nodes' gaps and forces at the current u.
    virtual void evaluate_contact_at(double delta) = 0;
    /// The bodies elastoplastic from here: the points' history sized for the mesh, the
    /// operator the tangent.
    virtual void init_plasticity() = 0;
    /// The bodies are elastoplastic (init_plasticity was called).
    virtual bool elastoplastic() const = 0;
    /// The converged state's trial states made the points' history, with the step's energies.
    virtual PlasticEnergies commit_plasticity() = 0;
    /// A body's strains at the axial mid-plane within ±half_angle [rad] of the contact point,
    /// which sits at the body's frame angle −turn (collective; every rank gets the profile).
    virtual std::vector<StrainProfilePoint> strain_profile(unsigned int body, double turn,
                                                           double half_angle) const = 0;
    /// The rolling study's journal is deformable and turns over the bore.
    virtual bool journal_turns_deformable() const = 0;
    /// Finite sliding's (or the turning journal's) new sparsity patterns so far.
    virtual unsigned int sliding_rebuilds() const = 0;
    /// [s] since the model was made (the runs' set-up and wall times).
    virtual double elapsed() const = 0;
    /// The converged state into a restart file and back (solve/rolling_restart.h), this
    /// rank's part: u, the points' history, the contact nodes' states and slip references.
    /// Read back on the same mesh and partition, after build_mesh and init_plasticity.
    virtual void write_restart(RestartWriter &out) const = 0;
    virtual void read_restart(RestartReader &in) = 0;
    /// What the linear solves cost (SystemSolver::summary), for the run's summary.
    virtual std::string solver_summary() const = 0;

  protected:
    ~StudyModel() = default;
  };
}  // namespace clearjoint::fe::detail
