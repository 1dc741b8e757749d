// fe_stage's own estimate of the error of F(delta_max) on an adaptive case's last mesh, as its
// manifest records it: read by run_pipeline (its log, the summary, the report's table) and by
// fit_stage --discretisation-error-from (the law's discretisation error where no preset figure
// applies, e.g. a Gmsh bearing). No deal.II: the manifest is JSON.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace clearjoint::laws
{
  /// fe_stage's own estimate of the relative error of F(delta_max) on an adaptive case's last
  /// mesh (its manifest's extra.adaptive.estimated_error_F_max; docs/fe.md "The error
  /// estimate"): the figure to use where the preset's measured one does not apply (a Gmsh
  /// bearing without a convergence study).
  struct OwnErrorEstimate
  {
    double relative = 0.0;     ///< [1]
    bool last_change = false;  ///< the last cycle's change: not extrapolated, not a bound
    int n_meshes = 0;          ///< meshes in the sequence
    std::optional<double> n_dofs;  ///< [1] of the last mesh
    std::string method;            ///< fe_stage's words for how it was made
  };

  /// The estimate in an fe_stage manifest; nullopt for a case without adaptive cycles (or one
  /// whose manifest is not of that shape).
  std::optional<OwnErrorEstimate> read_own_error_estimate(const nlohmann::json &fe_manifest);

  /// How the last cycle's change compared with the error on the recorded adaptive sequences
  /// (bench/adaptive_estimate_table.py: the 25 prefixes where it is fe_stage's estimate, against
  /// the far end of each reference): from 0.05 to 29 times it, median 1.12, above it on 16. So
  /// it is no bound either way, only an indication; the words below quote these figures. The
  /// one copy of them: run_pipeline's log and summary (own_error_F_max.last_change_record, which
  /// the report quotes) take them from here, and AdaptiveEstimate.BracketsTheReferenceOnThe-
  /// MeasuredSequences checks them against tests/data/fe/adaptive_sequences.txt.
  inline constexpr const char *last_change_record =
    "on the recorded sequences it was 0.05-29x the error, median 1.12";

  /// "0.85 % (extrapolated)" or "~3.3 % (the change in the last cycle, not extrapolated: on the
  /// recorded sequences it was 0.05-29x the error, median 1.12)".
  std::string describe_own_estimate(const OwnErrorEstimate &e);
}  // namespace clearjoint::laws
