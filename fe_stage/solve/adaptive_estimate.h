// The error of F(δ_max) on the last adaptive mesh, from the sequence of meshes (issue 11 item 4,
// issue 32 item 3), and whether an adaptive run has reached its target error. No deal.II:
// unit-tested in seconds.
#pragma once

#include <string>
#include <vector>

namespace clearjoint::fe
{
  struct AdaptiveEstimate
  {
    double error = -1.0;              // [1] estimated relative error of the last F; < 0: none
    std::string method;               // how it was obtained (extrapolated, or the last change)
    bool extrapolated = false;        // from F = F_inf + C N^-q (see estimate_adaptive_error)
    double order = 0.0;               // [1] q the estimate used, p/d (extrapolated only)
    double fitted_order = 0.0;        // [1] q of the least-squares fit (reported, not used)
    double extrapolated_force = 0.0;  // [N] F_inf (extrapolated only)
    unsigned int n_meshes_fitted = 0;  // meshes whose changes the fit used (extrapolated only)
  };

  /// The rate in the DoF count N at which the estimate extrapolates: p/d, the energy norm's
  /// rate on optimally refined meshes of degree-p elements in d dimensions (Kelly's indicator
  /// marks for the energy error). A functional such as F(δ_max) may converge faster (up to
  /// 2p/d), but the measured adaptive sequences show that a faster rate fitted through a few
  /// meshes is not to be trusted, and a slower one fitted there came from meshes before the
  /// asymptotic range (docs/fe.md "Adaptive refinement", "The error estimate").
  inline double energy_norm_rate(const unsigned int degree, const unsigned int dim = 3)
  {
    return static_cast<double>(degree) / static_cast<double>(dim);
  }

  /// The most changes |F_k − F_{k−1}| the fit of the rate uses (the last ones): an even
  /// number, so that the odd/even alternation of Kelly's sequences (a large change, then a
  /// small one, measured on six meshes) cancels, and the coarsest, least asymptotic meshes
  /// leave the fit as the sequence grows.
  inline constexpr unsigned int adaptive_fit_changes = 4;

  /// With three or more meshes whose last (up to adaptive_fit_changes) changes have one sign:
  /// the error of the last mesh is the Richardson tail of the last two cycles' change,
  /// |F_k − F_{k−2}| / ((N_k/N_{k−2})^q − 1), of F_k = F_∞ + C N_k^(−q) with q = max_order
  /// (fe_stage passes p/d): for a sequence of that form with any rate ≥ max_order an upper
  /// bound. The rate q of the least-squares fit over those changes, log|F_{j−1} − F_j| =
  /// log C + log(N_{j−1}^(−q) − N_j^(−q)) (with three meshes the three-mesh Richardson rate),
  /// is reported (fitted_order, `method`) but not used: faster than p/d it is not to be
  /// trusted, and on the recorded sequences a slower one came from meshes before the
  /// asymptotic range (adaptive_estimate.cc says which and what it cost). When a change in that window has the other sign,
  /// the meshes do not grow, or no positive rate fits (the changes grow), the estimate is the
  /// last cycle's change |F_k − F_{k−1}| / |F_k|, `method` "change in the last cycle (not
  /// extrapolated; not a bound)": on the recorded sequences it was 0.05–29× the error, median
  /// 1.13 (bench/adaptive_estimate_table.py), so neither a lower nor an upper bound. Fewer
  /// than two meshes: no estimate.
  AdaptiveEstimate estimate_adaptive_error(const std::vector<double> &n_dofs,
                                           const std::vector<double> &forces, double max_order);

  /// The same for a sequence of records with n_dofs and force (AdaptiveCycle of fe_model.h)
  /// computed with elements of polynomial degree `degree` in 3D.
  template <typename Cycle>
  AdaptiveEstimate estimate_adaptive_error(const std::vector<Cycle> &cycles,
                                           const unsigned int degree)
  {
    std::vector<double> n_dofs, forces;
    for (const auto &c : cycles)
      {
        n_dofs.push_back(static_cast<double>(c.n_dofs));
        forces.push_back(c.force);
      }
    return estimate_adaptive_error(n_dofs, forces, energy_norm_rate(degree));
  }

  /// Whether a target error (mesh.adaptive_target_error) is met: only an extrapolated estimate
  /// counts — the last cycle's change at or below the target says nothing about the error
  /// itself.
  inline bool adaptive_target_met(const AdaptiveEstimate &e, const double target)
  {
    return target > 0.0 && e.extrapolated && e.error >= 0.0 && e.error <= target;
  }
}  // namespace clearjoint::fe
