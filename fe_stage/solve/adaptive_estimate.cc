#include "fe_stage/solve/adaptive_estimate.h"

#include "common/error.h"

#include <cmath>

namespace clearjoint::fe
{
  AdaptiveEstimate estimate_adaptive_error(const std::vector<double> &N,
                                           const std::vector<double> &F)
  {
    AdaptiveEstimate e;
    if (F.size() < 2 || N.size() != F.size())
      return e;
    const std::size_t k = F.size() - 1;
    const double F2 = F[k], F1 = F[k - 1];
    e.error = std::abs(F2 - F1) / std::abs(F2);
    e.method = "change in the last cycle (a lower bound)";
    if (F.size() < 3)
      return e;
    const double F0 = F[k - 2];
    const double N0 = N[k - 2], N1 = N[k - 1], N2 = N[k];
    const double r = (F0 - F1) / (F1 - F2);
    if (!(r > 0.0) || !(N2 > N1 && N1 > N0))
      return e;
    auto ratio = [&](const double q) {
      return (std::pow(N0, -q) - std::pow(N1, -q)) / (std::pow(N1, -q) - std::pow(N2, -q));
    };
    // ratio(q) grows with q from (log N1 − log N0)/(log N2 − log N1) at q → 0; outside
    // [1e-3, 20] the sequence is not of this form (e.g. the differences grow)
    double lo = 1e-3, hi = 20.0;
    if (!(ratio(lo) < r && ratio(hi) > r))
      return e;
    for (int i = 0; i < 200 && hi - lo > 1e-12; ++i)  // bisection: 200 halvings bound it
      (ratio(0.5 * (lo + hi)) < r ? lo : hi) = 0.5 * (lo + hi);
    const double q = 0.5 * (lo + hi);
    const double F_inf = F2 - (F1 - F2) * std::pow(N2, -q) / (std::pow(N1, -q) - std::pow(N2, -q));
    e.extrapolated = true;
    e.order = q;
    e.extrapolated_force = F_inf;
    e.error = std::abs(F2 - F_inf) / std::abs(F_inf);
    e.method = "extrapolation of the last three meshes, F = F_inf + C N^-q, q = " + format_value(q);
    return e;
  }
}  // namespace clearjoint::fe
