// The journal's spin as one more Newton unknown (solve/spin_stepper.h, rolling.spin_solver
// bordered or coupled): what the iteration on the torque balance
//   g(γ̇) = (I (γ̇ − γ̇_n)/Δt − M(γ̇)) / scale = 0
// carries from one material Newton iteration to the next within an attempt at a step — its
// slope dg/dγ̇ (the bordered column's, or the iterates' secant, or the last step's), the last
// iterate, and the signs that it will not converge (the bodies' correction growing, the
// balance stalling), on which the root finder takes the step instead. No deal.II: the model's
// solves stay in SpinStepper.
#pragma once

#include <vector>

namespace clearjoint::fe
{
  class SpinBalanceIteration
  {
  public:
    /// `slope_last` [s/rad]: dg/dγ̇ from the last converged step (the coupled iteration's
    /// start; 0 for the bordered one, whose column gives its own).
    explicit SpinBalanceIteration(double slope_last);

    /// The bordered column's slope [s/rad]. M falls as γ̇ rises, so a true slope is positive;
    /// one that is not (a pathological active set) keeps the last one of this attempt. False
    /// when there is none yet: the root finder then takes the step.
    bool take_bordered_slope(double slope);

    /// The coupled iteration: the secant from the last iterate to (rate [rad/s], g), taken
    /// where it is positive and within 0.2–5× the last step's slope, or wherever the bodies
    /// have nearly converged (correction ≤ 100 × tolerance [m]: the balance is then exact).
    void take_secant(double rate, double g, double correction, double tolerance);

    /// [rad/s] The Newton step on the balance: 0 where |g| ≤ 1e-6, else −g / slope, at most
    /// half the rolling rate `roll` [rad/s] (a secant over nearly equal balances — slip under
    /// a small force — could send γ̇ to thousands of rad/s).
    double step(double g, double roll) const;

    /// The bodies converged (correction ≤ tolerance) and the balance holds, or the step is
    /// within 1e-10 of the rolling rate by this attempt's own slope (the root finder's two
    /// tolerances; a step by the last step's slope says nothing about the distance to the root).
    bool converged(double correction, double tolerance, double rate_step, double roll) const;

    enum class Trend
    {
      continues,
      diverges,  // the bodies' correction grew in three iterations running
      stalls     // |g| did not halve over the last four iterations
    };
    /// After an iteration that did not converge: its correction [m] and balance.
    Trend trend(double correction, double g);

    /// The iterate (rate, g) is left for rate + step.
    void advance(double rate, double g);

    /// [s/rad] the slope the steps are taken with
    double slope() const { return slope_; }
    /// whether it is this attempt's own (the bordered column's or a secant), not the last step's
    bool own_slope() const { return own_slope_; }

  private:
    double slope_last_, slope_;
    bool own_slope_ = false;
    bool have_previous_ = false;
    double rate_before_ = 0.0, g_before_ = 0.0;  // the last iterate
    double last_correction_ = 0.0;               // [m]
    unsigned int growths_ = 0;
    std::vector<double> balances_;  // |g| of each iteration that did not converge
  };
}  // namespace clearjoint::fe
