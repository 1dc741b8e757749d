#include "mbd_stage/integrator.h"

#include "mbd_stage/sundials_stepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace clearjoint::mbd
{
  namespace
  {
    /// The output times t0 + k·interval, k = 1, 2, … (t0 itself is written before the first
    /// step). Multiplied rather than summed, so the times do not drift.
    class OutputGrid
    {
    public:
      OutputGrid(const double t0, const double interval)
        : t0_(t0)
        , interval_(interval)
      {
      }
      double next() const { return t0_ + static_cast<double>(k_) * interval_; }
      void advance() { ++k_; }

    private:
      double t0_, interval_;
      long k_ = 1;
    };

    /// Whether a contact force may peak inside the step just taken, so that it is worth
    /// sampling: an active contact that was in compression (δ̇ > 0) at the start of the step
    /// (with damping, the force peaks before the maximum compression).
    class CompressionWatch
    {
    public:
      explicit CompressionWatch(std::vector<double> rates_at_start)
        : rates_prev_(std::move(rates_at_start))
      {
      }
      /// rates_now: δ̇ per contact at the end of the step, the next step's start.
      bool peak_possible(const MultibodySystem &sys, const std::vector<double> &rates_now)
      {
        bool in_contact = false;
        int ic = 0;
        for (const auto &cj : sys.clearance_joints())
          for (int c = 0; c < ClearanceJoint::n_contacts; ++c, ++ic)
            in_contact = in_contact || (cj->state(c).active &&
                                        rates_prev_.size() == rates_now.size() &&
                                        rates_prev_[ic] > 0.0);
        rates_prev_ = rates_now;
        return in_contact;
      }

    private:
      std::vector<double> rates_prev_;
    };

    /// Whether the roots found (+1 onset, −1 release per contact) switch some contact's mode.
    bool switches_a_contact(const MultibodySystem &sys, const std::vector<int> &found)
    {
      bool will_change = false;
      int i = 0;
      for (auto &cj : sys.clearance_joints())
        for (int c = 0; c < ClearanceJoint::n_contacts; ++c, ++i)
          will_change = will_change || (found[i] > 0 && !cj->state(c).active) ||
                        (found[i] < 0 && cj->state(c).active);
      return will_change;
    }

    /// Switches the contact modes at a root t: an onset activates the contact and records
    /// δ̇⁻ (the damping term's impact velocity, and whether the floor replaces it), a release
    /// deactivates it; both are recorded as events. Returns whether any mode changed.
    bool switch_contacts(const MultibodySystem &sys, const double *y,
                         const std::vector<int> &found, const double t,
                         std::vector<ContactEvent> &events)
    {
      const std::vector<double> rates = sys.contact_rates(y);
      bool changed = false;
      int i = 0;
      for (auto &cj : sys.clearance_joints())
        for (int c = 0; c < ClearanceJoint::n_contacts; ++c, ++i)
        {
          if (found[i] == 0)
            continue;
          ContactState &s = cj->state(c);
          if (found[i] > 0 && !s.active)
          {
            s.active = true;
            s.delta_dot_impact = rates[i];
            ++s.n_impacts;
            const ContactForceModel &model = c == 0 ? cj->radial_model() : cj->axial_model();
            if (model.chi() != 0.0 && rates[i] < model.min_impact_velocity())
              ++s.n_impact_velocity_floored;
            events.push_back({t, cj->name(), c, true, rates[i]});
            changed = true;
          }
          else if (found[i] < 0 && s.active)
          {
            s.active = false;
            events.push_back({t, cj->name(), c, false, rates[i]});
            changed = true;
          }
        }
      return changed;
    }
  } // namespace

  std::string Integrator::method_name(const IntegratorMethod m)
  {
    return integrator_method_names()[static_cast<std::size_t>(m)];
  }

  IntegratorMethod parse_integrator_method(const std::string &name)
  {
    const auto &names = integrator_method_names();
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name)
        return static_cast<IntegratorMethod>(i);
    throw std::invalid_argument("unknown integrator method " + name);
  }

  Integrator::Integrator(MultibodySystem &system, IntegratorSettings settings)
    : system_(system)
    , settings_(settings)
    , stepper_(std::make_unique<SundialsStepper>(system_, settings_, stats_))
  {
  }

  Integrator::~Integrator() = default;

  void Integrator::record_step_size(const double h_last, double &h_restart)
  {
    if (h_last > 0.0)
    {
      h_restart = 0.1 * h_last;
      stats_.h_min = std::min(stats_.h_min, h_last);
      stats_.h_max = std::max(stats_.h_max, h_last);
    }
  }

  void Integrator::sample_step(const double t, const double t_reached, const StepCallback &on_step)
  {
    const int n = system_.n_states();
    Eigen::VectorXd ys(n);
    for (int k = 1; k < settings_.n_step_samples; ++k)
    {
      const double ts = t + (t_reached - t) * k / settings_.n_step_samples;
      ys = Eigen::Map<const Eigen::VectorXd>(stepper_->state_at(ts), n);
      on_step(ts, ys, true);
    }
  }

  void Integrator::run(const double t0, const double t_end, const double output_interval,
                       const OutputCallback &on_output, const StepCallback &on_step)
  {
    SundialsStepper &stepper = *stepper_;
    const int n = system_.n_states(), ng = system_.n_gaps();
    stepper.make_vectors();
    double *yp = stepper.y();

    double h_restart = 0.0;  // [s] initial step after a restart (0: SUNDIALS' estimate)
    stepper.update_allowances();
    stepper.start(t0, t_end, h_restart);
    stats_ = StepStatistics{};
    stats_.h_min = std::numeric_limits<double>::infinity();
    Eigen::VectorXd y_out(n);
    const auto emit = [&](const double t, const double *src) {
      for (int i = 0; i < n; ++i)
        y_out[i] = src[i];
      on_output(t, y_out);
    };
    emit(t0, yp);
    OutputGrid grid(t0, output_interval);
    double t = t0;
    const double t_eps = 1e-12 * std::max(1.0, std::abs(t_end));
    std::vector<int> found(static_cast<std::size_t>(std::max(ng, 1)));
    CompressionWatch compression(system_.contact_rates(yp));

    // The state at the start of the current step: an event's restart state is recomputed from
    // it (see below).
    Eigen::VectorXd y_step_start(n);
    while (t < t_end - t_eps)
    {
      if (stepper.is_explicit())
        y_step_start = Eigen::Map<const Eigen::VectorXd>(yp, n);
      const double t_step_start = t;
      const SundialsStepper::Step step = stepper.step(t_end);
      const double t_reached = step.t_reached;
      // Accepted state: law-range counters (and "error"), the allowances of the depth guard.
      system_.observe_accepted(yp, settings_.depth_guard);
      stepper.update_allowances();
      record_step_size(stepper.last_step_size(), h_restart);
      // Dense output at the grid points passed.
      while (grid.next() <= t_reached + t_eps && grid.next() <= t_end + t_eps)
      {
        const double to = std::min(grid.next(), t_reached);
        emit(to, stepper.state_at(to));
        grid.advance();
      }
      if (on_step)
      {
        if (compression.peak_possible(system_, system_.contact_rates(yp)) &&
            settings_.n_step_samples > 1 && t_reached > t)
          sample_step(t, t_reached, on_step);
        Eigen::Map<const Eigen::VectorXd> ys(yp, n);
        on_step(t_reached, ys, false);
      }
      t = t_reached;
      if (!step.at_root)
        continue;
      ++stats_.n_roots;
      stepper.root_directions(found);
      // (A root within 1e-12 s of the step's start is left as interpolated: the interpolant's
      // error vanishes there like (t − t_n)², and ARKODE refuses a stop time that close.)
      if (stepper.is_explicit() && switches_a_contact(system_, found) &&
          t - t_step_start > 1e-12 * std::max(1.0, std::abs(t)))
      {
        // ARKODE returns the state at the root from its dense output (cubic Hermite here, error
        // O(h^4) over the whole step), and the integrator restarts from that state: every event
        // would inject the interpolant's error into the trajectory — at the defaults a 3e-9 s
        // shift of one impact of the frictionless FE scene, 2.2e-4 m/s of slider velocity by
        // 19 ms (docs/benchmarks.md). So the state at the root is recomputed by one DP5 step
        // from the start of the step that found it, with the contact modes still those of that
        // step, and of length t_root − t_n ≤ the accepted step (whose error test it passed).
        stepper.add_counters();
        stepper.recompute_state_at_root(t_step_start, y_step_start, t);
        ++stats_.n_event_resteps;
      }
      if (switch_contacts(system_, yp, found, t, events_))
      {
        stepper.add_counters();
        ++stats_.n_restarts;
        stepper.start(t, t_end, h_restart);
      }
    }
    stepper.add_counters();
    if (!std::isfinite(stats_.h_min))
      stats_.h_min = 0.0;
  }
} // namespace clearjoint::mbd
