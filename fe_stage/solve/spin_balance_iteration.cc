// The spin's Newton iteration on the journal's torque balance (solve/spin_balance_iteration.h).
#include "fe_stage/solve/spin_balance_iteration.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::fe
{
  SpinBalanceIteration::SpinBalanceIteration(const double slope_last)
    : slope_last_(slope_last)
    , slope_(slope_last)
  {}

  bool SpinBalanceIteration::take_bordered_slope(const double slope)
  {
    if (slope > 0.0 && std::isfinite(slope))
      {
        slope_ = slope;
        own_slope_ = true;
      }
    return own_slope_;
  }

  void SpinBalanceIteration::take_secant(const double rate, const double g, const double correction,
                                         const double tolerance)
  {
    if (!have_previous_ || rate == rate_before_)
      return;
    const double secant = (g - g_before_) / (rate - rate_before_);
    if (secant > 0.0 && ((secant > 0.2 * slope_last_ && secant < 5.0 * slope_last_) ||
                         correction <= 100.0 * tolerance))
      {
        slope_ = secant;
        own_slope_ = true;
      }
  }

  double SpinBalanceIteration::step(const double g, const double roll) const
  {
    return std::abs(g) <= 1e-6 ? 0.0 : std::clamp(-g / slope_, -0.5 * roll, 0.5 * roll);
  }

  bool SpinBalanceIteration::converged(const double correction, const double tolerance,
                                       const double rate_step, const double roll) const
  {
    return correction <= tolerance &&
           (rate_step == 0.0 || (own_slope_ && std::abs(rate_step) <= 1e-10 * roll));
  }

  SpinBalanceIteration::Trend SpinBalanceIteration::trend(const double correction, const double g)
  {
    growths_ = have_previous_ && correction > last_correction_ ? growths_ + 1 : 0;
    last_correction_ = correction;
    if (growths_ >= 3)
      return Trend::diverges;
    // (a first version's spin-up step crept 25 iterations at g ≈ 3.25 with a slope far from
    // the balance's; the root finder brackets instead)
    balances_.push_back(std::abs(g));
    if (balances_.size() > 4 && std::abs(g) > 1e-6 &&
        std::abs(g) > 0.5 * balances_[balances_.size() - 5])
      return Trend::stalls;
    return Trend::continues;
  }

  void SpinBalanceIteration::advance(const double rate, const double g)
  {
    rate_before_ = rate;
    g_before_ = g;
    have_previous_ = true;
  }
}  // namespace clearjoint::fe
