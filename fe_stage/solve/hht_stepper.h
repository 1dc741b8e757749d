// The impact study's time stepper: HHT-α (solve/hht.h) on the meshed bodies, and the rigid
// journal's one unknown δ found by the root finder (solve/root_finder.h), with Δt from the step
// controller (solve/step_controller.h). It owns the dynamic state — u, v, a and the contact
// forces λ of the meshed bodies, the journal's δ, δ̇, δ̈ and force F, the energy ledger — and
// the operator c_m M + (1+α)K of the current Δt; the study's run (ImpactRun, solve/impact_run.h) starts
// it, steps it and records what it reports.
//
// One step n → n+1: Newmark's predictor û and the known load b = c_m M û + α(K u_n − λ_n);
// then a contact solve of the bearing for the journal's position δ (rigid journal: g(δ) =
// m_J c_m (δ − δ̂) + (1+α)F(δ) − αF_n = 0; a deformable journal is part of the FE system: one
// solve); the Newmark updates, the contact forces, the energies. A step that fails is restored
// and cut.
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/step_controller.h"
#include "fe_stage/solve/stepper_interfaces.h"

#include <deal.II/lac/trilinos_vector.h>

#include <string>

namespace clearjoint::fe::detail
{
  class HhtStepper
  {
  public:
    /// The model's parts the stepper works on: it assembles the step's known load into the
    /// assembler, sets u before each contact solve and reads the contact nodes' forces.
    struct Parts
    {
      const FeScene &scene;
      const Bodies &bodies;
      const DofSpace &dofs;
      Assembler &system;
      State &state;
      ContactProblem &contact;
      MPI_Comm comm;
    };

    /// At rest at first touch, the journal moving toward the bearing at `velocity` [m/s]
    /// (rigid: mass m_J [kg], full body; deformable: its FE DoFs, a rigid translation).
    /// Assembles the operator for dt_nominal [s].
    HhtStepper(DynamicProblem &problem, const Parts &parts, const HhtAlpha &hht, double dt_nominal,
               unsigned int max_cuts, double m_J, double velocity, bool deformable_journal);

    /// One converged step from time() to time() + Δt — Δt shortened to reach end_time
    /// exactly when it is > 0 — filling rec's time, Δt, δ, δ̇, F, support force, energies,
    /// iterations, cuts and n_active. False with `message` when the step failed after its cuts
    /// (the state is then the last converged one).
    bool step(double end_time, DynamicStepRecord &rec, std::string &message);

    double time() const { return t_; }
    /// The Δt the next step starts with [s].
    double next_dt() const { return dt_; }
    /// [kg] the journal's mass, full body (deformable: from the FE mass matrix).
    double journal_mass() const { return journal_mass_; }
    double delta_rate() const { return d_rate_; }
    const TrilinosWrappers::MPI::Vector &displacement() const { return u_; }
    double numerical_dissipation() const { return ledger_.dissipation; }
    double work_contact() const { return work_contact_; }

  private:
    /// Solves the step at Δt from the converged state (throws StepFailure): the new δ.
    double solve_step(double dt, DynamicStepRecord &rec, IncrementRecord &inc);
    /// The converged step: Newmark updates, contact forces, energies, state advanced.
    void advance(double dt, double d_new, const IncrementRecord &inc, DynamicStepRecord &rec);
    /// The operator c_m M + (1+α)K for Δt (assembled again only when Δt changed).
    void operator_for(double dt);
    /// ½ sym xᵀ A x over all DoFs or the journal's (mask).
    double energy(const TrilinosWrappers::SparseMatrix &A, const TrilinosWrappers::MPI::Vector &x,
                  bool journal_only);
    /// The deformable journal's centre-of-mass displacement toward the bearing.
    double centre_of_mass_y(const TrilinosWrappers::MPI::Vector &x);

    DynamicProblem &problem_;
    const Parts model_;  // the model's parts it works on
    const unsigned int rank_;
    const HhtAlpha &hht_;
    StepController control_;
    const bool deformable_;
    const double m_J_;     // [kg] the rigid journal's mass (full body)
    double journal_mass_;  // [kg] full body
    double dt_, dt_operator_;
    double t_ = 0.0;
    TrilinosWrappers::MPI::Vector u_, v_, a_, lambda_, u_new_, v_new_, a_new_, lambda_new_, tmp_;
    double d_ = 0.0, d_rate_ = 0.0, d_acc_ = 0.0, F_ = 0.0;  // the journal
    // the deformable journal: its DoFs (mask), its y-DoFs, its modelled mass
    TrilinosWrappers::MPI::Vector journal_mask_, journal_y_;
    double journal_mass_modelled_ = 0.0;
    EnergyLedger ledger_;
    double work_contact_ = 0.0;
  };
}  // namespace clearjoint::fe::detail
