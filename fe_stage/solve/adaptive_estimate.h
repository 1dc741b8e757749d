// The error of F(δ_max) on the last adaptive mesh, from the sequence of meshes (issue 11 item 4),
// and whether an adaptive run has reached its target error. No deal.II: unit-tested in seconds.
#pragma once

#include <string>
#include <vector>

namespace clearjoint::fe
{
  struct AdaptiveEstimate
  {
    double error = -1.0;              // [1] estimated relative error of the last F; < 0: none
    std::string method;               // how it was obtained (a lower bound, or extrapolated)
    bool extrapolated = false;        // from F = F_inf + C N^-q through the last three meshes
    double order = 0.0;               // [1] q (extrapolated only)
    double extrapolated_force = 0.0;  // [N] F_inf (extrapolated only)
  };

  /// With three or more meshes, F_k = F_∞ + C N_k^(−q) through the last three (q by
  /// bisection: a generalised Richardson extrapolation in the DoF count N, as the uniform
  /// levels' in docs/benchmarks.md); otherwise, or when the last three do not approach a limit
  /// monotonically, the last cycle's change |F_k − F_{k−1}| / |F_k|, which only bounds the
  /// error from below — `method` says which. Fewer than two meshes: no estimate.
  AdaptiveEstimate estimate_adaptive_error(const std::vector<double> &n_dofs,
                                           const std::vector<double> &forces);

  /// The same for a sequence of records with n_dofs and force (AdaptiveCycle of fe_model.h).
  template <typename Cycle>
  AdaptiveEstimate estimate_adaptive_error(const std::vector<Cycle> &cycles)
  {
    std::vector<double> n_dofs, forces;
    for (const auto &c : cycles)
      {
        n_dofs.push_back(static_cast<double>(c.n_dofs));
        forces.push_back(c.force);
      }
    return estimate_adaptive_error(n_dofs, forces);
  }

  /// Whether a target error (mesh.adaptive_target_error) is met: only an extrapolated estimate
  /// counts — a lower bound at or below the target says nothing about the error itself.
  inline bool adaptive_target_met(const AdaptiveEstimate &e, const double target)
  {
    return target > 0.0 && e.extrapolated && e.error >= 0.0 && e.error <= target;
  }
}  // namespace clearjoint::fe
