// Dotted key paths into JSON documents ("mesh.global_refinements", "clearance_joints.0.law"):
// how pipeline.yaml's presets and overrides, and fe_stage --preset, set scene keys.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace clearjoint
{
  /// Sets "a.b.c" in a JSON object, creating intermediate objects; throws InputError if a
  /// non-object is in the way.
  void set_key_path(nlohmann::json &root, const std::string &key_path, const nlohmann::json &value,
                    const std::string &source);

  /// The value at "a.b.c" (numeric components index lists), or nullptr if absent.
  const nlohmann::json *find_key_path(const nlohmann::json &root, const std::string &key_path);
} // namespace clearjoint
