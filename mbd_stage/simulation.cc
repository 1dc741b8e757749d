#include "mbd_stage/simulation.h"

#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "mbd_stage/output_rows.h"
#include "mbd_stage/run_peaks.h"
#include "mbd_stage/simulation_summary.h"

#include <chrono>
#include <cmath>

namespace clearjoint::mbd
{
  std::vector<double> SimulationResult::column(const std::string &name) const
  {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name)
      {
        std::vector<double> v;
        v.reserve(rows.size());
        for (const auto &r : rows)
          v.push_back(r[c]);
        return v;
      }
    throw std::out_of_range("no column " + name);
  }

  namespace
  {
    using Clock = std::chrono::steady_clock;

    double seconds_since(const Clock::time_point start)
    {
      return std::chrono::duration<double>(Clock::now() - start).count();
    }

    /// The scene's budget (issue 16): thrown as a NumericalError from the step callback, so
    /// the run stops like any numerical failure (partial outputs kept, marked incomplete).
    void check_budget(const Scene &scene, const long n_steps, const double t,
                      const Clock::time_point start)
    {
      const auto where = [&] {
        return "at t = " + format_value(t) + " s of " + format_value(scene.duration) +
               " s; the scene's budget (keys budget.wall_time, budget.steps) stops runs that "
               "would otherwise go on for days — a step size collapsing to nothing usually "
               "means a stiff or badly scaled scene";
      };
      if (n_steps > scene.max_steps)
        throw NumericalError("step budget exceeded: " + std::to_string(scene.max_steps) +
                             " integrator steps taken " + where());
      const double seconds = seconds_since(start);
      if (seconds > scene.max_wall_time)
        throw NumericalError("wall-clock budget exceeded: " + format_value(seconds) +
                             " s > budget.wall_time = " + format_value(scene.max_wall_time) +
                             " s " + where());
    }

    /// "" if every value is finite, else which column and time holds the first that is not.
    std::string first_non_finite(const SimulationResult &res)
    {
      for (const auto &row : res.rows)
        for (std::size_t c = 0; c < row.size(); ++c)
          if (!std::isfinite(row[c]))
            return "non-finite value (" + format_value(row[c]) + ") in output column '" +
                   res.columns[c] + "' at t = " + format_value(row[0]) + " s";
      return "";
    }

    /// What happens at the integrator's callbacks: an output row at every output time, the
    /// peaks at every accepted step and interior sample, and the budget and interrupt checks
    /// after every accepted step.
    class RunObserver
    {
    public:
      RunObserver(Scene &scene, SimulationResult &res, const Clock::time_point start)
        : scene_(scene)
        , sys_(*scene.system)
        , res_(res)
        , start_(start)
        , columns_(make_output_columns(scene, sys_))
        , rows_(scene, sys_, columns_)
        , peaks_(scene, sys_, columns_.slider)
        , ydot_(static_cast<std::size_t>(sys_.n_states()))
      {
        res.columns = columns_.names;
        res.units = columns_.units;
      }

      void at_output(const double t, const Eigen::VectorXd &y)
      {
        sys_.rhs(t, y.data(), ydot_.data(), &ev_output_);
        rows_.append(t, ev_output_, res_);
        peaks_.at_state(t, ev_output_);
      }

      void at_step(const double t, const Eigen::VectorXd &y, const bool interior)
      {
        if (interior)
        {
          // Interior samples while in contact: only the contact-force peaks (no constraint
          // solve).
          peaks_.at_sample(t, sys_.radial_forces(y.data()));
          return;
        }
        check_budget(scene_, ++n_steps_, t, start_);
        interrupt::throw_if_requested("at t = " + format_value(t) + " s");
        sys_.rhs(t, y.data(), ydot_.data(), &ev_step_);
        peaks_.at_state(t, ev_step_);
      }

      const RunPeaks &peaks() const { return peaks_.peaks(); }

    private:
      Scene &scene_;
      MultibodySystem &sys_;
      SimulationResult &res_;
      Clock::time_point start_;
      OutputColumns columns_;
      OutputRows rows_;
      PeakTracker peaks_;
      std::vector<double> ydot_;             // scratch: rhs() writes the derivatives here
      SystemEvaluation ev_output_, ev_step_;  // reused to keep their allocations
      long n_steps_ = 0;
    };

    /// Runs the integrator over the scene's duration; a NumericalError (a failed step, the
    /// budget, an interrupt) ends the run incomplete with the rows reached so far.
    void integrate(Scene &scene, Integrator &integrator, RunObserver &observer,
                   SimulationResult &res)
    {
      log::Progress progress("mbd_stage " + scene.name, scene.duration, "s");
      try
      {
        integrator.run(
          0.0, scene.duration, scene.output_interval,
          [&](double t, const Eigen::VectorXd &y) {
            observer.at_output(t, y);
            progress.update(t);
          },
          [&](double t, const Eigen::VectorXd &y, bool interior) {
            observer.at_step(t, y, interior);
          });
        res.complete = true;
      }
      catch (const NumericalError &e)
      {
        res.failure = e.what();
      }
      // No run ends "complete" with a NaN or Inf in its outputs.
      if (const std::string bad = first_non_finite(res); res.complete && !bad.empty())
      {
        res.complete = false;
        res.failure = bad;
      }
      progress.finish();
    }
  } // namespace

  SimulationResult simulate(Scene &scene)
  {
    const auto start = Clock::now();
    SimulationResult res;
    RunObserver observer(scene, res, start);
    Integrator integrator(*scene.system, scene.integrator);
    integrate(scene, integrator, observer, res);
    res.statistics = integrator.statistics();
    res.events = integrator.events();
    res.peak_contact_force = observer.peaks().contact_force;
    res.first_impact_peak_force = observer.peaks().first_impact_force;
    res.wall_time = seconds_since(start);
    res.summary = make_summary(scene, res, observer.peaks());
    return res;
  }
} // namespace clearjoint::mbd
