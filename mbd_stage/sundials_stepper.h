// One interface over the two SUNDIALS integrators of the MBD stage — ARKODE's explicit ERKStep
// (dopri5, verner6, fehlberg8) and CVODE's BDF — that Integrator::run drives one step at a
// time: the state vector, creation and restart, one step with root finding on the contact gaps,
// dense output, the root directions, the exact state at an event, and SUNDIALS' counters. The
// contacts' depth guard enters here: ARKODE's step-size choice through a stability bound, CVODE's
// right-hand side by rejecting stages deeper than the allowance (see Integrator::run).
// Every SUNDIALS return flag is checked; a failure throws NumericalError naming the flag (and
// the message of an exception a callback caught). Private to integrator.cc.
#pragma once

#include "mbd_stage/integrator.h"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  class SundialsStepper
  {
  public:
    /// `stats` receives SUNDIALS' counters (steps, right-hand sides, error-test failures,
    /// Jacobians, nonlinear failures), added up over restarts.
    SundialsStepper(MultibodySystem &system, const IntegratorSettings &settings,
                    StepStatistics &stats);
    ~SundialsStepper();
    SundialsStepper(const SundialsStepper &) = delete;
    SundialsStepper &operator=(const SundialsStepper &) = delete;

    /// True for the ARKODE methods, false for CVODE's BDF.
    bool is_explicit() const { return erk_; }
    /// Makes the context and vectors: y = the system's initial state, and the absolute
    /// tolerances of positions, velocities and work states.
    void make_vectors();
    /// The state SUNDIALS advances (n_states values; valid for the stepper's lifetime).
    double *y() const;
    /// The first call creates the integrator at t_start; later calls restart it there from
    /// y() — with an initial step of min(h_restart, depth-guard step) when h_restart > 0,
    /// else SUNDIALS' own estimate. It stops at t_end.
    void start(double t_start, double t_end, double h_restart);

    struct Step
    {
      int flag = 0;            ///< SUNDIALS' return flag (≥ 0)
      double t_reached = 0.0;  ///< [s]
      bool at_root = false;    ///< the step ended at a root of a gap function
    };
    /// One step towards t_end (at most to a root).
    Step step(double t_end);
    /// [s] the size of the last accepted step.
    double last_step_size() const;
    /// The dense output at t (inside the last step); valid until the next call.
    const double *state_at(double t) const;
    /// Per gap function: +1 a root crossed upwards (onset), −1 downwards (release), 0 none.
    void root_directions(std::vector<int> &found) const;
    /// Explicit methods: replaces y() at the root t_root by one step of the method of length
    /// t_root − t_step_start from the step's start state (y_step_start), with root finding
    /// off; see Integrator::run for why.
    void recompute_state_at_root(double t_step_start, const Eigen::VectorXd &y_step_start,
                                 double t_root);
    /// Adds SUNDIALS' counters since the last (re)start to the statistics. Call before every
    /// restart (which resets them) and at the end.
    void add_counters();
    /// BDF: the depth each contact may reach in the next step, from the accepted state y().
    void update_allowances();

  private:
    void create_erk(double t_start);
    void create_cvode(double t_start);
    void check(int flag, const char *what) const;

    /// Depth allowance of contact i given its accepted penetration δ [m].
    double allowance(int i, double delta) const;
    double guard_step(const double *y) const;
    void update_accel(double t, const double *y);

    static int rhs(realtype t, N_Vector y, N_Vector ydot, void *user);
    static int roots(realtype t, N_Vector y, realtype *g, void *user);
    static int stability(N_Vector y, realtype t, realtype *hstab, void *user);

    MultibodySystem &system_;
    const IntegratorSettings &settings_;
    StepStatistics &stats_;
    bool erk_ = true;
    int n_gaps_ = 0;

    SUNContext ctx_ = nullptr;
    N_Vector y_ = nullptr, atol_ = nullptr, dky_ = nullptr;
    SUNMatrix A_ = nullptr;
    SUNLinearSolver LS_ = nullptr;
    void *mem_ = nullptr;

    std::string pending_error_;  // message of an exception thrown inside a callback
    bool pending_fatal_ = false;
    std::vector<double> allowed_depth_;  // [m] per contact, from the last accepted state (BDF)
    std::vector<double> g_scratch_;
    // δ̈ estimates for the guard: the change of δ̇ over the last accepted step.
    std::vector<double> accel_, prev_rates_;
    double prev_t_ = 0.0;
  };
} // namespace clearjoint::mbd
