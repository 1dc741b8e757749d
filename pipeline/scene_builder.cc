#include "pipeline/scene_builder.h"

#include "common/strict_reader.h"

#include <algorithm>
#include <filesystem>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  void absolutize_paths(nlohmann::json &node, const std::string &base_dir)
  {
    if (node.is_object() || node.is_array())
    {
      for (auto &child : node)
        absolutize_paths(child, base_dir);
      return;
    }
    if (!node.is_string())
      return;
    const std::string value = node.get<std::string>();
    const bool looks_like_path =
      value.find('/') != std::string::npos || value.find('.') != std::string::npos;
    if (value.empty() || value[0] == '/' || !looks_like_path)
      return;
    std::error_code ec;
    const fs::path candidate = fs::path(base_dir) / value;
    if (fs::is_regular_file(candidate, ec))
      node = fs::canonical(candidate).string();
  }

  nlohmann::json compose_scene(const PipelineConfig &config, const std::string &base,
                               const std::string &stage, const Overrides &overrides)
  {
    nlohmann::json scene = read_structured_file(base);
    absolutize_paths(scene, fs::absolute(base).parent_path().string());
    const auto preset = config.presets.find(config.preset);
    if (preset != config.presets.end())
      for (const auto &[key, value] : preset->second)
        if (key.rfind(stage + ":", 0) == 0)
          set_key_path(scene, key.substr(stage.size() + 1), value, config.source);
    for (const auto &[key, value] : overrides)
      set_key_path(scene, key, value, config.source);
    return scene;
  }

  namespace
  {
    void collect_files(const nlohmann::json &node, std::vector<std::string> &out)
    {
      if (node.is_object() || node.is_array())
      {
        for (const auto &child : node)
          collect_files(child, out);
        return;
      }
      if (!node.is_string())
        return;
      const std::string value = node.get<std::string>();
      std::error_code ec;
      if (!value.empty() && value[0] == '/' && fs::is_regular_file(value, ec) &&
          std::find(out.begin(), out.end(), value) == out.end())
        out.push_back(value);
    }
  } // namespace

  std::vector<std::string> files_named_in(const nlohmann::json &scene)
  {
    std::vector<std::string> out;
    collect_files(scene, out);
    return out;
  }
} // namespace clearjoint::pipeline
