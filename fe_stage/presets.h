// fe_stage --preset: the FE scene settings of pipeline.yaml's presets (fast | standard |
// accurate), read from the same file run_pipeline reads, so a scene run by hand with a preset
// gets exactly the pipeline's mesh. No deal.II.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace clearjoint::fe
{
  using PresetOverrides = std::vector<std::pair<std::string, nlohmann::json>>;

  /// The source tree's pipeline.yaml (the committed presets).
  std::string default_presets_file();

  /// presets.<name>.fe of `pipeline_file` as (scene key path, value) pairs, in file order.
  /// InputError naming --preset and the presets the file has if `name` is not one of them.
  /// For a scene of `study` rolling, the file's rolling.overrides follow (run_pipeline sets them
  /// after the preset's keys: they keep the rolling mesh coarse whatever the preset), so
  /// `fe_stage rolling.yaml --preset P` runs what the pipeline's rolling task runs.
  PresetOverrides read_fe_preset(const std::string &pipeline_file, const std::string &name,
                                 const std::string &study = "");

  /// Applies the overrides to a scene document (before it is read and validated).
  void apply_preset(nlohmann::json &scene, const PresetOverrides &overrides,
                    const std::string &pipeline_file);
} // namespace clearjoint::fe
