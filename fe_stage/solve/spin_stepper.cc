#include "fe_stage/solve/spin_stepper.h"

#include "fe_stage/solve/root_finder.h"

#include <cmath>

namespace clearjoint::fe::detail
{
  SpinStepper::SpinStepper(ContactModel &model, const rolling::Motion &motion, const double t_end,
                           const unsigned int n_steps, const unsigned int max_cuts,
                           const double inertia)
    : m_(model)
    , motion_(motion)
    , t_end_(t_end)
    , inertia_(inertia)
    // the step size carries over: a step that needed cuts starts the next one at its own
    // size, which doubles (up to the nominal) after two steps without a cut
    , control_(t_end / n_steps, max_cuts, 2)
    , u_previous_step_(model.dofs_.owned(), model.comm_)
  {}

  bool SpinStepper::solve(Step &step, std::string &message)
  {
    double &dt = step.dt;
    ContactModel::RollingSolve &rs = step.state;
    double &rate_new = step.rate;
    unsigned int &spin_evaluations = step.spin_evaluations;
    dt = control_.begin_step(t_end_ - t_);
    rate_new = gamma_rate_;
    saved_ = m_.save_state();
    bool predict_in_time = true;
    for (;;)
      {
        const double t1 = t_ + dt;
        m_.frame_.phi = motion_.phi(t1);
        m_.frame_.centre_previous = motion_.centre_frame(t_);
        m_.frame_.centre = motion_.centre_frame(t1);
        const double delta1 = motion_.delta(t1);
        const double dphi = motion_.phi(t1) - motion_.phi(t_);
        // the scale of the balance: from the last step's force and torque once there is
        // one (so that it is known before the first evaluation), else from the first
        // evaluation's
        double torque_scale =
          last_force_ > 0.0 ?
            std::max({m_.scene_.contact.mu * last_force_ * m_.scene_.geometry.R_J(),
                      std::abs(last_torque_), inertia_ * motion_.rolling_rate(t1) / dt, 1e-30}) :
            0.0;
        bool predicted_in_time = false;
        unsigned int n_evaluated = 0;
        double rate_last = 0.0, rate_before = 0.0;
        TrilinosWrappers::MPI::Vector u_last(m_.dofs_.owned(), m_.comm_),
          u_before(m_.dofs_.owned(), m_.comm_);
        try
          {
            // g(γ̇) / scale, the scale μ F R_J (+ the inertia_ term): the balance holds
            // to 1e-6 of the largest friction torque
            auto g = [&](const double rate) {
              m_.frame_.delta_psi = rate * dt - dphi;
              // Where the material Newton iteration starts (only the start: the same
              // converged state, fewer iterations):
              // - the attempt's first evaluation: the state extrapolated linearly in time
              //   from the last two converged steps (the reduced pipeline scene: 12.3 →
              //   11.4 s at 16 steps, 20.3 → 17.2 s at 32). A patch that moves far in a
              //   step is extrapolated badly (the 8-step scene's hold steps failed from
              //   it), so an attempt that fails from the prediction is tried again at the
              //   same Δt from the last state before the step is cut;
              // - later ones: the state predicted linearly in γ̇ from the attempt's last
              //   two evaluations, within two of their spacings (the state moves nearly
              //   linearly with the spin near the root: 14.2 → 12.3 s and 24.2 → 20.3 s)
              // start = last + w (last − before), as the quasi-static push's predictor
              const auto start_from = [&](const TrilinosWrappers::MPI::Vector &last,
                                          const TrilinosWrappers::MPI::Vector &before,
                                          const double w) {
                m_.state_.u_owned() = last;
                m_.state_.u_owned().sadd(1.0 + w, -w, before);
                m_.state_.publish();
              };
              if (n_evaluated == 0 && have_previous_ && predict_in_time)
                {
                  predicted_in_time = true;
                  start_from(saved_.u, u_previous_step_, dt / dt_previous_);
                }
              if (n_evaluated >= 2 && rate != rate_last && rate_last != rate_before &&
                  std::abs(rate - rate_last) <= 2.0 * std::abs(rate_last - rate_before))
                start_from(u_last, u_before, (rate - rate_last) / (rate_last - rate_before));
              // The deformable journal turns over the bore: the bore nodes' partners are
              // found again for this pose, between the bore (X + u) and the journal placed
              // at c + Q(ψ)(X − a + u), both at the start state; the slip counts from the
              // step's start with them (follow_sliding, which rebuilds the sparsity pattern
              // when they do not fit it). Couplings kept from the step's start would be
              // off by R_J Δψ²/2 in the gap: 19 µm for a 3.6° step, more than the push.
              if (m_.rolling_deformable_journal())
                {
                  ScopedTimer timer(search_time_);
                  m_.follow_sliding(saved_.u);
                  ++n_searches_;
                }
              if (log::level() <= log::Level::debug && m_.rank_ == 0)
                log::debug(" torque evaluation at the journal's spin " + format_value(rate) +
                           " rad/s (t " + format_value(t1) + " s, dt " + format_value(dt) + " s)");
              rs = m_.solve_rolling_state(delta1);
              u_before.swap(u_last);
              u_last = m_.state_.u_owned();
              rate_before = rate_last;
              rate_last = rate;
              ++n_evaluated;
              const double inertial = inertia_ * (rate - gamma_rate_) / dt;
              if (torque_scale == 0.0)
                torque_scale = std::max(
                  {m_.scene_.contact.mu * std::abs(rs.record.force) * m_.scene_.geometry.R_J(),
                   std::abs(rs.torque_journal), inertia_ * motion_.rolling_rate(t1) / dt, 1e-30});
              return (inertial - rs.torque_journal) / torque_scale;
            };
            // the bracket: spinning up, between the last rate and the rolling rate;
            // rolling already (within 5 % of it), a narrow one at the last rate — the root
            // moves little from step to step and the torque is steep there (stick), so
            // the wide bracket cost 2–3 more evaluations a step, each a material Newton
            // solve (the bracket widens itself if the root lies outside). Rolling already
            // and the torque's slope dM/dγ̇ known from the last step: the second point is
            // the Newton step with that slope instead, near the root as the slope changes
            // little from step to step (the reduced pipeline scene: 81 → 76 evaluations
            // at 16 steps, 142 → 136 at 32, docs/benchmarks.md)
            const double a = gamma_rate_;
            const double roll = motion_.rolling_rate(t1);
            const bool rolling_already = std::abs(roll - a) <= 5e-2 * roll;
            const double slope_guess =
              torque_scale > 0.0 ? (inertia_ / dt - torque_rate_slope_) / torque_scale : 0.0;
            const IncreasingRoot balance{g, 1e-6, 1e-10 * roll,
                                         m_.scene_.rolling.max_spin_iterations,
                                         "the journal's torque balance"};
            const auto root =
              rolling_already && torque_rate_slope_ < 0.0 && std::isfinite(slope_guess) ?
                solve_increasing_from(balance, a, slope_guess) :
                solve_increasing(balance, a, rolling_already ? a + 2e-4 * roll : roll);
            spin_evaluations = root.evaluations;
            if (!root.converged)
              throw StepFailure{root.message};
            rate_new = root.x;  // the last evaluation: the model's state is this one
            // dM/dγ̇ [N m s] from g's slope: g = (I (γ̇ − γ̇_n)/Δt − M)/scale
            if (root.evaluations >= 2 && root.slope > 0.0)
              torque_rate_slope_ = inertia_ / dt - root.slope * torque_scale;
            last_force_ = std::abs(rs.record.force);
            last_torque_ = rs.torque_journal;
            break;
          }
        catch (const StepFailure &f)
          {
            m_.restore_state(saved_);
            if (!retry(f, predicted_in_time, predict_in_time, dt, message))
              return false;
          }
      }
    step.cuts = control_.cuts();
    return true;
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
        if (m_.rank_ == 0)
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
        if (m_.rank_ == 0)
          log::error("fe_stage: " + message);
        return false;
      }
    dt = control_.size();
    if (m_.rank_ == 0)
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
}  // namespace clearjoint::fe::detail
