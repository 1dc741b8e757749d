#include "mbd_stage/integrator.h"

#include "common/error.h"
#include "laws/law_range_error.h"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

namespace clearjoint::mbd
{
  namespace
  {
    std::string flag_name(const bool erk, const int flag)
    {
      char *s = erk ? ERKStepGetReturnFlagName(flag) : CVodeGetReturnFlagName(flag);
      std::string out = s ? s : std::to_string(flag);
      std::free(s);
      return out;
    }
  } // namespace

  struct Integrator::Impl
  {
    MultibodySystem *system = nullptr;
    bool erk = true;
    SUNContext ctx = nullptr;
    N_Vector y = nullptr, atol = nullptr, dky = nullptr;
    SUNMatrix A = nullptr;
    SUNLinearSolver LS = nullptr;
    void *mem = nullptr;
    std::string pending_error;   // message of an exception thrown inside a callback
    bool pending_fatal = false;
    double depth_guard = 0.1;          // [1] fraction of c_r (IntegratorSettings::depth_guard)
    std::vector<double> allowed_depth;  // [m] per contact, from the last accepted state (BDF)
    std::vector<double> g_scratch;

    /// Depth allowance of contact i given its accepted penetration δ [m]: max(D, δ + D/2),
    /// D = depth_guard·c_r of its joint (the same rule as ClearanceJoint::guard_step).
    double allowance(const int i, const double delta) const
    {
      const double D = depth_guard * system->clearance_joints()[i / 3]->geometry().c_r();
      return std::max(D, delta + 0.5 * D);
    }

    double guard_step(const double *y) const
    {
      return system->guard_step(y, depth_guard, accel.empty() ? nullptr : accel.data());
    }
    // δ̈ estimates for the guard: the change of δ̇ over the last accepted step.
    std::vector<double> accel, prev_rates;
    double prev_t = 0.0;
    void update_accel(const double t, const double *y)
    {
      const std::vector<double> rates = system->contact_rates(y);
      if (prev_rates.size() == rates.size() && t > prev_t)
      {
        accel.resize(rates.size());
        for (std::size_t i = 0; i < rates.size(); ++i)
          accel[i] = (rates[i] - prev_rates[i]) / (t - prev_t);
      }
      prev_rates = rates;
      prev_t = t;
    }

    static int stability(N_Vector y, realtype t, realtype *hstab, void *user)
    {
      auto *self = static_cast<Impl *>(user);
      try
      {
        self->update_accel(t, N_VGetArrayPointer(y));
        const double h = self->guard_step(N_VGetArrayPointer(y));
        *hstab = std::isfinite(h) ? h : -1.0;  // ≤ 0: no bound
        return 0;
      }
      catch (const std::exception &e)
      {
        self->pending_error = e.what();
        self->pending_fatal = true;
        return -1;
      }
    }

    void check(const int flag, const char *what) const
    {
      if (flag < 0)
        throw NumericalError(std::string(erk ? "ARKODE " : "CVODE ") + what + " failed: " +
                             flag_name(erk, flag) +
                             (pending_error.empty() ? "" : " (" + pending_error + ")"));
    }

    static int rhs(realtype t, N_Vector y, N_Vector ydot, void *user)
    {
      auto *self = static_cast<Impl *>(user);
      try
      {
        // CVODE (BDF) retries a step with a smaller size after a recoverable failure: the depth
        // guard rejects any stage deeper than the allowance. (ARKODE's explicit stepper has
        // no such retry; there the guard bounds the step size instead, see stability().)
        if (!self->erk && !self->allowed_depth.empty())
        {
          self->g_scratch.resize(self->allowed_depth.size());
          self->system->gaps(N_VGetArrayPointer(y), self->g_scratch.data());
          for (std::size_t i = 0; i < self->allowed_depth.size(); ++i)
            if (self->g_scratch[i] > self->allowed_depth[i])
              return 1;
        }
        self->system->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
        return 0;
      }
      catch (const laws::LawRangeError &e)
      {
        self->pending_error = e.what();
        self->pending_fatal = true;
        return -1;  // the scene asked for "error" outside the law's range: stop
      }
      catch (const NumericalError &e)
      {
        self->pending_error = e.what();
        return 1;  // recoverable: the integrator retries with a smaller step
      }
      catch (const std::exception &e)
      {
        self->pending_error = e.what();
        self->pending_fatal = true;
        return -1;
      }
    }

    static int roots(realtype, N_Vector y, realtype *g, void *user)
    {
      auto *self = static_cast<Impl *>(user);
      try
      {
        self->system->gaps(N_VGetArrayPointer(y), g);
        return 0;
      }
      catch (const std::exception &e)
      {
        self->pending_error = e.what();
        self->pending_fatal = true;
        return -1;
      }
    }

    ~Impl()
    {
      if (mem)
      {
        if (erk)
          ERKStepFree(&mem);
        else
          CVodeFree(&mem);
      }
      if (LS)
        SUNLinSolFree(LS);
      if (A)
        SUNMatDestroy(A);
      if (y)
        N_VDestroy(y);
      if (atol)
        N_VDestroy(atol);
      if (dky)
        N_VDestroy(dky);
      if (ctx)
        SUNContext_Free(&ctx);
    }
  };

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
    : impl_(new Impl)
    , system_(system)
    , settings_(settings)
  {
    impl_->system = &system;
    impl_->erk = settings.method != IntegratorMethod::bdf;
    impl_->depth_guard = settings.depth_guard;
  }

  Integrator::~Integrator() { delete impl_; }

  void Integrator::run(const double t0, const double t_end, const double output_interval,
                       const std::function<void(double, const Eigen::VectorXd &)> &on_output,
                       const std::function<void(double, const Eigen::VectorXd &, bool)> &on_step)
  {
    Impl &m = *impl_;
    const bool erk = m.erk;
    const int n = system_.n_states(), ng = system_.n_gaps(), nb = system_.n_bodies();
    if (SUNContext_Create(nullptr, &m.ctx) != 0)
      throw NumericalError("SUNContext_Create failed");
    m.y = N_VNew_Serial(n, m.ctx);
    m.atol = N_VNew_Serial(n, m.ctx);
    m.dky = N_VNew_Serial(n, m.ctx);
    if (!m.y || !m.atol || !m.dky)
      throw NumericalError("N_VNew_Serial failed");
    double *yp = N_VGetArrayPointer(m.y), *ap = N_VGetArrayPointer(m.atol);
    const Eigen::VectorXd &y0 = system_.initial_state();
    for (int i = 0; i < n; ++i)
    {
      yp[i] = y0[i];
      ap[i] = i < 7 * nb ? settings_.atol_position
                         : (i < 13 * nb ? settings_.atol_velocity : settings_.atol_work);
    }

    double h_restart = 0.0;  // [s] initial step after a restart (0: SUNDIALS' estimate)
    const auto create = [&](const double t_start) {
      if (erk)
      {
        if (!m.mem)
        {
          m.mem = ERKStepCreate(&Impl::rhs, t_start, m.y, m.ctx);
          if (!m.mem)
            throw NumericalError("ERKStepCreate failed");
          const ARKODE_ERKTableID table =
            settings_.method == IntegratorMethod::verner6     ? ARKODE_VERNER_8_5_6
            : settings_.method == IntegratorMethod::fehlberg8 ? ARKODE_FEHLBERG_13_7_8
                                                              : ARKODE_DORMAND_PRINCE_7_4_5;
          m.check(ERKStepSetTableNum(m.mem, table), "SetTableNum");
          // Cubic Hermite dense output (root finding, output rows, peak samples). ARKODE's
          // default for DP5 is degree 4, which costs extra right-hand sides in every step
          // that is interpolated — here every step (root functions, output rows every
          // 1e-5 s): 36 502 instead of 15 238 for the damped FE scene at rtol 1e-10, and its
          // slider velocity was no closer to the rtol 1e-12 run (9.4e-5 against 3.6e-5 m/s
          // over 0–20 ms; docs/benchmarks.md).
          m.check(ERKStepSetInterpolantDegree(m.mem, settings_.interpolant_degree),
                  "SetInterpolantDegree");
          m.check(ERKStepSetUserData(m.mem, &m), "SetUserData");
          m.check(ERKStepSVtolerances(m.mem, settings_.rtol, m.atol), "SVtolerances");
          m.check(ERKStepSetMaxNumSteps(m.mem, settings_.max_num_steps), "SetMaxNumSteps");
          if (settings_.max_step > 0.0)
            m.check(ERKStepSetMaxStep(m.mem, settings_.max_step), "SetMaxStep");
          if (ng > 0)
          {
            m.check(ERKStepRootInit(m.mem, ng, &Impl::roots), "RootInit");
            m.check(ERKStepSetNoInactiveRootWarn(m.mem), "SetNoInactiveRootWarn");
            if (settings_.depth_guard > 0.0)
            {
              // The depth guard enters ARKODE's step-size choice as an explicit-stability
              // bound; ARKODE takes half of it (its default CFL fraction 0.5), a margin for
              // the curvature the linear prediction in guard_step() ignores.
              m.check(ERKStepSetStabilityFn(m.mem, &Impl::stability, &m), "SetStabilityFn");
            }
          }
        }
        else
        {
          m.check(ERKStepReInit(m.mem, &Impl::rhs, t_start, m.y), "ReInit");
          // Restart with a tenth of the last accepted step instead of SUNDIALS' estimate from
          // scratch (~1e-13 s here, then ~10 steps to grow back); the error test still rejects
          // a first step that is too long.
          if (h_restart > 0.0)
            m.check(ERKStepSetInitStep(m.mem, std::min(h_restart, m.guard_step(yp))),
                    "SetInitStep");
        }
        m.check(ERKStepSetStopTime(m.mem, t_end), "SetStopTime");
      }
      else
      {
        if (!m.mem)
        {
          m.mem = CVodeCreate(CV_BDF, m.ctx);
          if (!m.mem)
            throw NumericalError("CVodeCreate failed");
          m.check(CVodeInit(m.mem, &Impl::rhs, t_start, m.y), "Init");
          m.check(CVodeSetUserData(m.mem, &m), "SetUserData");
          m.check(CVodeSVtolerances(m.mem, settings_.rtol, m.atol), "SVtolerances");
          m.A = SUNDenseMatrix(n, n, m.ctx);
          m.LS = SUNLinSol_Dense(m.y, m.A, m.ctx);
          if (!m.A || !m.LS)
            throw NumericalError("dense linear solver creation failed");
          m.check(CVodeSetLinearSolver(m.mem, m.LS, m.A), "SetLinearSolver");
          m.check(CVodeSetMaxNumSteps(m.mem, settings_.max_num_steps), "SetMaxNumSteps");
          if (settings_.max_step > 0.0)
            m.check(CVodeSetMaxStep(m.mem, settings_.max_step), "SetMaxStep");
          if (ng > 0)
          {
            m.check(CVodeRootInit(m.mem, ng, &Impl::roots), "RootInit");
            m.check(CVodeSetNoInactiveRootWarn(m.mem), "SetNoInactiveRootWarn");
          }
        }
        else
        {
          m.check(CVodeReInit(m.mem, t_start, m.y), "ReInit");
          if (h_restart > 0.0)
            m.check(CVodeSetInitStep(m.mem, std::min(h_restart, m.guard_step(yp))),
                    "SetInitStep");
        }
        m.check(CVodeSetStopTime(m.mem, t_end), "SetStopTime");
      }
    };

    // Statistics accumulate over restarts (ReInit resets SUNDIALS' counters).
    const auto harvest = [&]() {
      long ns = 0, nf = 0, ne = 0, nj = 0, nn = 0;
      if (erk)
      {
        long nfe = 0;
        m.check(ERKStepGetNumSteps(m.mem, &ns), "GetNumSteps");
        m.check(ERKStepGetNumRhsEvals(m.mem, &nfe), "GetNumRhsEvals");
        m.check(ERKStepGetNumErrTestFails(m.mem, &ne), "GetNumErrTestFails");
        nf = nfe;
      }
      else
      {
        m.check(CVodeGetNumSteps(m.mem, &ns), "GetNumSteps");
        m.check(CVodeGetNumRhsEvals(m.mem, &nf), "GetNumRhsEvals");
        m.check(CVodeGetNumErrTestFails(m.mem, &ne), "GetNumErrTestFails");
        m.check(CVodeGetNumJacEvals(m.mem, &nj), "GetNumJacEvals");
        m.check(CVodeGetNumNonlinSolvConvFails(m.mem, &nn), "GetNumNonlinSolvConvFails");
      }
      stats_.n_steps += ns;
      stats_.n_rhs += nf;
      stats_.n_error_test_failures += ne;
      stats_.n_jacobians += nj;
      stats_.n_nonlinear_failures += nn;
    };

    const auto update_allowances = [&]() {
      if (erk || ng == 0 || !(settings_.depth_guard > 0.0))
        return;
      m.allowed_depth.resize(static_cast<std::size_t>(ng));
      m.g_scratch.resize(static_cast<std::size_t>(ng));
      system_.gaps(yp, m.g_scratch.data());
      for (int i = 0; i < ng; ++i)
        m.allowed_depth[i] = m.allowance(i, m.g_scratch[i]);
    };
    update_allowances();
    create(t0);
    stats_ = StepStatistics{};
    stats_.h_min = std::numeric_limits<double>::infinity();
    Eigen::VectorXd y_out(n);
    const auto emit = [&](const double t, const double *src) {
      for (int i = 0; i < n; ++i)
        y_out[i] = src[i];
      on_output(t, y_out);
    };
    emit(t0, yp);
    long k_out = 1;
    const auto next_output = [&]() { return t0 + static_cast<double>(k_out) * output_interval; };
    double t = t0;
    const double t_eps = 1e-12 * std::max(1.0, std::abs(t_end));
    std::vector<int> found(static_cast<std::size_t>(std::max(ng, 1)));
    std::vector<double> rates_prev = system_.contact_rates(yp);

    // The state at the start of the current step: an event's restart state is recomputed from it
    // (see below).
    Eigen::VectorXd y_step_start(n);
    while (t < t_end - t_eps)
    {
      if (erk)
        y_step_start = Eigen::Map<const Eigen::VectorXd>(yp, n);
      const double t_step_start = t;
      double t_reached = t;
      const int flag = erk ? ERKStepEvolve(m.mem, t_end, m.y, &t_reached, ARK_ONE_STEP)
                           : CVode(m.mem, t_end, m.y, &t_reached, CV_ONE_STEP);
      if (flag < 0)
      {
        harvest();
        m.check(flag, erk ? "ERKStepEvolve" : "CVode");
      }
      // Accepted state: law-range counters (and "error"), the allowances of the depth guard.
      system_.observe_accepted(yp, settings_.depth_guard);
      update_allowances();
      // Step size of the last accepted step.
      double h_last = 0.0;
      m.check(erk ? ERKStepGetLastStep(m.mem, &h_last) : CVodeGetLastStep(m.mem, &h_last),
              "GetLastStep");
      if (h_last > 0.0)
      {
        h_restart = 0.1 * h_last;
        stats_.h_min = std::min(stats_.h_min, h_last);
        stats_.h_max = std::max(stats_.h_max, h_last);
      }
      // Dense output at the grid points passed.
      while (next_output() <= t_reached + t_eps && next_output() <= t_end + t_eps)
      {
        const double to = std::min(next_output(), t_reached);
        m.check(erk ? ERKStepGetDky(m.mem, to, 0, m.dky) : CVodeGetDky(m.mem, to, 0, m.dky),
                "GetDky");
        emit(to, N_VGetArrayPointer(m.dky));
        ++k_out;
      }
      if (on_step)
      {
        // Sample the step only where a contact force may peak inside it: an active contact that
        // was in compression (δ̇ > 0) at the start of the step (with damping, the force peaks
        // before the maximum compression).
        const std::vector<double> rates_now = system_.contact_rates(yp);
        bool in_contact = false;
        int ic = 0;
        for (const auto &cj : system_.clearance_joints())
          for (int c = 0; c < ClearanceJoint::n_contacts; ++c, ++ic)
            in_contact = in_contact || (cj->state(c).active && rates_prev.size() == rates_now.size() &&
                                        rates_prev[ic] > 0.0);
        rates_prev = rates_now;
        if (in_contact && settings_.n_step_samples > 1 && t_reached > t)
        {
          Eigen::VectorXd ys(n);
          for (int k = 1; k < settings_.n_step_samples; ++k)
          {
            const double ts = t + (t_reached - t) * k / settings_.n_step_samples;
            m.check(erk ? ERKStepGetDky(m.mem, ts, 0, m.dky) : CVodeGetDky(m.mem, ts, 0, m.dky),
                    "GetDky");
            ys = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(m.dky), n);
            on_step(ts, ys, true);
          }
        }
        Eigen::Map<const Eigen::VectorXd> ys(yp, n);
        on_step(t_reached, ys, false);
      }
      t = t_reached;
      const bool is_root = erk ? flag == ARK_ROOT_RETURN : flag == CV_ROOT_RETURN;
      if (!is_root)
        continue;
      ++stats_.n_roots;
      m.check(erk ? ERKStepGetRootInfo(m.mem, found.data()) : CVodeGetRootInfo(m.mem, found.data()),
              "GetRootInfo");
      bool will_change = false;
      {
        int i = 0;
        for (auto &cj : system_.clearance_joints())
          for (int c = 0; c < ClearanceJoint::n_contacts; ++c, ++i)
            will_change = will_change || (found[i] > 0 && !cj->state(c).active) ||
                          (found[i] < 0 && cj->state(c).active);
      }
      // (A root within 1e-12 s of the step's start is left as interpolated: the interpolant's
      // error vanishes there like (t − t_n)², and ARKODE refuses a stop time that close.)
      if (erk && will_change && t - t_step_start > 1e-12 * std::max(1.0, std::abs(t)))
      {
        // ARKODE returns the state at the root from its dense output (cubic Hermite here, error
        // O(h^4) over the whole step), and the integrator restarts from that state: every event
        // would inject the interpolant's error into the trajectory — at the defaults a 3e-9 s
        // shift of one impact of the frictionless FE scene, 2.2e-4 m/s of slider velocity by
        // 19 ms (docs/benchmarks.md). So the state at the root is recomputed by one DP5 step
        // from the start of the step that found it, with the contact modes still those of that
        // step, and of length t_root − t_n ≤ the accepted step (whose error test it passed).
        harvest();
        Eigen::Map<Eigen::VectorXd>(yp, n) = y_step_start;
        m.check(ERKStepReInit(m.mem, &Impl::rhs, t_step_start, m.y), "ReInit");
        m.check(ERKStepRootInit(m.mem, 0, nullptr), "RootInit");
        m.check(ERKStepSetFixedStep(m.mem, t - t_step_start), "SetFixedStep");
        m.check(ERKStepSetStopTime(m.mem, t), "SetStopTime");
        double t_exact = t_step_start;
        const int f = ERKStepEvolve(m.mem, t, m.y, &t_exact, ARK_NORMAL);
        if (f < 0)
        {
          harvest();
          m.check(f, "ERKStepEvolve (state at an event)");
        }
        // (its step and right-hand sides are harvested with the restart below)
        m.check(ERKStepSetFixedStep(m.mem, 0.0), "SetFixedStep");
        m.check(ERKStepRootInit(m.mem, ng, &Impl::roots), "RootInit");
        m.check(ERKStepSetNoInactiveRootWarn(m.mem), "SetNoInactiveRootWarn");
        ++stats_.n_event_resteps;
      }
      const std::vector<double> rates = system_.contact_rates(yp);
      bool changed = false;
      int i = 0;
      for (auto &cj : system_.clearance_joints())
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
            events_.push_back({t, cj->name(), c, true, rates[i]});
            changed = true;
          }
          else if (found[i] < 0 && s.active)
          {
            s.active = false;
            events_.push_back({t, cj->name(), c, false, rates[i]});
            changed = true;
          }
        }
      if (changed)
      {
        harvest();
        ++stats_.n_restarts;
        create(t);
      }
    }
    harvest();
    if (!std::isfinite(stats_.h_min))
      stats_.h_min = 0.0;
  }
} // namespace clearjoint::mbd
