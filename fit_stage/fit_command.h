// The fit_stage command: reads force–penetration CSV files, fits F = K·δ^n, writes law files
// (or a law family), their manifest and plots. Kept apart from main() so tests can call it.
#pragma once

#include "fit_stage/power_law_fitter.h"
#include "laws/law_file.h"

#include <optional>
#include <string>
#include <vector>

namespace clearjoint::fit
{
  struct FitCommand
  {
    std::vector<std::string> inputs;  ///< one CSV, or FILE=VALUE pairs with --family
    std::string output;               ///< law (or law-family) JSON path
    std::optional<std::string> family_parameter;  ///< e.g. "theta", "t_B"
    std::string family_unit;          ///< unit of the family parameter (SI)
    std::string family_policy = "error";
    std::optional<std::string> scene_file;  ///< scene parameters to embed (YAML/JSON)
    std::optional<double> delta_ref;  ///< [m] reference penetration; default: top of range
    /// The FE data's measured error of F (--discretisation-error), recorded in every law
    /// written; the fit cannot see it (laws/law_file.h).
    std::optional<laws::DiscretisationError> discretisation_error;
    FitOptions options;
    bool plots = true;
  };

  /// Parses "A:B" (metres) into the options' range; throws InputError naming --range.
  void parse_range(const std::string &text, FitOptions &options);
  /// Parses "K,n"; throws InputError naming --start.
  std::pair<double, double> parse_start(const std::string &text);

  /// --discretisation-error-from: the largest of fe_stage's own error estimates of F(delta_max)
  /// in these manifests of adaptive runs (laws/own_error_estimate.h), with its source. Throws
  /// InputError naming a manifest that is unreadable or has no estimate, or an estimate outside
  /// [0, 100) %. `skip_missing` (--check before the FE cases ran): manifests that do not exist
  /// are skipped, and nullopt when none does.
  std::optional<laws::DiscretisationError> own_estimate_error(
    const std::vector<std::string> &manifests, bool skip_missing);

  /// Fits one CSV file into a law (does not write it). `scene` is embedded as given.
  laws::LawFile fit_csv_file(const std::string &csv_path, const FitOptions &options,
                             const nlohmann::json &scene, std::optional<double> delta_ref);

  /// fit_stage --check: validates what can be validated without fitting — the scene file, and
  /// each data file that already exists (readable CSV with 'delta' and 'force' columns; a
  /// FILE=VALUE member's VALUE a finite number). Throws InputError; writes nothing. Data files
  /// that do not exist yet (a pipeline checks before its FE cases ran) are skipped.
  void check_fit_command(const FitCommand &command);

  /// Runs the whole command: returns the process exit code (see fit_stage --help).
  int run_fit_command(const FitCommand &command, int argc, const char *const *argv);
} // namespace clearjoint::fit
