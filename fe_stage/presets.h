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
  PresetOverrides read_fe_preset(const std::string &pipeline_file, const std::string &name);

  /// The file's rolling.overrides (empty if none), which run_pipeline sets on its rolling
  /// study's scene after the preset's keys (they keep that mesh coarse whatever the preset):
  /// `fe_stage rolling.yaml --preset P` sets them too, so it runs what the pipeline's task runs.
  PresetOverrides read_rolling_overrides(const std::string &pipeline_file);

  /// The file's rolling.presets.<name> (empty if the file has no rolling.presets, or the entry
  /// is null): the rolling study's own settings for that preset, which run_pipeline sets after
  /// rolling.overrides (its mesh and time steps per preset).
  PresetOverrides read_rolling_preset(const std::string &pipeline_file, const std::string &name);

  /// Applies the overrides to a scene document (before it is read and validated).
  void apply_preset(nlohmann::json &scene, const PresetOverrides &overrides,
                    const std::string &pipeline_file);
}  // namespace clearjoint::fe
