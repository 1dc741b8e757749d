// The scenes run_pipeline generates: a base scene (YAML or JSON) with its relative file paths
// made absolute, the preset's overrides for its stage, then the sweep's or run's own overrides.
#pragma once

#include "pipeline/pipeline_config.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  /// Stages resolve relative file paths in a scene against the scene's own folder. A generated
  /// scene lives elsewhere (<run>/scenes/), so every string of the base scene that names an
  /// existing file relative to base_dir becomes absolute (canonical).
  void absolutize_paths(nlohmann::json &node, const std::string &base_dir);

  /// read(base) → absolutize_paths → preset overrides of `stage` ("fe" | "mbd") → `overrides`.
  nlohmann::json compose_scene(const PipelineConfig &config, const std::string &base,
                               const std::string &stage, const Overrides &overrides);

  /// Every string in the scene that is an absolute path of an existing regular file (meshes,
  /// law files, ...): their contents enter the task's identity, so changing such a file
  /// re-runs the task even though the scene text did not change.
  std::vector<std::string> files_named_in(const nlohmann::json &scene);
} // namespace clearjoint::pipeline
