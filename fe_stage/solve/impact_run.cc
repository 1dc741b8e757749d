// The impact study's time stepping (paper §3.2; issue 12): the rigid journal, launched at first
// touch toward the bearing, against the elastic bearing ring, by Hilber–Hughes–Taylor α.
//
// Per run:
//   1. the quasi-static curve F_qs(δ) of the same journal on the same mesh, pushed to 1.5× the
//      δ_max a linear contact of the probed stiffness would reach — the reference the dynamic
//      path is compared with, and the contact stiffness k_c that sets the time step:
//      T_c = 2π √(m_J/k_c) is the period of the journal's mass on the contact (the contact
//      lasts about T_c/2), and Δt = T_c / impact.steps_per_period (≥ 10: Δt/T ≤ 1/10). The
//      bearing's own modes faster than that are not resolved; HHT's α < 0 damps them.
//   2. time steps n → n+1 (HhtStepper, solve/hht_stepper.h). The bearing:
//      M a + (1+α)(K u − λ)_{n+1} − α(K u − λ)_n = 0 with the contact force λ enforced
//      exactly by the active set (the constraint rows of the quasi-static model): the condensed operator is c_m M + (1+α)K and the known part
//      b = c_m M û + α(K u_n − λ_n) (û the Newmark predictor), so that the residual
//      (c_m M + (1+α)K) u − b at the constrained DoFs is (1+α)λ_{n+1}. The journal (full-body
//      mass m_J, one unknown δ): m_J δ̈_{n+1} + (1+α)F_{n+1} − αF_n = 0, F the contact force.
//      For a given journal position δ the bearing's step is a contact solve (solve_increment);
//      g(δ) = m_J c_m (δ − δ̂) + (1+α)F_{n+1}(δ) − αF_n increases with δ, so the position is
//      found by regula falsi (Illinois, solve/root_finder.h) on a bracket that always exists:
//      [δ̂ − g(δ̂)/(m_J c_m), δ̂] (F ≥ 0 and grows with δ). A step that fails is halved, state
//      restored (solve/step_controller.h: at most loading.max_cuts times a step, never below
//      the nominal Δt halved as often); Δt grows back after four easy steps.
//   3. what each step records, the peak and the separation: the run stops when the journal
//      has left the bearing (out of contact for T_c/10 after contact, moving away) or at the
//      end time.
#include "fe_stage/solve/impact_run.h"

#include "fe_stage/solve/adaptive_cycles.h"
#include "fe_stage/solve/quasi_static_stepper.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <algorithm>
#include <cmath>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// Linear interpolation of the static curve at δ (0 below the first point's δ is reached
    /// through the origin); beyond the last point, the last segment extended.
    double interpolate_curve(const std::vector<IncrementRecord> &c, const double delta)
    {
      double d0 = 0.0, f0 = 0.0;
      for (std::size_t i = 0; i < c.size(); ++i)
        {
          const double d1 = c[i].delta, f1 = c[i].force;
          if (delta <= d1 || i + 1 == c.size())
            return f0 + (f1 - f0) * (delta - d0) / (d1 - d0);
          d0 = d1;
          f0 = f1;
        }
      return 0.0;
    }

    /// When the journal has left the bearing: out of contact for a tenth of the contact period
    /// (a momentary opening of the contact inside the impact does not end it) and moving away;
    /// and when the contact ended.
    class SeparationWatch
    {
    public:
      /// After each converged step (steps: all so far, the last this one, ending at t after
      /// dt_step; dt the next step's Δt [s]): whether this step completes the separation.
      bool update(const std::vector<DynamicStepRecord> &steps, const double t, const double dt_step,
                  const double dt, const double contact_period, const bool separated)
      {
        const DynamicStepRecord &rec = steps.back();
        if (rec.n_active > 0)
          {
            in_contact_ = true;
            free_steps_ = 0;
          }
        else if (in_contact_)
          {
            if (free_steps_ == 0)
              {
                // the contact ended inside this step: where the line through the last two
                // forces reaches zero, within this step
                contact_end_ = t - dt_step;
                if (steps.size() >= 3)
                  {
                    const auto &p1 = steps[steps.size() - 2], &p0 = steps[steps.size() - 3];
                    const double slope = (p1.force - p0.force) / (p1.time - p0.time);
                    if (slope < 0.0)
                      contact_end_ = std::min(t, p1.time - p1.force / slope);
                  }
              }
            ++free_steps_;
          }
        // (in whole steps, with a margin: T_c/dt differs between rank counts by round-off)
        const double free_needed = std::max(2.0, std::ceil(0.1 * contact_period / dt - 1e-6));
        return !separated && in_contact_ && rec.n_active == 0 && rec.delta_rate < 0.0 &&
               free_steps_ >= free_needed;
      }
      /// [s] when the contact last ended.
      double contact_end() const { return contact_end_; }

    private:
      bool in_contact_ = false;
      unsigned int free_steps_ = 0;  // steps without contact since the contact last ended
      double contact_end_ = 0.0;
    };

    /// The progress line of a step. ETA: the simulated time still to go at the wall time per
    /// simulated second so far. Without an end time the run ends when the journal has left:
    /// about 0.6 T_c for a linear contact (T_c/2 and the T_c/10 out of contact), later if the
    /// contact lasts.
    void log_step(const DynamicStepRecord &rec, const double t, const double dt,
                  const double end_time, const double t_end, const double contact_period,
                  const double wall_start)
    {
      const double t_expected =
        end_time > 0.0 ? t_end : std::min(t_end, std::max(0.6 * contact_period, t));
      const double per_second = (rec.wall_time - wall_start) / t;
      std::string eta = "";
      if (t_expected > t)
        eta = "  ETA " + log::format_duration(per_second * (t_expected - t)) +
              (end_time > 0.0 ? "" : " (if the journal leaves at 0.6 T_c)");
      char buf[360];
      std::snprintf(buf, sizeof(buf),
                    "fe_stage: step %u  t %.4g us  dt %.3g us  delta %.4g um  rate %.4g "
                    "m/s  F %.6g N  journal its %u  contact its %u  active %u  %s%s",
                    rec.step, t * 1e6, dt * 1e6, rec.delta * 1e6, rec.delta_rate, rec.force,
                    rec.journal_iterations, rec.contact_iterations, rec.n_active,
                    log::format_duration(rec.wall_time).c_str(), eta.c_str());
      log::info(buf);
    }

    /// The impact's summary after its steps: restitution, the energies left, and the peak
    /// against the quasi-static curve at the same δ (the dynamic gap).
    void summarise(ImpactSummary &S, const std::vector<DynamicStepRecord> &steps,
                   const std::vector<IncrementRecord> &curve, const double velocity_in,
                   const double numerical_dissipation, const double work_contact)
    {
      S.n_steps = static_cast<unsigned int>(steps.size());
      if (S.separated)
        S.restitution = S.velocity_out / velocity_in;
      S.numerical_dissipation = numerical_dissipation;
      S.work_contact = work_contact;
      if (!steps.empty())
        {
          const auto &e = steps.back();
          S.bearing_energy_left = e.kinetic_bearing + e.strain_bearing;
        }
      // the impulse of the contact force (trapezoidal over the steps, from F = 0 at t = 0) and
      // its mean over the contact
      double t_prev = 0.0, f_prev = 0.0;
      for (const auto &s : steps)
        {
          S.impulse += 0.5 * (f_prev + s.force) * (s.time - t_prev);
          t_prev = s.time;
          f_prev = s.force;
        }
      if (S.separated && S.contact_duration > 0.0)
        S.mean_force = S.impulse / S.contact_duration;
      S.quasi_static_force_at_peak_delta = interpolate_curve(curve, S.delta_at_peak);
      S.dynamic_gap = S.quasi_static_force_at_peak_delta > 0.0 ?
                        S.peak_force / S.quasi_static_force_at_peak_delta - 1.0 :
                        0.0;
    }

    void log_summary(const ImpactSummary &S)
    {
      log::info("fe_stage: impact: peak force " + format_value(S.peak_force) +
                " N at t = " + format_value(S.time_of_peak) + " s, delta_max " +
                format_value(S.delta_max) + " m, " +
                (S.separated ? "contact duration " + format_value(S.contact_duration) +
                                 " s, restitution " + format_value(S.restitution) :
                               std::string("still in contact at the end time")) +
                "; quasi-static F at the peak's delta " +
                format_value(S.quasi_static_force_at_peak_delta) + " N (dynamic " +
                format_value(100.0 * S.dynamic_gap) + " % above)");
    }
  }  // namespace

  ImpactRun::ImpactRun(StudyModel &model, const Parts &parts)
    : model_(model)
    , parts_(parts)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
    , n_ranks_(Utilities::MPI::n_mpi_processes(parts.comm))
  {}

  RunResult ImpactRun::run()
  {
    RunResult result;
    const HhtAlpha hht = begin(result);
    if (!adapt_mesh(result))
      return result;
    describe_mesh(result);
    if (!compute_reference(result))
      return result;
    // 2. Time steps. A deformable journal is free now: the constraints are rebuilt without its
    // loaded set (the static curve pushed it at its end faces or axis, as the thickness study).
    const bool deformable = parts_.plan.deformable_partner;
    if (deformable)
      model_.free_journal();
    auto &S = result.impact;
    const auto &I = parts_.scene.impact;
    const double m_J = S.journal_mass;
    HhtStepper stepper = model_.hht_stepper(hht, S.time_step, parts_.scene.loading.max_cuts, m_J,
                                            I.velocity, deformable);
    S.journal_mass = stepper.journal_mass();
    if (deformable && rank_ == 0)
      log::info("fe_stage: impact: deformable journal, FE mass " + format_value(S.journal_mass) +
                " kg (rho pi R_J^2 L_J = " + format_value(m_J) + " kg)");
    S.kinetic_initial = 0.5 * S.journal_mass * I.velocity * I.velocity;
    // impact_history.csv's t = 0 row — first touch, the journal at v_in, everything else at
    // rest — with the mass the ledger starts from (it was the rigid journal's ρ π R_J² L_J:
    // 1 + 3.8e-5 of ½mv² off for the deformable journal on the coarsest mesh, its discrete
    // volume)
    if (parts_.options.on_dynamic_step)
      {
        DynamicStepRecord start;
        start.delta_rate = I.velocity;
        start.kinetic_journal = S.kinetic_initial;
        parts_.options.on_dynamic_step(start);
      }
    TrilinosWrappers::MPI::Vector u_peak(parts_.dofs.owned(), parts_.comm);
    bool have_peak = false;
    if (!march(result, stepper, u_peak, have_peak))
      return result;
    // 3. The summary and the yield check where the force peaked.
    finish(result, stepper, have_peak ? &u_peak : nullptr);
    return result;
  }

  HhtAlpha ImpactRun::begin(RunResult &result)
  {
    result.n_ranks = n_ranks_;
    const auto &I = parts_.scene.impact;
    auto &S = result.impact;
    model_.build_mesh();
    S.velocity_in = I.velocity;
    S.journal_mass =
      rigid_journal_mass(parts_.scene);  // a deformable journal's: its FE mass, later
    // the application's operator and α, β, γ (an explicit α checked here, before the static
    // curve's cost)
    const HhtAlpha hht =
      HhtAlpha::for_application(I.application, I.alpha, "impact.alpha", parts_.scene.source_file);
    S.alpha = hht.alpha();
    S.kinetic_initial = 0.5 * S.journal_mass * I.velocity * I.velocity;
    return hht;
  }

  void ImpactRun::describe_mesh(RunResult &result) const
  {
    const auto &I = parts_.scene.impact;
    const auto &S = result.impact;
    model_.record_mesh(result);
    if (rank_ == 0)
      log::info("fe_stage: impact: " + std::to_string(result.n_cells) + " cells, " +
                std::to_string(result.n_dofs) + " DoFs; " +
                (parts_.plan.deformable_partner ? "deformable" : "rigid") + " journal " +
                format_value(S.journal_mass) + " kg at " + format_value(I.velocity) +
                " m/s, setup " + log::format_duration(result.setup_time));
  }

  bool ImpactRun::expected_penetration(QuasiStaticStepper &stepper, RunResult &result,
                                       double &delta_estimate)
  {
    const double delta_probe = 0.02 * parts_.scene.loading.delta_max;
    double f_probe = 0.0;
    if (!stepper.push_through({delta_probe}, result.message,
                              [&](unsigned int, IncrementRecord &r) { f_probe = r.force; }))
      {
        result.message = "static probe of the contact stiffness: " + result.message;
        return false;
      }
    if (!(f_probe > 0.0))
      {
        result.message = "the static probe at delta = " + format_value(delta_probe) +
                         " m found no contact force (mesh too coarse where the journal touches)";
        return false;
      }
    delta_estimate =
      parts_.scene.impact.velocity * std::sqrt(result.impact.journal_mass * delta_probe / f_probe);
    return true;
  }

  bool ImpactRun::adapt_mesh(RunResult &result)
  {
    if (parts_.scene.mesh.adaptive_cycles == 0)
      return true;
    const auto failed = [&](const std::string &what) {
      result.message = what + ": " + result.message;
      result.wall_time = model_.elapsed();
      return false;
    };
    // The meshes are marked where the impact is expected to peak: the static push to the
    // penetration a linear contact of the base mesh's probed stiffness reaches (the same
    // estimate that sizes the reference curve below), fixed for every cycle so that the
    // sequence F_k(δ_mark) is one quantity and gives the mesh's error estimate for the force
    // at the peak's penetration.
    QuasiStaticStepper stepper = model_.quasi_static_stepper();
    double delta_mark = 0.0;
    if (!expected_penetration(stepper, result, delta_mark))
      return failed("adaptive cycles, base mesh");
    result.adaptive_marking_delta = delta_mark;
    if (rank_ == 0)
      log::info("fe_stage: impact: adaptive cycles marked at the expected delta_max " +
                format_value(delta_mark) + " m (static probe on the base mesh)");
    AdaptiveCycles cycles(model_, {parts_.scene, parts_.bodies, parts_.dofs, parts_.comm},
                          delta_mark, "F(expected delta_max)");
    if (!cycles.refine(stepper, result))
      return false;
    if (cycles.final_mesh_marked())
      cycles.close(result, result.adaptive_cycles.back());
    else
      {
        // the final mesh's own push to δ_mark closes the sequence
        AdaptiveCycle last;
        if (!cycles.push_to_mark(stepper, result.message, last))
          return failed("the final adaptive mesh's push to the expected delta_max");
        cycles.close(result, last);
      }
    model_.start_from_rest();
    return true;
  }

  bool ImpactRun::compute_reference(RunResult &result)
  {
    const auto &I = parts_.scene.impact;
    const auto &L = parts_.scene.loading;
    auto &S = result.impact;
    const double m_J = S.journal_mass;
    const auto failed = [&](const std::string &message) {
      result.message = message;
      result.wall_time = model_.elapsed();
      return false;
    };
    // 1. The static probe and the quasi-static reference curve on this mesh.
    QuasiStaticStepper stepper = model_.quasi_static_stepper();
    double delta_estimate = 0.0;
    if (!expected_penetration(stepper, result, delta_estimate))
      return failed(result.message);
    const double delta_curve = 1.5 * delta_estimate;
    if (delta_curve > L.delta_max)
      throw InputError(parts_.scene.source_file, "loading.delta_max", format_value(L.delta_max),
                       ">= " + format_value(delta_curve) + " m for this impact",
                       "study impact: the contact candidates and the quasi-static reference "
                       "curve cover penetrations up to loading.delta_max; this impact is "
                       "expected to reach " +
                         format_value(delta_estimate) + " m");
    std::vector<double> targets;
    for (unsigned int k = 1; k <= L.n_increments; ++k)
      targets.push_back(delta_curve * k / L.n_increments);
    const bool curve_ok =
      stepper.push_through(targets, result.message, [&](unsigned int, IncrementRecord &r) {
        r.wall_time = model_.elapsed();
        result.increments.push_back(r);
        if (parts_.options.on_increment)
          parts_.options.on_increment(r);
      });
    if (!curve_ok)
      return failed("quasi-static reference curve: " + result.message);
    // the time scales: the contact's secant stiffness at the expected δ_max and its period
    S.contact_stiffness = interpolate_curve(result.increments, delta_estimate) / delta_estimate;
    S.contact_period = 2.0 * numbers::PI * std::sqrt(m_J / S.contact_stiffness);
    S.time_step = I.time_step > 0.0 ? I.time_step : S.contact_period / I.steps_per_period;
    if (rank_ == 0)
      log::info("fe_stage: impact: contact stiffness " + format_value(S.contact_stiffness) +
                " N/m (static curve at the expected delta_max " + format_value(delta_estimate) +
                " m), period T_c = " + format_value(S.contact_period) +
                " s, dt = " + format_value(S.time_step) + " s (T_c/" +
                format_value(S.contact_period / S.time_step) + "), end time " +
                format_value(end_time(S.contact_period)) + " s");
    return true;
  }

  double ImpactRun::end_time(const double contact_period) const
  {
    return parts_.scene.impact.end_time > 0.0 ? parts_.scene.impact.end_time : 4.0 * contact_period;
  }

  bool ImpactRun::march(RunResult &result, HhtStepper &stepper,
                        TrilinosWrappers::MPI::Vector &u_peak, bool &have_peak)
  {
    const auto &I = parts_.scene.impact;
    auto &S = result.impact;
    const double t_end = end_time(S.contact_period);
    const auto failed = [&]() {
      result.wall_time = model_.elapsed();
      result.field_files = parts_.fields.files(false);
      return false;
    };
    SeparationWatch watch;
    parts_.fields.create_directory();
    if (parts_.fields.enabled())
      {
        model_.evaluate_contact_at(0.0);
        parts_.fields.write(0, 0.0);
      }
    const double wall_dynamic_start = model_.elapsed();
    unsigned int step = 0;
    for (; step < I.max_steps && stepper.time() < t_end * (1.0 - 1e-12); ++step)
      {
        DynamicStepRecord rec;
        rec.step = step + 1;
        if (!stepper.step(I.end_time, rec, result.message))
          {
            if (rank_ == 0)
              log::error("fe_stage: " + result.message);
            return failed();
          }
        const double t = stepper.time(), dt_step = rec.time_step, dt = stepper.next_dt();
        const double d = rec.delta, d_rate = rec.delta_rate, F = rec.force;
        rec.wall_time = model_.elapsed();
        result.dynamic_steps.push_back(rec);
        if (F > S.peak_force)
          {
            S.peak_force = F;
            S.time_of_peak = t;
            S.delta_at_peak = d;
            u_peak = stepper.displacement();
            have_peak = true;
          }
        S.delta_max = std::max(S.delta_max, d);
        if (parts_.options.on_dynamic_step)
          parts_.options.on_dynamic_step(rec);
        if (rank_ == 0)
          log_step(rec, t, dt, I.end_time, t_end, S.contact_period, wall_dynamic_start);
        const bool last =
          watch.update(result.dynamic_steps, t, dt_step, dt, S.contact_period, S.separated);
        if (parts_.fields.enabled() && (rec.step % I.field_stride == 0 || last))
          parts_.fields.write(rec.step, t);
        if (last && !S.separated)
          {
            S.separated = true;
            S.contact_duration = watch.contact_end();
            S.velocity_out = -d_rate;
            if (I.end_time == 0.0)  // a given end time is run to (the bearing's vibration)
              break;
          }
      }
    if (step >= I.max_steps && !S.separated && stepper.time() < t_end * (1.0 - 1e-12))
      {
        result.message = "impact.max_steps = " + std::to_string(I.max_steps) +
                         " reached at t = " + format_value(stepper.time()) +
                         " s before the end time";
        return failed();
      }
    return true;
  }

  void ImpactRun::finish(RunResult &result, const HhtStepper &stepper,
                         const TrilinosWrappers::MPI::Vector *u_peak)
  {
    auto &S = result.impact;
    summarise(S, result.dynamic_steps, result.increments, parts_.scene.impact.velocity,
              stepper.numerical_dissipation(), stepper.work_contact());
    if (rank_ == 0)
      log_summary(S);
    if (u_peak)
      {
        parts_.state.u_owned() = *u_peak;
        parts_.state.publish();
        result.yield_check = parts_.fields.check_yield(nullptr);
        parts_.fields.log_yield_check(result.yield_check);
      }
    result.complete = true;
    result.wall_time = model_.elapsed();
    result.field_files = parts_.fields.files(true);
  }
}  // namespace clearjoint::fe::detail
