// The rolling study's step on the journal's spin (solve/spin_stepper.cc), on a stand-in for the
// model: one displacement u that follows the journal's turn ψ (u = a ψ when converged) and a
// torque that drives the journal toward rolling, M = K (a ψ_roll − u). Its material iteration
// flickers by ±c around the converged u, as the contact's trailing-edge decisions do on the
// level-2 ring, so the bordered spin iteration cannot bring the balance below 1e-6 and stalls;
// its converged solves (the root finder's evaluations) are exact. The balance's root is known:
//   I γ̇/Δt = K a (γ̇_roll − γ̇) Δt   ⇒   γ̇ = K a Δt γ̇_roll / (I/Δt + K a Δt).
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/core/state.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/material_newton.h"
#include "fe_stage/solve/spin_stepper.h"
#include "fe_stage/solve/stepper_interfaces.h"

#include <deal.II/base/index_set.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace clearjoint;
using namespace clearjoint::fe;
using namespace clearjoint::fe::detail;

namespace
{
  struct Visit
  {
    double u = 0.0, psi = 0.0;  // [m], [rad]
  };

  class FlickeringSpin final : public SpinProblem
  {
  public:
    static constexpr double a = 1e-3;     // [m/rad] u per turn of the journal
    static constexpr double K = 6e3;      // [N m / m] the torque's stiffness in u
    static constexpr double force = 1e3;  // [N] the contact force each solve reports
    // [m] the flicker: K c = 6e-4 N m, 1e-4 of the balance's scale μ F R_J ≈ 6 N m — what the
    // level-2 ring's step 12 showed (|g| 3.5e-5..2.3e-4 over its last five iterations)
    static constexpr double c = 1e-7;

    FlickeringSpin(State &state, const JournalFrame &frame, const double psi_roll)
      : state_(state)
      , frame_(frame)
      , psi_roll_(psi_roll)
    {}

    Snapshot save_state() const override
    {
      Snapshot s;
      s.u = state_.u_owned();
      return s;
    }
    void restore_state(const Snapshot &s) override { state_.set(s.u); }
    bool journal_turns_deformable() const override { return false; }
    void pair_turned_journal(const TrilinosWrappers::MPI::Vector &) override {}

    RollingSolve solve_rolling_state(double) override
    {
      solve_starts.push_back({u(), frame_.delta_psi});
      set_u(a * frame_.delta_psi);
      RollingSolve r;
      r.torque_journal = journal_torque();
      r.newton_iterations = 1;
      r.record.force = force;
      return r;
    }

    MaterialIteration material_iteration(double, bool, TurnSensitivity *sensitivity) override
    {
      // the flicker alternates in sign and shrinks by 1 % an iteration, so the correction
      // never grows (the iteration stalls, it does not diverge)
      const double flicker = (iterates.size() % 2 == 0 ? c : -c) * std::pow(0.99, iterates.size());
      MaterialIteration it;
      const double target = a * frame_.delta_psi + flicker;
      it.correction = std::abs(target - u());
      it.record.force = force;
      set_u(target);
      if (sensitivity)
        {
          sensitivity->du.reinit(state_.u_owned());
          sensitivity->du = a * sensitivity->d_psi;
          sensitivity->d_torque = -K * a * sensitivity->d_psi;
        }
      iterates.push_back({u(), frame_.delta_psi});
      return it;
    }

    double journal_torque() const override { return K * (a * psi_roll_ - u()); }
    double material_tolerance() const override { return 1e-12; }

    std::vector<Visit> iterates, solve_starts;

  private:
    double u() const { return state_.u_owned()[0]; }
    void set_u(const double v)
    {
      state_.u_owned() = v;
      state_.publish();
    }

    State &state_;
    const JournalFrame &frame_;
    const double psi_roll_;
  };
}  // namespace

// A bordered iteration that stalls near the root hands the step to the root finder where it
// stopped — its spin, its state — not back at the step's start (the level-2 ring's step 12:
// 139 contact iterations that way, 51 from the stall). The step must converge to the balance's
// root, the root finder's first evaluation must start from the last iterate, and the step
// counts as one the root finder took.
TEST(SpinStepper, StalledBorderedIterationHandsItsIterateToTheRootFinder)
{
  FeScene scene;
  scene.study = Study::rolling;
  scene.contact.mu = 0.3;
  ASSERT_EQ(scene.rolling.spin_solver, Rolling::SpinSolver::bordered);
  rolling::Motion motion;
  motion.omega_B = 12.56;
  motion.ramp_time = 0.25;
  motion.delta_max = 1e-3;
  motion.c_r = scene.geometry.c_r;
  motion.R_B = scene.geometry.R_B;
  motion.R_J = scene.geometry.R_J();
  const double t_end = 0.01, inertia = 1.8e-6;  // one step of 0.01 s; the journal's I [kg m²]
  const double dt = t_end, roll = motion.rolling_rate(dt);
  const double dphi = motion.phi(dt) - motion.phi(0.0);

  const dealii::IndexSet one = dealii::complete_index_set(1);
  State state;
  state.reinit(one, one, MPI_COMM_SELF);
  JournalFrame frame;
  frame.turning = true;
  FlickeringSpin problem(state, frame, roll * dt - dphi);
  SpinStepper stepper(problem, scene, state, frame, MPI_COMM_SELF, motion, t_end, 1, 0, inertia);

  SpinStepper::Step step;
  std::string message;
  ASSERT_TRUE(stepper.solve(step, message)) << message;
  ASSERT_GE(problem.iterates.size(), 5u);  // the stall is judged over four iterations
  ASSERT_FALSE(problem.solve_starts.empty());
  EXPECT_FALSE(step.coupled);
  EXPECT_EQ(step.cuts, 0u);
  EXPECT_EQ(stepper.n_coupled_fallbacks(), 1u);

  // the root finder's first evaluation: at the last iterate's turn, from its u (the step's
  // start was u = 0 at the spin 0)
  const Visit &last = problem.iterates.back(), &first = problem.solve_starts.front();
  EXPECT_EQ(first.psi, last.psi);
  EXPECT_EQ(first.u, last.u);
  EXPECT_NE(first.u, 0.0);
  // from there the linear balance's root is one secant away: two evaluations, three at most
  // (the cold root finder from the step's start takes at least as many, and each of them
  // would be a whole material solve from the elastic predictor)
  EXPECT_LE(problem.solve_starts.size(), 3u);

  const double Ka = FlickeringSpin::K * FlickeringSpin::a;
  const double exact = Ka * dt * roll / (inertia / dt + Ka * dt);
  // the root finder's tolerance |g| ≤ 1e-6 of the scale μ F R_J, in γ̇ through the balance's
  // slope (I/Δt + K a Δt)/scale
  const double scale = scene.contact.mu * FlickeringSpin::force * motion.R_J;
  const double rate_tolerance = 1e-6 * scale / (inertia / dt + Ka * dt);
  EXPECT_NEAR(step.rate, exact, rate_tolerance);
  std::printf("stalled after %zu bordered iterations; the root finder took %zu evaluations; "
              "γ̇ %.9f rad/s (root %.9f, tolerance %.1e)\n",
              problem.iterates.size(), problem.solve_starts.size(), step.rate, exact,
              rate_tolerance);
}
