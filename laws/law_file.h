// The law file, schema clearjoint.law/1: the contract between the FE/fit half and the MBD half.
//
// {
//   "schema": "clearjoint.law/1",
//   "law":         {"form": "F = K*delta^n", "K": 3.6595e8, "n": 1.0114},
//   "units":       {"delta": "m", "force": "N", "K": "N/m^n", "n": "1"},
//   "valid_range": {"delta_min": 0.0, "delta_max": 5.0e-5},          // m
//   "reference":   {"delta_ref": 5.0e-5, "F_ref": 16344.0},          // m, N  (SPEC §3)
//   "mm_N":        {"K": 338240.0, "n": 1.0114},                     // the same law, δ in mm
//   "source":      {"kind": "paper" | "fit" | "confidence_band", "description": "...",
//                   "data_file": "..." | null, "data_sha256": "..." | null},
//   "scene":       { ...free-form parameters of the FE scene it came from... } | null,
//   "diagnostics": { ...FitDiagnostics, see below... } | null,
//   "discretisation_error": {"F_relative": 0.02, "unit": "1", "description": "..."} | null
// }
// discretisation_error is the measured relative error of the FE force on the mesh the data came
// from (the pipeline preset's Richardson estimate of F(δ_max)); the regression intervals in
// diagnostics do not contain it (they only see the scatter about the fit), so a band built
// from them alone is narrower than the truth (laws/confidence_band.h uses both). Optional
// when reading (files written before it existed); written always, null when not known.
// K and n are correlated (K carries units of N/m^n), so comparisons and interpolation use
// F_ref = F(δ_ref), not K.
#pragma once

#include "laws/power_law.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::laws
{
  inline constexpr const char *law_schema = "clearjoint.law/1";

  /// Regression diagnostics of a fit (SPEC §3). Units: K-related in N/m^n, residuals in N.
  struct FitDiagnostics
  {
    std::size_t n_points = 0;
    std::string weighting;          ///< "absolute" | "relative"
    double fit_delta_min = 0.0;     ///< [m] fit range actually used
    double fit_delta_max = 0.0;     ///< [m]
    double r_squared = 0.0;         ///< [1] coefficient of determination (unweighted)
    double residual_std = 0.0;      ///< [N] sqrt(SSR/(N−2)) (weighted units if relative)
    double sum_squared_residuals = 0.0;
    double K_std_error = 0.0;       ///< [N/m^n]
    double n_std_error = 0.0;       ///< [1]
    double K_ci95_low = 0.0, K_ci95_high = 0.0;  ///< [N/m^n] Student-t, N−2 dof
    double n_ci95_low = 0.0, n_ci95_high = 0.0;  ///< [1]
    double correlation_K_n = 0.0;   ///< [1]
    double condition_number = 0.0;  ///< [1] of the column-scaled Jacobian at the solution
    double max_relative_residual = 0.0;  ///< [1] max |F_fit − F| / F
    std::string solver_summary;     ///< Ceres' one-line report
    std::vector<double> delta;      ///< [m] data used
    std::vector<double> force;      ///< [N] data used
    std::vector<double> residual;   ///< [N] F_data − F_fit
  };

  /// The FE data's own error, measured by mesh refinement (not by the fit).
  struct DiscretisationError
  {
    double F_relative = 0.0;  ///< [1] estimated |F_h − F_exact| / F_exact, e.g. 0.02 for 2 %
    std::string description;  ///< where and how it was measured
  };

  struct LawFile
  {
    PowerLaw law;
    double delta_min = 0.0;   ///< [m] valid range
    double delta_max = 0.0;   ///< [m]
    double delta_ref = 0.0;   ///< [m] reference penetration (normally delta_max)
    std::string source_kind;  ///< "paper" | "fit" | "confidence_band" (laws/confidence_band.h)
    std::string source_description;
    std::optional<std::string> data_file, data_sha256;
    nlohmann::json scene;     ///< null or the FE scene parameters
    std::optional<FitDiagnostics> diagnostics;
    std::optional<DiscretisationError> discretisation_error;

    double F_ref() const { return law.force(delta_ref); }  ///< [N]
    BoundedPowerLaw bounded(RangePolicy policy) const
    {
      return BoundedPowerLaw(law, delta_min, delta_max, policy);
    }
  };

  nlohmann::json to_json(const LawFile &law);
  nlohmann::json to_json(const FitDiagnostics &d);
  /// Strict: unknown keys, missing keys, a wrong schema, wrong units, K ≤ 0, n ≤ 0, or an
  /// F_ref inconsistent with K, n (> 1e-6 relative) → InputError naming `source` and the key.
  LawFile law_from_json(const nlohmann::json &j, const std::string &source,
                        const std::string &key_prefix = "");

  LawFile read_law_file(const std::string &path);
  /// Writes atomically (temporary name, then rename).
  void write_law_file(const std::string &path, const LawFile &law);
} // namespace clearjoint::laws
