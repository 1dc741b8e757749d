// Fits F = K·δ^n to force–penetration data by nonlinear least squares (Ceres), started from a
// log–log linear fit, and computes the regression diagnostics of SPEC §3.
#pragma once

#include "laws/law_file.h"

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::fit
{
  enum class Weighting
  {
    absolute,  ///< residual F_fit − F (every point counts the same in N)
    relative,  ///< residual (F_fit − F)/F (every point counts the same in percent)
  };

  struct FitOptions
  {
    /// [m] only points with range_min ≤ δ ≤ range_max are fitted (defaults: all).
    double range_min = 0.0;
    double range_max = std::numeric_limits<double>::infinity();
    Weighting weighting = Weighting::absolute;
    /// Start (K [N/m^n], n); if absent, the log–log linear fit gives it.
    std::optional<std::pair<double, double>> start;
    /// Name of the data for messages (file name).
    std::string source = "data";
  };

  struct FitResult
  {
    laws::PowerLaw law;
    laws::FitDiagnostics diagnostics;
    std::pair<double, double> start_used;  ///< (K, n) Ceres started from
    unsigned int n_origin_rows_skipped = 0;
  };

  /// Validates the data (finite, δ ≥ 0, F ≥ 0, ≥ 3 points with δ > 0 in range, F not constant)
  /// → InputError naming `options.source`; the origin row (0, 0) is skipped; throws
  /// NumericalError if Ceres does not converge or the covariance is rank-deficient.
  FitResult fit_power_law(const std::vector<double> &delta, const std::vector<double> &force,
                          const FitOptions &options);

  /// The log–log linear least-squares fit ln F = ln K + n ln δ over points with δ, F > 0.
  std::pair<double, double> log_log_start(const std::vector<double> &delta,
                                          const std::vector<double> &force);
} // namespace clearjoint::fit
