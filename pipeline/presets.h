// The presets' measured cost and error (pipeline.yaml presets.<name>.measured), for the log
// at the start and end of a run and for the report's table.
#pragma once

#include "pipeline/pipeline_config.h"

#include <nlohmann/json.hpp>

#include <string>

namespace clearjoint::pipeline
{
  /// One line per FE study: "thickness 2.0 % (t_B = 4 mm, ...)" or "misalignment: not yet
  /// measured (...)"; studies the preset gives no entry for say so too.
  std::string describe_preset_errors(const PipelineConfig &config, const std::string &preset);

  /// Every preset with its scene settings, measurements and whether it is the chosen one
  /// (pipeline_summary.json "presets").
  nlohmann::json presets_summary(const PipelineConfig &config);
} // namespace clearjoint::pipeline
