#include "fe_stage/solve/hht.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace clearjoint::fe
{
  HhtAlpha::HhtAlpha(const Operator op, const double alpha, const double beta, const double gamma,
                     const double kappa)
    : op_(op), alpha_(alpha), beta_(beta), gamma_(gamma), kappa_(kappa)
  {}

  HhtAlpha::HhtAlpha(const double alpha, const std::string &key_path, const std::string &file)
  {
    // Abaqus's range [−1/2, 0]: unconditionally stable throughout, second order (the header
    // says why −1/3, not −1/2, is the most damping)
    if (!(std::isfinite(alpha) && alpha >= alpha_min && alpha <= alpha_max))
      throw InputError(file, key_path, format_value(alpha), "[-1/2, 0]",
                       "Hilber-Hughes-Taylor alpha (Abaqus's range); 0 = trapezoidal rule, no "
                       "numerical damping; -1/3 damps the most");
    alpha_ = alpha;
    beta_ = 0.25 * (1.0 - alpha) * (1.0 - alpha);
    gamma_ = 0.5 - alpha;
    kappa_ = 0.5 - beta_;
  }

  HhtAlpha::HhtAlpha(const double alpha, const double beta, const double gamma)
  {
    if (!(std::isfinite(alpha) && alpha >= alpha_min && alpha <= alpha_max &&
          std::isfinite(beta) && beta > 0.0 && std::isfinite(gamma) && gamma >= 0.5))
      throw std::invalid_argument("HhtAlpha: (alpha, beta, gamma) = (" + format_value(alpha) +
                                  ", " + format_value(beta) + ", " + format_value(gamma) +
                                  ") needs alpha in [-1/2, 0], beta > 0, gamma >= 1/2");
    alpha_ = alpha;
    beta_ = beta;
    gamma_ = gamma;
    kappa_ = 0.5 - beta;
  }

  HhtAlpha HhtAlpha::backward_euler()
  {
    return HhtAlpha(Operator::backward_euler, 0.0, 1.0, 1.0, 0.0);
  }

  HhtAlpha HhtAlpha::for_application(const DynamicApplication application,
                                     const std::optional<double> alpha,
                                     const std::string &alpha_key, const std::string &file)
  {
    switch (application)
      {
        case DynamicApplication::transient_fidelity:
          return HhtAlpha(alpha.value_or(transient_fidelity_alpha), alpha_key, file);
        case DynamicApplication::moderate_dissipation:
          return HhtAlpha(alpha.value_or(moderate_dissipation_alpha), alpha_key, file);
        case DynamicApplication::quasi_static:
          if (alpha)
            throw InputError(file, alpha_key, format_value(*alpha),
                             "no value with application quasi_static",
                             "quasi_static is backward Euler, which has no alpha; give alpha "
                             "with transient_fidelity or moderate_dissipation");
          return backward_euler();
      }
    throw std::invalid_argument("HhtAlpha: unknown application");
  }

  double HhtAlpha::spectral_radius_limit() const
  {
    // ωΔt → ∞ (docs/fe.md): the equation of motion leaves (1+α)u' = αu, root r = α/(1+α); the
    // Newmark relations then give the 2×2 block [[1 − γ/β, 1 − γ − γκ/β], [−1/β, −κ/β]] with
    // trace T and determinant D
    const double r = alpha_ / (1.0 + alpha_);
    const double T = 1.0 - (gamma_ + kappa_) / beta_;
    const double D = (1.0 - gamma_ - kappa_) / beta_;
    const double disc = T * T - 4.0 * D;
    // HHT's pair is a double root (disc = 0 exactly, its rounding ~1e-16 T² would move the
    // roots by √disc ~ 1e-8): within a few ulps of zero, or below it (a complex pair), both
    // roots have the modulus √|D|
    double pair = 0.0;
    if (disc > 64.0 * std::numeric_limits<double>::epsilon() * (T * T + 4.0 * std::abs(D)))
      pair = std::max(std::abs(0.5 * (T + std::sqrt(disc))), std::abs(0.5 * (T - std::sqrt(disc))));
    else
      pair = std::sqrt(std::abs(D));
    return std::max(std::abs(r), pair);
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
