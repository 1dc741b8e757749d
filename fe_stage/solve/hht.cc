#include "fe_stage/solve/hht.h"

#include "common/error.h"

#include <cmath>
#include <stdexcept>

namespace clearjoint::fe
{
  HhtAlpha::HhtAlpha(const double alpha, const std::string &key_path, const std::string &file)
  {
    // [−1/3, 0]: HHT's range of unconditional stability with second-order accuracy.
    if (!(std::isfinite(alpha) && alpha >= -1.0 / 3.0 && alpha <= 0.0))
      throw InputError(file, key_path, format_value(alpha), "[-1/3, 0]",
                       "Hilber-Hughes-Taylor alpha; 0 = trapezoidal rule, no numerical damping");
    alpha_ = alpha;
    beta_ = 0.25 * (1.0 - alpha) * (1.0 - alpha);
    gamma_ = 0.5 - alpha;
  }

  void HhtAlpha::check_dt(const double dt)
  {
    if (!(std::isfinite(dt) && dt > 0.0))
      throw std::invalid_argument("HhtAlpha: time step " + format_value(dt) + " s is not > 0");
  }

  MatrixCoefficients HhtAlpha::coefficients(const double dt) const
  {
    check_dt(dt);
    MatrixCoefficients c;
    c.mass = 1.0 / (beta_ * dt * dt);
    c.damping = (1.0 + alpha_) * gamma_ / (beta_ * dt);
    c.stiffness = 1.0 + alpha_;
    return c;
  }

  void EnergyLedger::start(const double T0)
  {
    *this = EnergyLedger{};
    kinetic_initial = T0;
    kinetic = T0;
  }

  double EnergyLedger::add_step(const double T_new, const double dW_internal,
                                const double dW_applied)
  {
    const double d = dW_applied - (T_new - kinetic) - dW_internal;
    kinetic = T_new;
    work_internal += dW_internal;
    work_applied += dW_applied;
    dissipation += d;
    return d;
  }
}  // namespace clearjoint::fe
