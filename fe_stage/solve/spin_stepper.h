// The rolling study's time stepper (paper §3.4): the bearing turned to φ = ω_B t and the
// journal pushed to δ(t) (rolling::Motion), and the journal's spin rate γ̇ found from its
// torque balance  I (γ̇ − γ̇_n)/Δt = M(γ̇)  (backward Euler; M the contact's torque on the
// journal, which falls as γ̇ rises: one root). rolling.spin_solver chooses how:
// - bordered: γ̇ an unknown of each material Newton iteration beside the displacements (its
//   torque-balance row, and the displacements' dependence on the journal's turn from one more
//   solve of the iteration's contact system); one nonlinear solve a step, from the first step;
// - coupled (default): γ̇ and the bodies' state in one iteration — each material Newton
//   iteration solves the bodies at the current γ̇, then γ̇ takes a Newton step on the balance
//   with the slope dM/dγ̇ of the last step (secant-corrected); one nonlinear solve a step. Until
//   a slope is known (the first step), and for a step where it fails, the root finder below;
// - nested: a root finder on γ̇ (solve/root_finder.h) around whole material solves, each
//   evaluation of M a converged state of the elastoplastic bodies
//   (SpinProblem::solve_rolling_state). It owns the
// spin's state (t, γ, γ̇), what carries from step to step — the balance's scale and slope
// dM/dγ̇, the state before the last step (the predictor in time), Δt (solve/step_controller.h)
// — and the journal's search counters; the study's run (RollingRun, solve/rolling_run.h) records each step
// and commits the material before accept().
#pragma once

#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/core/restart_stream.h"
#include "fe_stage/core/state.h"
#include "fe_stage/core/step_failure.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/rolling_kinematics.h"
#include "fe_stage/solve/step_controller.h"
#include "fe_stage/solve/stepper_interfaces.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include <optional>
#include <string>

namespace clearjoint::fe::detail
{
  class SpinStepper
  {
  public:
    /// A step the stepper solved: its Δt [s], the journal's new spin rate [rad/s], the model's
    /// state there, the torque evaluations and the cuts it took.
    struct Step
    {
      double dt = 0.0;
      double rate = 0.0;
      RollingSolve state;
      unsigned int spin_evaluations = 0;
      unsigned int cuts = 0;
      /// what the step cost, failed attempts included: material Newton iterations, active-set
      /// contact iterations, linear solver iterations
      unsigned int newton_iterations = 0, contact_iterations = 0, linear_iterations = 0;
      unsigned int line_search_steps = 0;  // trial points the material line search rejected
      bool coupled = false;  // the coupled iteration converged it (else the root finder)
    };

    /// Works on the model's state u and journal frame, which it moves; the rest through
    /// `problem`.
    SpinStepper(SpinProblem &problem, const FeScene &scene, State &state, JournalFrame &frame,
                MPI_Comm comm, const rolling::Motion &motion, double t_end, unsigned int n_steps,
                unsigned int max_cuts, double inertia);

    /// Solves the next step from time() (Δt shortened to reach t_end): the model then holds its
    /// converged state. False with `message` when it failed after its cuts (the model holds
    /// the last converged state).
    bool solve(Step &step, std::string &message);
    /// The step was recorded and committed: time, γ, γ̇ move to its end.
    void accept(const Step &step);

    double time() const { return t_; }
    double gamma() const { return gamma_; }
    double gamma_rate() const { return gamma_rate_; }
    unsigned int n_searches() const { return n_searches_; }
    double search_time() const { return search_time_; }  // [s]

    /// Steps whose coupled iteration failed and that the root finder solved instead.
    unsigned int n_coupled_fallbacks() const { return n_coupled_fallbacks_; }

    /// What carries to the next step, after accept(), into a restart file and back (the
    /// model's state is the model's to write): t, γ, γ̇, the step size, the balance's scale
    /// and slope, the state before the last step, the counters.
    void write_restart(RestartWriter &out) const;
    void read_restart(RestartReader &in);

  private:
    /// What an attempt at Δt solves for: the push δ at its end [m], the bearing's turn over
    /// it [rad], the torque balance's scale [N m] (0: not known before the first evaluation).
    struct Attempt
    {
      double dt = 0.0, delta = 0.0, dphi = 0.0, torque_scale = 0.0;
    };
    Attempt begin_attempt(double dt);
    double torque_scale(double force, double torque, double t1, double dt) const;
    void start_predicted_in_time(double dt);
    void pair_turned_journal();
    /// Where a coupled iteration that stalled on the torque balance left the step: the spin
    /// [rad/s] of its last iterate (the model holds that iterate's state), the balance's slope
    /// there [s/rad] and its scale [N m]. The root finder goes on from it.
    struct Stall
    {
      double rate = 0.0, slope = 0.0, scale = 0.0;
    };
    bool solve_coupled(const Attempt &a, bool bordered, Step &step, std::optional<Stall> &stall);
    void solve_nested(Attempt &attempt, Step &step, bool predict_in_time, bool &predicted_in_time,
                      const Stall *from = nullptr);
    bool solve_nested_from(const Stall &stall, Attempt &attempt, Step &step);
    bool retry(const StepFailure &f, bool predicted_in_time, bool &predict_in_time, double &dt,
               std::string &message);

    SpinProblem &problem_;
    const FeScene &scene_;
    State &state_;
    JournalFrame &frame_;
    const unsigned int rank_;
    const rolling::Motion motion_;
    const double t_end_, inertia_;
    StepController control_;
    double t_ = 0.0, gamma_ = 0.0, gamma_rate_ = 0.0;
    // the torque balance's scale and slope dM/dγ̇ from the last converged step (0: none yet;
    // M falls as γ̇ rises, so a known slope is negative)
    double last_force_ = 0.0, last_torque_ = 0.0, torque_rate_slope_ = 0.0;
    // the state before the last converged step, for the predictor in time
    TrilinosWrappers::MPI::Vector u_previous_step_;
    double dt_previous_ = 0.0;
    bool have_previous_ = false;
    Snapshot saved_;            // the converged state the step in progress starts from
    double search_time_ = 0.0;  // [s] the deformable journal's searches and rebuilds
    unsigned int n_searches_ = 0;
    unsigned int n_coupled_fallbacks_ = 0;
  };
}  // namespace clearjoint::fe::detail
