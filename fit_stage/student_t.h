// Quantiles of Student's t distribution, for the 95 % confidence intervals of fitted
// parameters (N − 2 degrees of freedom). Our own small implementation: the regularized
// incomplete beta function by Lentz's continued fraction, inverted by bisection.
#pragma once

namespace clearjoint::fit
{
  /// P(T ≤ t) for T ~ Student t with `dof` > 0 degrees of freedom.
  double student_t_cdf(double t, double dof);
  /// t such that P(T ≤ t) = p, for p in (0, 1). Accurate to ~1e-12 relative.
  double student_t_quantile(double p, double dof);
} // namespace clearjoint::fit
