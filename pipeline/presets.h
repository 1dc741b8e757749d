// The presets' measured cost and error (pipeline.yaml presets.<name>.measured), for the log
// at the start and end of a run and for the report's table.
#pragma once

#include "laws/own_error_estimate.h"
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

  // fe_stage's own error estimate of an adaptive case (laws/own_error_estimate.h), as the run
  // and its report read it
  using laws::describe_own_estimate;
  using laws::last_change_record;
  using laws::OwnErrorEstimate;
  using laws::read_own_error_estimate;

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
