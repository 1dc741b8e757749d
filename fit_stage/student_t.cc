#include "fit_stage/student_t.h"

#include <cmath>
#include <stdexcept>

namespace clearjoint::fit
{
  namespace
  {
    // Continued fraction for the incomplete beta function (modified Lentz), valid for
    // x < (a + 1)/(a + b + 2); the caller uses the symmetry I_x(a,b) = 1 − I_{1−x}(b,a) otherwise.
    double beta_continued_fraction(const double a, const double b, const double x)
    {
      constexpr double tiny = 1e-300, eps = 1e-15;
      double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
      if (std::abs(d) < tiny)
        d = tiny;
      d = 1.0 / d;
      double h = d;
      for (int m = 1; m <= 10000; ++m)
      {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
        d = 1.0 + aa * d;
        d = std::abs(d) < tiny ? tiny : d;
        c = 1.0 + aa / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1.0 / d;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
        d = 1.0 + aa * d;
        d = std::abs(d) < tiny ? tiny : d;
        c = 1.0 + aa / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < eps)
          return h;
      }
      throw std::runtime_error("incomplete beta continued fraction did not converge");
    }

    double regularized_incomplete_beta(const double a, const double b, const double x)
    {
      if (x <= 0.0)
        return 0.0;
      if (x >= 1.0)
        return 1.0;
      const double ln_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                              a * std::log(x) + b * std::log1p(-x);
      if (x < (a + 1.0) / (a + b + 2.0))
        return std::exp(ln_front) * beta_continued_fraction(a, b, x) / a;
      return 1.0 - std::exp(ln_front) * beta_continued_fraction(b, a, 1.0 - x) / b;
    }
  } // namespace

  double student_t_cdf(const double t, const double dof)
  {
    // Two forms of the same identity, chosen so the beta function's argument never sits next
    // to 1 (where 1 − x loses digits):  P(|T| > t) = I_{ν/(ν+t²)}(ν/2, 1/2)
    //                                   P(|T| < t) = I_{t²/(ν+t²)}(1/2, ν/2).
    const double t2 = t * t;
    if (t2 < dof)
    {
      const double inner = 0.5 * regularized_incomplete_beta(0.5, 0.5 * dof, t2 / (dof + t2));
      return t >= 0.0 ? 0.5 + inner : 0.5 - inner;
    }
    const double tail = 0.5 * regularized_incomplete_beta(0.5 * dof, 0.5, dof / (dof + t2));
    return t >= 0.0 ? 1.0 - tail : tail;
  }

  double student_t_quantile(const double p, const double dof)
  {
    if (!(p > 0.0 && p < 1.0) || !(dof > 0.0))
      throw std::invalid_argument("student_t_quantile: p in (0,1) and dof > 0 required");
    double lo = -1.0, hi = 1.0;
    for (int i = 0; i < 200 && student_t_cdf(lo, dof) > p; ++i)
      lo *= 2.0;
    for (int i = 0; i < 200 && student_t_cdf(hi, dof) < p; ++i)
      hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-14 * std::max(1.0, std::abs(hi)); ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (student_t_cdf(mid, dof) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
} // namespace clearjoint::fit
