// The presets' measured cost and error (pipeline.yaml presets.<name>.measured), for the log
// at the start and end of a run and for the report's table.
#pragma once

#include "pipeline/pipeline_config.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <utility>

namespace clearjoint::pipeline
{
  /// One line per FE sweep: "thickness 2.0 % (t_B = 4 mm, ...)" or "misalignment: not yet
  /// measured (...)"; sweeps the preset gives no entry for say so too.
  std::string describe_preset_errors(const PipelineConfig &config, const std::string &preset);

  /// Every preset with its scene settings (its `fe` and `mbd` maps; a sweep's own settings for
  /// it under `sweeps.<sweep>`, the rolling study's under `rolling`, null without them),
  /// measurements and whether it is the chosen one (pipeline_summary.json "presets").
  nlohmann::json presets_summary(const PipelineConfig &config);

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
  };

  /// The estimate in an fe_stage manifest; nullopt for a case without adaptive cycles (or one
  /// whose manifest is not of that shape).
  std::optional<OwnErrorEstimate> read_own_error_estimate(const nlohmann::json &fe_manifest);

  /// How the last cycle's change compared with the error on the recorded adaptive sequences
  /// (bench/adaptive_estimate_table.py: the 23 prefixes where it is fe_stage's estimate, against
  /// the far end of each reference): from 0.05 to 29 times it, median 1.13, above it on 16. So
  /// it is no bound either way, only an indication; the words below quote these figures.
  inline constexpr const char *last_change_record =
    "on the recorded sequences it was 0.05-29x the error, median 1.13";

  /// "0.85 % (extrapolated)" or "~3.3 % (the change in the last cycle, not extrapolated: on the
  /// recorded sequences it was 0.05-29x the error, median 1.13)".
  std::string describe_own_estimate(const OwnErrorEstimate &e);

  /// The run's own estimates of one FE sweep (value label → estimate) beside the chosen
  /// preset's measured figure for it: "own estimate of the error of F(delta_max): t_B=0.004
  /// 0.85 % (extrapolated), ...; preset fast measured 1.2 %", or, where the preset's figure is
  /// null or absent, "...; preset fast: not measured for this sweep, so the run's own estimate
  /// is the figure to use".
  std::string describe_own_estimates(const PipelineConfig &config, const std::string &sweep,
                                     const std::map<std::string, OwnErrorEstimate> &estimates);

  /// A measured figure "misses" a run's time when either is more than this factor times the
  /// other (report.py uses the same factor): the figure is stale in either direction — too low,
  /// it makes the time-left estimate and the Slurm time limits too short; too high, it
  /// overstates the preset's cost and the limits — so it no longer describes the code on the
  /// machine it runs on.
  inline constexpr double stale_factor = 1.5;
  inline bool figure_missed(const double run_seconds, const double figure_seconds)
  {
    return run_seconds > stale_factor * figure_seconds ||
           figure_seconds > stale_factor * run_seconds;
  }

  /// The chosen preset's measured time of one task [s] and the key of `measured` it comes from:
  /// stage fe_stage → case_times.<sweep>, else fe_case_time; fe_impact → impact_time;
  /// fe_impact_deformable → impact_deformable_time;
  /// fe_rolling → rolling_time. nullopt for other stages and for figures not measured.
  std::optional<std::pair<std::string, double>> task_figure(const PipelineConfig &config,
                                                            const std::string &stage,
                                                            const std::string &sweep = "");

  /// "preset fast measured 2.3 s", and ", this run 3.1x that: figure stale?" when
  /// figure_missed(): the text beside a task's time in the log.
  std::string describe_against_figure(const std::string &preset, double run_seconds,
                                      double figure_seconds);
} // namespace clearjoint::pipeline
