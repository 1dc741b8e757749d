// Time integration with SUNDIALS, with root finding on the contact gap functions.
//   dopri5:  ARKODE ERKStep, Dormand–Prince 5(4) (MATLAB's ode45, as in the paper), optional max step
//   verner6: ARKODE ERKStep, Verner 6(5), 8 stages (ARKODE_VERNER_8_5_6)
//   fehlberg8: ARKODE ERKStep, Fehlberg 8(7), 13 stages (ARKODE_FEHLBERG_13_7_8)
//   bdf:    CVODE variable-order BDF with a dense direct linear solver (stiff contact)
// Contact onset and release are located as roots of g = δ (SPEC §4): the contact force has a
// kink at onset (δ^n, n ≈ 1), so the discrete contact mode is frozen within a step, switched
// exactly at the root (where δ̇⁻ is recorded), and the integrator is restarted there. A long
// free-flight step that would land deep inside the bearing cannot happen: with the mode frozen
// the motion in that step is free flight, and the step is cut back at the root.
// Every SUNDIALS return flag is checked; a failure throws NumericalError naming the flag.
// SUNDIALS itself is driven through sundials_stepper.h; run() holds the contact logic.
#pragma once

#include "mbd_stage/multibody_system.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace clearjoint::mbd
{
  class SundialsStepper;  // sundials_stepper.h, private to integrator.cc

  enum class IntegratorMethod
  {
    dopri5,
    verner6,
    fehlberg8,
    bdf,
  };
  IntegratorMethod parse_integrator_method(const std::string &name);
  /// Names accepted by parse_integrator_method (the scene's integrator.method).
  inline const std::vector<std::string> &integrator_method_names()
  {
    static const std::vector<std::string> names{"dopri5", "verner6", "fehlberg8", "bdf"};
    return names;
  }

  struct IntegratorSettings
  {
    IntegratorMethod method = IntegratorMethod::dopri5;
    // The shipped scenes' values (docs/mbd.md §5 says why).
    double rtol = 1e-11;          ///< [1] relative tolerance
    double atol_position = 1e-13; ///< [m] absolute tolerance of positions (and [1] of e)
    double atol_velocity = 1e-10; ///< [m/s] absolute tolerance of velocities (rad/s alike)
    double atol_work = 1e-8;      ///< [J] absolute tolerance of the work states
    double max_step = 0.0;        ///< [s] 0: no limit
    long max_num_steps = 50000000;
    /// [1] depth guard, as a fraction of the radial clearance c_r: a step may take a contact
    /// at most to max(guard·c_r, δ_accepted + guard·c_r/2) deep (see Integrator::run).
    double depth_guard = 0.1;
    int n_step_samples = 8;       ///< samples per step while in contact (peak tracking)
    int interpolant_degree = 3;   ///< Hermite dense output, explicit methods (sundials_stepper.cc)
  };

  struct ContactEvent
  {
    double t = 0.0;              ///< [s]
    std::string joint;
    int contact = 0;             ///< 0 radial, 1 axial +, 2 axial −
    bool onset = true;           ///< false: release
    double delta_dot = 0.0;      ///< [m/s] δ̇ at the event (δ̇⁻ for an onset)
  };

  struct StepStatistics
  {
    long n_steps = 0, n_rhs = 0, n_error_test_failures = 0, n_restarts = 0, n_roots = 0;
    /// Explicit methods: steps that recomputed the state at an event from its step's start
    /// (included in n_steps and n_rhs).
    long n_event_resteps = 0;
    long n_jacobians = 0, n_nonlinear_failures = 0;
    double h_min = 0.0, h_max = 0.0;  ///< [s] smallest and largest accepted step
  };

  class Integrator
  {
  public:
    Integrator(MultibodySystem &system, IntegratorSettings settings);
    ~Integrator();
    Integrator(const Integrator &) = delete;
    Integrator &operator=(const Integrator &) = delete;

    using OutputCallback = std::function<void(double, const Eigen::VectorXd &)>;
    using StepCallback = std::function<void(double, const Eigen::VectorXd &, bool interior)>;

    /// Integrates from t0 to t_end. `on_output(t, y)` is called at t0 and at every multiple of
    /// output_interval (dense output), and `on_step(t, y, false)` after every accepted step — and
    /// (with interior = true) at n_step_samples − 1 interior points (dense output) of each step in
    /// which an active contact turns from compression to restitution, so the peak contact force
    /// is not missed between step ends.
    void run(double t0, double t_end, double output_interval, const OutputCallback &on_output,
             const StepCallback &on_step = {});

    const StepStatistics &statistics() const { return stats_; }
    const std::vector<ContactEvent> &events() const { return events_; }
    static std::string method_name(IntegratorMethod m);

  private:
    /// Keeps the accepted step size h_last [s] in the statistics (h_min, h_max) and makes a
    /// tenth of it the initial step of the next restart.
    void record_step_size(double h_last, double &h_restart);
    /// Calls on_step(…, interior = true) at n_step_samples − 1 points inside the step
    /// (t, t_reached).
    void sample_step(double t, double t_reached, const StepCallback &on_step);

    MultibodySystem &system_;
    IntegratorSettings settings_;
    StepStatistics stats_;
    std::vector<ContactEvent> events_;
    std::unique_ptr<SundialsStepper> stepper_;  // after settings_ and stats_: it refers to them
  };
} // namespace clearjoint::mbd
