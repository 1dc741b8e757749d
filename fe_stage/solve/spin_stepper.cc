#include "fe_stage/solve/spin_stepper.h"

#include "fe_stage/core/restart_values.h"
#include "fe_stage/core/scoped_timer.h"
#include "fe_stage/core/step_failure.h"
#include "fe_stage/solve/root_finder.h"
#include "fe_stage/solve/spin_balance_iteration.h"

#include "common/error.h"
#include "common/log.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace clearjoint::fe::detail
{
  SpinStepper::SpinStepper(SpinProblem &problem, const FeScene &scene, State &state,
                           JournalFrame &frame, MPI_Comm comm, const rolling::Motion &motion,
                           const double t_end, const unsigned int n_steps,
                           const unsigned int max_cuts, const double inertia)
    : problem_(problem)
    , scene_(scene)
    , state_(state)
    , frame_(frame)
    , rank_(Utilities::MPI::this_mpi_process(comm))
    , motion_(motion)
    , t_end_(t_end)
    , inertia_(inertia)
    // the step size carries over: a step that needed cuts starts the next one at its own
    // size, which doubles (up to the nominal) after two steps without a cut
    , control_(t_end / n_steps, max_cuts, 2)
  {
    u_previous_step_.reinit(state.u_owned());  // zero, on the owned DoFs
  }

  bool SpinStepper::solve(Step &step, std::string &message)
  {
    step = Step{};
    step.dt = control_.begin_step(t_end_ - t_);
    step.rate = gamma_rate_;
    saved_ = problem_.save_state();
    bool predict_in_time = true;
    for (;;)
      {
        Attempt attempt = begin_attempt(step.dt);
        bool predicted_in_time = false;
        try
          {
            // rolling.spin_solver coupled, once the last step gave the balance's slope (it
            // is negative once known): one iteration for γ̇ and the state. Failed from the
            // state predicted in time: the attempt is tried again from the last state (as
            // the root finder's); failed from there: the root finder, from the same start
            // at the same Δt. Stalled on the torque balance: first the root finder from the
            // stall (solve_nested_from), then as any failure
            // (bordered: from the first step on, its slope its own in every iteration)
            const bool bordered = scene_.rolling.spin_solver == Rolling::SpinSolver::bordered;
            if (bordered || (scene_.rolling.spin_solver == Rolling::SpinSolver::coupled &&
                             torque_rate_slope_ < 0.0 && attempt.torque_scale > 0.0))
              {
                if (have_previous_ && predict_in_time)
                  {
                    predicted_in_time = true;
                    start_predicted_in_time(step.dt);
                  }
                std::optional<Stall> stall;
                if (solve_coupled(attempt, bordered, step, stall))
                  break;
                if (stall && solve_nested_from(*stall, attempt, step))
                  {
                    ++n_coupled_fallbacks_;
                    break;
                  }
                if (predicted_in_time)
                  throw StepFailure{"the coupled iteration failed"};
                problem_.restore_state(saved_);
                ++n_coupled_fallbacks_;
              }
            solve_nested(attempt, step, predict_in_time, predicted_in_time);
            break;
          }
        catch (const StepFailure &f)
          {
            problem_.restore_state(saved_);
            if (!retry(f, predicted_in_time, predict_in_time, step.dt, message))
              return false;
          }
      }
    step.cuts = control_.cuts();
    return true;
  }

  /// The frame and the journal's centre moved to t + Δt; what the attempt solves for.
  SpinStepper::Attempt SpinStepper::begin_attempt(const double dt)
  {
    const double t1 = t_ + dt;
    frame_.phi = motion_.phi(t1);
    frame_.centre_previous = motion_.centre_frame(t_);
    frame_.centre = motion_.centre_frame(t1);
    Attempt a;
    a.dt = dt;
    a.delta = motion_.delta(t1);
    a.dphi = motion_.phi(t1) - motion_.phi(t_);
    // the scale of the balance: from the last step's force and torque once there is one
    // (so that it is known before the first evaluation), else from the first evaluation's
    // (solve_nested)
    a.torque_scale = last_force_ > 0.0 ? torque_scale(last_force_, last_torque_, t1, dt) : 0.0;
    return a;
  }

  /// [N m] the torque balance's scale at a contact force [N] and journal torque [N m]: the
  /// largest friction torque μ F R_J, the torque, or the inertial torque of spinning up to the
  /// rolling rate within Δt.
  double SpinStepper::torque_scale(const double force, const double torque, const double t1,
                                   const double dt) const
  {
    return std::max({scene_.contact.mu * force * scene_.geometry.R_J(), std::abs(torque),
                     inertia_ * motion_.rolling_rate(t1) / dt, 1e-30});
  }

  /// The deformable journal's partners found again for its pose now, slip counted from the
  /// step's start (nothing for the rigid journal), timed and counted.
  void SpinStepper::pair_turned_journal()
  {
    if (!problem_.journal_turns_deformable())
      return;
    ScopedTimer timer(search_time_);
    problem_.pair_turned_journal(saved_.u);
    ++n_searches_;
  }

  /// The state extrapolated linearly in time from the last two converged steps.
  void SpinStepper::start_predicted_in_time(const double dt)
  {
    const double w = dt / dt_previous_;
    state_.u_owned() = saved_.u;
    state_.u_owned().sadd(1.0 + w, -w, u_previous_step_);
    state_.publish();
  }

  /// After a coupled iteration stalled on the torque balance: the root finder from its last
  /// iterate — that spin, that state, the balance's slope there — instead of from the step's
  /// start. The stall is the active sets and the yielding points flickering as γ̇ moves by
  /// 1e-5 of itself while the balance sits at 1e-5..1e-4 of its scale, short of the 1e-6
  /// tolerance; the bodies there are within a few iterations of their converged state at a
  /// fixed γ̇, and the root is within the secant's reach. (The level-2 paper's case, step 12:
  /// the bordered iteration stalled twice, then the root finder from the step's start took 18
  /// material iterations for its first evaluation alone.) False when it failed: the caller
  /// goes on as after any failed coupled iteration.
  bool SpinStepper::solve_nested_from(const Stall &stall, Attempt &attempt, Step &step)
  {
    try
      {
        bool predicted_in_time = false;
        solve_nested(attempt, step, false, predicted_in_time, &stall);
        return true;
      }
    catch (const StepFailure &f)
      {
        if (rank_ == 0)
          log::debug(" the root finder from the stalled iteration failed (" + f.reason + ")");
        return false;
      }
  }

  /// rolling.spin_solver nested (and the coupled iteration's fallback): the root of the torque
  /// balance over γ̇, each evaluation a converged state of the bodies. From `from` (a stalled
  /// coupled iteration): its first evaluation at the stall's spin from the model's state
  /// there, the second by the stall's slope. Throws StepFailure.
  void SpinStepper::solve_nested(Attempt &attempt, Step &step, const bool predict_in_time,
                                 bool &predicted_in_time, const Stall *from)
  {
    if (from)
      attempt.torque_scale = from->scale;
    const double dt = attempt.dt, t1 = t_ + dt;
    double &torque_scale = attempt.torque_scale;
    RollingSolve &rs = step.state;
    unsigned int n_evaluated = 0;
    double rate_last = 0.0, rate_before = 0.0;
    TrilinosWrappers::MPI::Vector u_last, u_before;
    u_last.reinit(state_.u_owned());  // zero, on the owned DoFs
    u_before.reinit(state_.u_owned());
    // g(γ̇) / scale, the scale μ F R_J (+ the inertia_ term): the balance holds to 1e-6 of
    // the largest friction torque
    auto g = [&](const double rate) {
      frame_.delta_psi = rate * dt - attempt.dphi;
      // Where the material Newton iteration starts (only the start: the same converged
      // state, fewer iterations):
      // - the attempt's first evaluation: the state extrapolated linearly in time from the
      //   last two converged steps (the reduced pipeline scene: 12.3 → 11.4 s at 16 steps,
      //   20.3 → 17.2 s at 32). A patch that moves far in a step is extrapolated badly (the
      //   8-step scene's hold steps failed from it), so an attempt that fails from the
      //   prediction is tried again at the same Δt from the last state before the step is
      //   cut;
      // - later ones: the state predicted linearly in γ̇ from the attempt's last two
      //   evaluations, within two of their spacings (the state moves nearly linearly with
      //   the spin near the root: 14.2 → 12.3 s and 24.2 → 20.3 s)
      if (n_evaluated == 0 && have_previous_ && predict_in_time)
        {
          predicted_in_time = true;
          start_predicted_in_time(dt);
        }
      if (n_evaluated >= 2 && rate != rate_last && rate_last != rate_before &&
          std::abs(rate - rate_last) <= 2.0 * std::abs(rate_last - rate_before))
        {
          // start = last + w (last − before), as the quasi-static push's predictor
          const double w = (rate - rate_last) / (rate_last - rate_before);
          state_.u_owned() = u_last;
          state_.u_owned().sadd(1.0 + w, -w, u_before);
          state_.publish();
        }
      // The deformable journal turns over the bore: the bore nodes' partners are found
      // again for this pose, between the bore (X + u) and the journal placed at
      // c + Q(ψ)(X − a + u), both at the start state; the slip counts from the step's start
      // with them (follow_sliding, which rebuilds the sparsity pattern when they do not fit
      // it). Couplings kept from the step's start would be off by R_J Δψ²/2 in the gap:
      // 19 µm for a 3.6° step, more than the push.
      pair_turned_journal();
      if (log::level() <= log::Level::debug && rank_ == 0)
        log::debug(" torque evaluation at the journal's spin " + format_value(rate) + " rad/s (t " +
                   format_value(t1) + " s, dt " + format_value(dt) + " s)");
      rs = problem_.solve_rolling_state(attempt.delta);
      step.newton_iterations += rs.newton_iterations;
      step.line_search_steps += rs.line_search_steps;
      step.contact_iterations += rs.contact_iterations;
      step.linear_iterations += rs.linear_iterations;
      u_before.swap(u_last);
      u_last = state_.u_owned();
      rate_before = rate_last;
      rate_last = rate;
      ++n_evaluated;
      const double inertial = inertia_ * (rate - gamma_rate_) / dt;
      if (torque_scale == 0.0)
        torque_scale = this->torque_scale(std::abs(rs.record.force), rs.torque_journal, t1, dt);
      return (inertial - rs.torque_journal) / torque_scale;
    };
    // the bracket: spinning up, between the last rate and the rolling rate; rolling already
    // (within 5 % of it), a narrow one at the last rate — the root moves little from step to
    // step and the torque is steep there (stick), so the wide bracket cost 2–3 more
    // evaluations a step, each a material Newton solve (the bracket widens itself if the
    // root lies outside). Rolling already and the torque's slope dM/dγ̇ known from the last
    // step: the second point is the Newton step with that slope instead, near the root as
    // the slope changes little from step to step (the reduced pipeline scene: 81 → 76
    // evaluations at 16 steps, 142 → 136 at 32, docs/benchmarks.md)
    const double a = from ? from->rate : gamma_rate_;
    const double roll = motion_.rolling_rate(t1);
    const bool rolling_already = std::abs(roll - a) <= 5e-2 * roll;
    const double slope_guess =
      torque_scale > 0.0 ? (inertia_ / dt - torque_rate_slope_) / torque_scale : 0.0;
    const IncreasingRoot balance{g, 1e-6, 1e-10 * roll, scene_.rolling.max_spin_iterations,
                                 "the journal's torque balance"};
    const auto root = from ? solve_increasing_from(balance, a, from->slope) :
                      rolling_already && torque_rate_slope_ < 0.0 && std::isfinite(slope_guess) ?
                             solve_increasing_from(balance, a, slope_guess) :
                             solve_increasing(balance, a, rolling_already ? a + 2e-4 * roll : roll);
    step.spin_evaluations = root.evaluations;
    if (!root.converged)
      throw StepFailure{root.message};
    step.rate = root.x;  // the last evaluation: the model's state is this one
    // dM/dγ̇ [N m s] from g's slope: g = (I (γ̇ − γ̇_n)/Δt − M)/scale
    if (root.evaluations >= 2 && root.slope > 0.0)
      torque_rate_slope_ = inertia_ / dt - root.slope * torque_scale;
    last_force_ = std::abs(rs.record.force);
    last_torque_ = rs.torque_journal;
  }

  /// The coupled iteration (rolling.spin_solver coupled) from the model's current state: each
  /// material Newton iteration solves the bodies at the current γ̇ (the tangent, its load and
  /// the active-set contact solve), then γ̇ takes a Newton step on the torque balance
  ///   g(γ̇) = (I (γ̇ − γ̇_n)/Δt − M)/scale
  /// with the slope dg/dγ̇ of the last converged step — the balance's total derivative along
  /// converged states, which is what a Newton step on γ̇ needs once the bodies follow it —
  /// replaced by the secant over the last two iterates when that lies within a factor of 5 of
  /// it (the slope changes with the stick/slip pattern; a secant further off is taken for the
  /// bodies' own convergence, not the balance's), or whatever it is once the bodies have
  /// settled (the correction within 100 tolerances: g's change is then the balance's own, as
  /// in a step without contact, where M = 0 and the slope is I/Δt alone). Converged when one
  /// iterate meets the material Newton tolerance (SpinProblem::material_tolerance) and the
  /// root finder's (|g| ≤ 1e-6, or a γ̇ step by the iterates' secant below 1e-10 of the
  /// rolling rate). False when it diverges (the correction grew three times running), stalls
  /// (then with `stall`, the model left at its last iterate), a solve fails, or it runs out of
  /// rolling.max_newton_iterations; the caller restores the state.
  ///
  /// `bordered` (rolling.spin_solver bordered): Newton on the bodies and γ̇ together. The
  /// linearised problem of an iteration is, with ψ = γ̇ Δt − Δφ the journal's turn,
  ///     K Δu + R_ψ Δψ = −R,    g_u Δu + g_ψ Δψ = −g;
  /// eliminated by blocks: the iteration's own contact solve is the first column (Δu at the
  /// turn now), and the same solve at ψ + dψ with the same tangent and sets
  /// (SpinProblem::material_iteration's TurnSensitivity) the second, w = du/dψ with the
  /// torque's change. The balance's slope is then the linearised total derivative
  ///     dg/dγ̇ = (I/Δt − dM/dγ̇)/scale,   dM/dγ̇ = Δt dM/dψ,
  /// γ̇ takes the Newton step −g/(dg/dγ̇) and u follows it, u += Δγ̇ Δt w: the next iteration
  /// starts where the linearised bodies would be at the new spin, instead of having to find
  /// it (the coupled iteration's linear tail, ~10× an iteration: docs/benchmarks.md "Why a
  /// bordered solve would pay"). One more linear solve an iteration, no slope carried from
  /// step to step.
  bool SpinStepper::solve_coupled(const Attempt &a, const bool bordered, Step &step,
                                  std::optional<Stall> &stall)
  {
    const double tolerance = problem_.material_tolerance();
    const double roll = motion_.rolling_rate(t_ + a.dt);
    const unsigned int max_it = scene_.rolling.max_newton_iterations;
    // the balance's scale: the attempt's (from the last step), else (bordered's first step)
    // from the first iteration's force and torque, as the root finder's first evaluation
    double scale = a.torque_scale;
    SpinBalanceIteration balance(bordered ? 0.0 :
                                            (inertia_ / a.dt - torque_rate_slope_) / scale);
    // the turn the sensitivity is taken over: 1 % of the rolling rate's over the step. The
    // linearised state is linear in it but for the rotation's curvature (a relative error of
    // dψ/2 ~ 1e-4 of the column) and the solves' round-off (1e-10 of |b|), which this keeps
    // apart
    const double rate_perturbation = 1e-2 * roll;  // [rad/s]
    TurnSensitivity sensitivity;
    // γ̇ starts at the last step's, as the root finder's bracket does: where the balance is
    // flat in γ̇ (no contact: M = 0, g = I (γ̇ − γ̇_n)/(Δt scale)) its tolerance on g would
    // accept a guess off by 1e-6 scale Δt/I — 3e-3 rad/s for the 1.8e-6 kg m² journal under
    // 381 N — where this start is the exact root. (Extrapolated in time instead, the reduced
    // scenes' spin-up steps overshot the root twofold and hold steps kept a spin off by 5e-4.)
    double rate = gamma_rate_;
    double rate_searched = std::numeric_limits<double>::quiet_NaN();
    const auto hand_over = [&](const std::string &why) {
      if (rank_ == 0)
        log::debug(" the coupled iteration " + why + "; the root finder takes the step");
      return false;
    };
    try
      {
        for (unsigned int k = 0; k < max_it; ++k)
          {
            frame_.delta_psi = rate * a.dt - a.dphi;
            // the deformable journal's partners for this pose (as in the root finder's
            // evaluations), found again whenever γ̇ moved
            if (!(rate == rate_searched))
              {
                pair_turned_journal();
                rate_searched = rate;
              }
            sensitivity.d_psi = rate_perturbation * a.dt;
            const MaterialIteration it = problem_.material_iteration(
              a.delta, k > 0 && scene_.solver.line_search, bordered ? &sensitivity : nullptr);
            ++step.newton_iterations;
            step.line_search_steps += it.line_search_steps;
            step.contact_iterations += it.record.contact_iterations;
            step.linear_iterations += it.record.linear_iterations + sensitivity.linear_iterations;
            const double torque = problem_.journal_torque();
            if (scale == 0.0)
              scale = torque_scale(std::abs(it.record.force), torque, t_ + a.dt, a.dt);
            const double g = (inertia_ * (rate - gamma_rate_) / a.dt - torque) / scale;
            if (!bordered)
              balance.take_secant(rate, g, it.correction, tolerance);
            else if (!balance.take_bordered_slope(
                       (inertia_ / a.dt - sensitivity.d_torque / rate_perturbation) / scale))
              return hand_over("finds a balance that does not rise with the spin");
            const double rate_step = balance.step(g, roll);
            if (log::level() <= log::Level::debug && rank_ == 0)
              log::debug("  coupled iteration " + std::to_string(k + 1) + ": spin " +
                         format_value(rate) + " rad/s, balance " + format_value(g) +
                         ", correction " + format_value(it.correction) + " m, " +
                         std::to_string(it.n_plastic_points) + " quadrature points yielding");
            if (balance.converged(it.correction, tolerance, rate_step, roll))
              {
                step.rate = rate;
                step.spin_evaluations = k + 1;
                step.coupled = true;
                step.state.record = it.record;
                step.state.torque_journal = torque;
                step.state.newton_iterations = k + 1;
                step.state.contact_iterations = step.contact_iterations;
                step.state.linear_iterations = step.linear_iterations;
                if (balance.own_slope())
                  torque_rate_slope_ = inertia_ / a.dt - balance.slope() * scale;
                last_force_ = std::abs(it.record.force);
                last_torque_ = torque;
                return true;
              }
            switch (balance.trend(it.correction, g))
              {
                case SpinBalanceIteration::Trend::diverges:
                  return hand_over("diverges");
                case SpinBalanceIteration::Trend::stalls:
                  stall = Stall{rate, balance.slope(), scale};
                  if (rank_ == 0)
                    log::debug(" the coupled iteration stalls on the torque balance; the root "
                               "finder goes on from its last iterate");
                  return false;
                case SpinBalanceIteration::Trend::continues:
                  break;
              }
            balance.advance(rate, g);
            rate += rate_step;
            if (bordered && rate_step != 0.0)
              {
                // the bodies follow the spin as the linearised problem says: u += Δγ̇ Δt w
                state_.u_owned().add(rate_step / rate_perturbation, sensitivity.du);
                state_.publish();
              }
          }
      }
    catch (const StepFailure &f)
      {
        return hand_over("failed (" + f.reason + ")");
      }
    return hand_over("did not converge in " + std::to_string(max_it) + " iterations");
  }

  /// After a failed attempt at Δt (the state restored): an attempt that started from the state
  /// predicted in time is tried again at the same Δt from the last state; otherwise the step
  /// is cut (the step controller's floor: a step that keeps failing would otherwise shrink
  /// without end, t + Δt → t). False with `message` when no cut is left.
  bool SpinStepper::retry(const StepFailure &f, const bool predicted_in_time, bool &predict_in_time,
                          double &dt, std::string &message)
  {
    if (predicted_in_time)
      {
        predict_in_time = false;
        if (rank_ == 0)
          log::debug("fe_stage: time step to t = " + format_value(t_ + dt) +
                     " s failed from the state predicted in time (" + f.reason +
                     "); again from the last state");
        return true;
      }
    if (!control_.cut())
      {
        message = "time step to t = " + format_value(t_ + dt) + " s failed after " +
                  std::to_string(control_.cuts()) + " cuts" + control_.floor_note("s") + ": " +
                  f.reason;
        if (rank_ == 0)
          log::error("fe_stage: " + message);
        return false;
      }
    dt = control_.size();
    if (rank_ == 0)
      log::warning("fe_stage: time step to t = " + format_value(t_ + 2 * dt) + " s failed (" +
                   f.reason + "); retrying with dt " + format_value(dt) + " s");
    return true;
  }

  void SpinStepper::accept(const Step &step)
  {
    gamma_ += step.rate * step.dt;
    gamma_rate_ = step.rate;
    t_ += step.dt;
    u_previous_step_ = saved_.u;
    dt_previous_ = step.dt;
    have_previous_ = true;
    control_.accept();
  }

  void SpinStepper::write_restart(RestartWriter &out) const
  {
    out.section("spin stepper");
    for (const double v : {t_, gamma_, gamma_rate_, last_force_, last_torque_, torque_rate_slope_,
                           dt_previous_, search_time_})
      out.put(v);
    out.put(have_previous_);
    out.put(n_searches_);
    out.put(n_coupled_fallbacks_);
    out.put(control_.carried());
    put_owned(out, u_previous_step_);
  }

  void SpinStepper::read_restart(RestartReader &in)
  {
    in.section("spin stepper");
    for (double *v : {&t_, &gamma_, &gamma_rate_, &last_force_, &last_torque_, &torque_rate_slope_,
                      &dt_previous_, &search_time_})
      *v = in.get<double>();
    have_previous_ = in.get<bool>();
    n_searches_ = in.get<unsigned int>();
    n_coupled_fallbacks_ = in.get<unsigned int>();
    const auto carried = in.get<StepController::Carried>();
    if (!(carried.size > 0.0 && carried.size <= control_.nominal()))
      in.damaged("its step size " + format_value(carried.size) + " s is not in (0, " +
                 format_value(control_.nominal()) + "] s, this scene's nominal step");
    control_.restore(carried);
    if (!(t_ >= 0.0 && t_ <= t_end_ * (1.0 + 1e-12)))
      in.damaged("its time " + format_value(t_) + " s is not in [0, " + format_value(t_end_) +
                 "] s, this scene's run");
    get_owned(in, u_previous_step_, "the state before the last step");
  }
}  // namespace clearjoint::fe::detail
