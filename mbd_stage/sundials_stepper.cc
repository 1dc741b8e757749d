#include "mbd_stage/sundials_stepper.h"

#include "common/error.h"
#include "laws/law_range_error.h"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

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

  SundialsStepper::SundialsStepper(MultibodySystem &system, const IntegratorSettings &settings,
                                   StepStatistics &stats)
    : system_(system)
    , settings_(settings)
    , stats_(stats)
    , erk_(settings.method != IntegratorMethod::bdf)
    , n_gaps_(system.n_gaps())
  {
  }

  SundialsStepper::~SundialsStepper()
  {
    if (mem_)
    {
      if (erk_)
        ERKStepFree(&mem_);
      else
        CVodeFree(&mem_);
    }
    if (LS_)
      SUNLinSolFree(LS_);
    if (A_)
      SUNMatDestroy(A_);
    if (y_)
      N_VDestroy(y_);
    if (atol_)
      N_VDestroy(atol_);
    if (dky_)
      N_VDestroy(dky_);
    if (ctx_)
      SUNContext_Free(&ctx_);
  }

  void SundialsStepper::check(const int flag, const char *what) const
  {
    if (flag < 0)
      throw NumericalError(std::string(erk_ ? "ARKODE " : "CVODE ") + what + " failed: " +
                           flag_name(erk_, flag) +
                           (pending_error_.empty() ? "" : " (" + pending_error_ + ")"));
  }

  // ---- the depth guard ---------------------------------------------------------------------

  double SundialsStepper::allowance(const int i, const double delta) const
  {
    // max(D, δ + D/2), D = depth_guard·c_r of its joint (the same rule as
    // ClearanceJoint::guard_step).
    const double D =
      settings_.depth_guard * system_.clearance_joints()[i / 3]->geometry().c_r();
    return std::max(D, delta + 0.5 * D);
  }

  double SundialsStepper::guard_step(const double *y) const
  {
    return system_.guard_step(y, settings_.depth_guard, accel_.empty() ? nullptr : accel_.data());
  }

  void SundialsStepper::update_accel(const double t, const double *y)
  {
    const std::vector<double> rates = system_.contact_rates(y);
    if (prev_rates_.size() == rates.size() && t > prev_t_)
    {
      accel_.resize(rates.size());
      for (std::size_t i = 0; i < rates.size(); ++i)
        accel_[i] = (rates[i] - prev_rates_[i]) / (t - prev_t_);
    }
    prev_rates_ = rates;
    prev_t_ = t;
  }

  void SundialsStepper::update_allowances()
  {
    if (erk_ || n_gaps_ == 0 || !(settings_.depth_guard > 0.0))
      return;
    allowed_depth_.resize(static_cast<std::size_t>(n_gaps_));
    g_scratch_.resize(static_cast<std::size_t>(n_gaps_));
    system_.gaps(y(), g_scratch_.data());
    for (int i = 0; i < n_gaps_; ++i)
      allowed_depth_[i] = allowance(i, g_scratch_[i]);
  }

  // ---- SUNDIALS' callbacks: exceptions become return flags ---------------------------------

  int SundialsStepper::stability(N_Vector y, realtype t, realtype *hstab, void *user)
  {
    auto *self = static_cast<SundialsStepper *>(user);
    try
    {
      self->update_accel(t, N_VGetArrayPointer(y));
      const double h = self->guard_step(N_VGetArrayPointer(y));
      *hstab = std::isfinite(h) ? h : -1.0;  // ≤ 0: no bound
      return 0;
    }
    catch (const std::exception &e)
    {
      self->pending_error_ = e.what();
      self->pending_fatal_ = true;
      return -1;
    }
  }

  int SundialsStepper::rhs(realtype t, N_Vector y, N_Vector ydot, void *user)
  {
    auto *self = static_cast<SundialsStepper *>(user);
    try
    {
      // CVODE (BDF) retries a step with a smaller size after a recoverable failure: the depth
      // guard rejects any stage deeper than the allowance. (ARKODE's explicit stepper has
      // no such retry; there the guard bounds the step size instead, see stability().)
      if (!self->erk_ && !self->allowed_depth_.empty())
      {
        self->g_scratch_.resize(self->allowed_depth_.size());
        self->system_.gaps(N_VGetArrayPointer(y), self->g_scratch_.data());
        for (std::size_t i = 0; i < self->allowed_depth_.size(); ++i)
          if (self->g_scratch_[i] > self->allowed_depth_[i])
            return 1;
      }
      self->system_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    }
    catch (const laws::LawRangeError &e)
    {
      self->pending_error_ = e.what();
      self->pending_fatal_ = true;
      return -1;  // the scene asked for "error" outside the law's range: stop
    }
    catch (const NumericalError &e)
    {
      self->pending_error_ = e.what();
      return 1;  // recoverable: the integrator retries with a smaller step
    }
    catch (const std::exception &e)
    {
      self->pending_error_ = e.what();
      self->pending_fatal_ = true;
      return -1;
    }
  }

  int SundialsStepper::roots(realtype, N_Vector y, realtype *g, void *user)
  {
    auto *self = static_cast<SundialsStepper *>(user);
    try
    {
      self->system_.gaps(N_VGetArrayPointer(y), g);
      return 0;
    }
    catch (const std::exception &e)
    {
      self->pending_error_ = e.what();
      self->pending_fatal_ = true;
      return -1;
    }
  }

  // ---- creation and restart ----------------------------------------------------------------

  void SundialsStepper::make_vectors()
  {
    const int n = system_.n_states(), nb = system_.n_bodies();
    if (SUNContext_Create(nullptr, &ctx_) != 0)
      throw NumericalError("SUNContext_Create failed");
    y_ = N_VNew_Serial(n, ctx_);
    atol_ = N_VNew_Serial(n, ctx_);
    dky_ = N_VNew_Serial(n, ctx_);
    if (!y_ || !atol_ || !dky_)
      throw NumericalError("N_VNew_Serial failed");
    double *yp = N_VGetArrayPointer(y_), *ap = N_VGetArrayPointer(atol_);
    const Eigen::VectorXd &y0 = system_.initial_state();
    // State layout per body (MultibodySystem): 7 positions (r, e), then 6 velocities; the
    // work states last.
    for (int i = 0; i < n; ++i)
    {
      yp[i] = y0[i];
      ap[i] = i < 7 * nb ? settings_.atol_position
                         : (i < 13 * nb ? settings_.atol_velocity : settings_.atol_work);
    }
  }

  double *SundialsStepper::y() const { return N_VGetArrayPointer(y_); }

  void SundialsStepper::create_erk(const double t_start)
  {
    mem_ = ERKStepCreate(&SundialsStepper::rhs, t_start, y_, ctx_);
    if (!mem_)
      throw NumericalError("ERKStepCreate failed");
    const ARKODE_ERKTableID table =
      settings_.method == IntegratorMethod::verner6     ? ARKODE_VERNER_8_5_6
      : settings_.method == IntegratorMethod::fehlberg8 ? ARKODE_FEHLBERG_13_7_8
                                                        : ARKODE_DORMAND_PRINCE_7_4_5;
    check(ERKStepSetTableNum(mem_, table), "SetTableNum");
    // Cubic Hermite dense output (root finding, output rows, peak samples). ARKODE's
    // default for DP5 is degree 4, which costs extra right-hand sides in every step
    // that is interpolated — here every step (root functions, output rows every
    // 1e-5 s): 36 502 instead of 15 238 for the damped FE scene at rtol 1e-10, and its
    // slider velocity was no closer to the rtol 1e-12 run (9.4e-5 against 3.6e-5 m/s
    // over 0–20 ms; docs/benchmarks.md).
    check(ERKStepSetInterpolantDegree(mem_, settings_.interpolant_degree),
          "SetInterpolantDegree");
    check(ERKStepSetUserData(mem_, this), "SetUserData");
    check(ERKStepSVtolerances(mem_, settings_.rtol, atol_), "SVtolerances");
    check(ERKStepSetMaxNumSteps(mem_, settings_.max_num_steps), "SetMaxNumSteps");
    if (settings_.max_step > 0.0)
      check(ERKStepSetMaxStep(mem_, settings_.max_step), "SetMaxStep");
    if (n_gaps_ > 0)
    {
      check(ERKStepRootInit(mem_, n_gaps_, &SundialsStepper::roots), "RootInit");
      check(ERKStepSetNoInactiveRootWarn(mem_), "SetNoInactiveRootWarn");
      if (settings_.depth_guard > 0.0)
      {
        // The depth guard enters ARKODE's step-size choice as an explicit-stability
        // bound; ARKODE takes half of it (its default CFL fraction 0.5), a margin for
        // the curvature the linear prediction in guard_step() ignores.
        check(ERKStepSetStabilityFn(mem_, &SundialsStepper::stability, this), "SetStabilityFn");
      }
    }
  }

  void SundialsStepper::create_cvode(const double t_start)
  {
    const int n = system_.n_states();
    mem_ = CVodeCreate(CV_BDF, ctx_);
    if (!mem_)
      throw NumericalError("CVodeCreate failed");
    check(CVodeInit(mem_, &SundialsStepper::rhs, t_start, y_), "Init");
    check(CVodeSetUserData(mem_, this), "SetUserData");
    check(CVodeSVtolerances(mem_, settings_.rtol, atol_), "SVtolerances");
    A_ = SUNDenseMatrix(n, n, ctx_);
    LS_ = SUNLinSol_Dense(y_, A_, ctx_);
    if (!A_ || !LS_)
      throw NumericalError("dense linear solver creation failed");
    check(CVodeSetLinearSolver(mem_, LS_, A_), "SetLinearSolver");
    check(CVodeSetMaxNumSteps(mem_, settings_.max_num_steps), "SetMaxNumSteps");
    if (settings_.max_step > 0.0)
      check(CVodeSetMaxStep(mem_, settings_.max_step), "SetMaxStep");
    if (n_gaps_ > 0)
    {
      check(CVodeRootInit(mem_, n_gaps_, &SundialsStepper::roots), "RootInit");
      check(CVodeSetNoInactiveRootWarn(mem_), "SetNoInactiveRootWarn");
    }
  }

  void SundialsStepper::start(const double t_start, const double t_end, const double h_restart)
  {
    if (erk_)
    {
      if (!mem_)
        create_erk(t_start);
      else
      {
        check(ERKStepReInit(mem_, &SundialsStepper::rhs, t_start, y_), "ReInit");
        // Restart with a tenth of the last accepted step instead of SUNDIALS' estimate from
        // scratch (~1e-13 s here, then ~10 steps to grow back); the error test still rejects
        // a first step that is too long.
        if (h_restart > 0.0)
          check(ERKStepSetInitStep(mem_, std::min(h_restart, guard_step(y()))), "SetInitStep");
      }
      check(ERKStepSetStopTime(mem_, t_end), "SetStopTime");
    }
    else
    {
      if (!mem_)
        create_cvode(t_start);
      else
      {
        check(CVodeReInit(mem_, t_start, y_), "ReInit");
        if (h_restart > 0.0)
          check(CVodeSetInitStep(mem_, std::min(h_restart, guard_step(y()))), "SetInitStep");
      }
      check(CVodeSetStopTime(mem_, t_end), "SetStopTime");
    }
  }

  // ---- stepping ----------------------------------------------------------------------------

  SundialsStepper::Step SundialsStepper::step(const double t_end)
  {
    Step s;
    s.flag = erk_ ? ERKStepEvolve(mem_, t_end, y_, &s.t_reached, ARK_ONE_STEP)
                  : CVode(mem_, t_end, y_, &s.t_reached, CV_ONE_STEP);
    if (s.flag < 0)
    {
      add_counters();
      check(s.flag, erk_ ? "ERKStepEvolve" : "CVode");
    }
    s.at_root = erk_ ? s.flag == ARK_ROOT_RETURN : s.flag == CV_ROOT_RETURN;
    return s;
  }

  double SundialsStepper::last_step_size() const
  {
    double h_last = 0.0;
    check(erk_ ? ERKStepGetLastStep(mem_, &h_last) : CVodeGetLastStep(mem_, &h_last),
          "GetLastStep");
    return h_last;
  }

  const double *SundialsStepper::state_at(const double t) const
  {
    check(erk_ ? ERKStepGetDky(mem_, t, 0, dky_) : CVodeGetDky(mem_, t, 0, dky_), "GetDky");
    return N_VGetArrayPointer(dky_);
  }

  void SundialsStepper::root_directions(std::vector<int> &found) const
  {
    check(erk_ ? ERKStepGetRootInfo(mem_, found.data()) : CVodeGetRootInfo(mem_, found.data()),
          "GetRootInfo");
  }

  void SundialsStepper::recompute_state_at_root(const double t_step_start,
                                                const Eigen::VectorXd &y_step_start,
                                                const double t_root)
  {
    Eigen::Map<Eigen::VectorXd>(y(), system_.n_states()) = y_step_start;
    check(ERKStepReInit(mem_, &SundialsStepper::rhs, t_step_start, y_), "ReInit");
    check(ERKStepRootInit(mem_, 0, nullptr), "RootInit");
    check(ERKStepSetFixedStep(mem_, t_root - t_step_start), "SetFixedStep");
    check(ERKStepSetStopTime(mem_, t_root), "SetStopTime");
    double t_exact = t_step_start;
    const int f = ERKStepEvolve(mem_, t_root, y_, &t_exact, ARK_NORMAL);
    if (f < 0)
    {
      add_counters();
      check(f, "ERKStepEvolve (state at an event)");
    }
    // (its step and right-hand sides are counted with the restart that follows)
    check(ERKStepSetFixedStep(mem_, 0.0), "SetFixedStep");
    check(ERKStepRootInit(mem_, n_gaps_, &SundialsStepper::roots), "RootInit");
    check(ERKStepSetNoInactiveRootWarn(mem_), "SetNoInactiveRootWarn");
  }

  void SundialsStepper::add_counters()
  {
    long ns = 0, nf = 0, ne = 0, nj = 0, nn = 0;
    if (erk_)
    {
      long nfe = 0;
      check(ERKStepGetNumSteps(mem_, &ns), "GetNumSteps");
      check(ERKStepGetNumRhsEvals(mem_, &nfe), "GetNumRhsEvals");
      check(ERKStepGetNumErrTestFails(mem_, &ne), "GetNumErrTestFails");
      nf = nfe;
    }
    else
    {
      check(CVodeGetNumSteps(mem_, &ns), "GetNumSteps");
      check(CVodeGetNumRhsEvals(mem_, &nf), "GetNumRhsEvals");
      check(CVodeGetNumErrTestFails(mem_, &ne), "GetNumErrTestFails");
      check(CVodeGetNumJacEvals(mem_, &nj), "GetNumJacEvals");
      check(CVodeGetNumNonlinSolvConvFails(mem_, &nn), "GetNumNonlinSolvConvFails");
    }
    stats_.n_steps += ns;
    stats_.n_rhs += nf;
    stats_.n_error_test_failures += ne;
    stats_.n_jacobians += nj;
    stats_.n_nonlinear_failures += nn;
  }
} // namespace clearjoint::mbd
