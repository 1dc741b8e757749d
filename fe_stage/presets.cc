#include "fe_stage/presets.h"

#include "common/error.h"
#include "common/key_path.h"
#include "common/strict_reader.h"

namespace clearjoint::fe
{
  std::string default_presets_file()
  {
    return std::string(CLEARJOINT_SOURCE_DIR) + "/pipeline.yaml";
  }

  namespace
  {
    /// A block of scene settings in the pipeline file (`where` its key path) as (key path,
    /// value) pairs in file order; InputError unless it is a mapping (`expected` says what is).
    PresetOverrides settings_of(const nlohmann::json &block, const std::string &pipeline_file,
                                const std::string &where, const std::string &expected)
    {
      if (!block.is_object())
        throw InputError(pipeline_file, where, block.dump(), expected);
      PresetOverrides out;
      for (const auto &[k, v] : block.items())
        out.emplace_back(k, v);
      return out;
    }

    const std::string mapping_or_null = "a mapping of scene key paths to values, or null";
  }  // namespace

  PresetOverrides read_fe_preset(const std::string &pipeline_file, const std::string &name)
  {
    const nlohmann::json doc = read_structured_file(pipeline_file);
    const nlohmann::json *presets = find_key_path(doc, "presets");
    if (!presets || !presets->is_object() || presets->empty())
      throw InputError(pipeline_file, "presets", "(missing)",
                       "a mapping of presets (fast, standard, accurate)");
    if (!presets->contains(name))
      {
        std::string names;
        for (const auto &item : presets->items())
          names += (names.empty() ? "" : " | ") + item.key();
        throw InputError("", "--preset", name, names + " (the presets of " + pipeline_file + ")");
      }
    const nlohmann::json fe = presets->at(name).value("fe", nlohmann::json());
    if (fe.is_null())
      return {};  // the preset leaves the FE scene as it is
    return settings_of(fe, pipeline_file, "presets." + name + ".fe", mapping_or_null);
  }

  PresetOverrides read_rolling_overrides(const std::string &pipeline_file)
  {
    const nlohmann::json doc = read_structured_file(pipeline_file);
    const nlohmann::json *rolling = find_key_path(doc, "rolling.overrides");
    if (!rolling)
      return {};
    return settings_of(*rolling, pipeline_file, "rolling.overrides",
                       "a mapping of scene key paths to values");
  }

  PresetOverrides read_rolling_preset(const std::string &pipeline_file, const std::string &name)
  {
    const nlohmann::json doc = read_structured_file(pipeline_file);
    const nlohmann::json *presets = find_key_path(doc, "rolling.presets");
    if (!presets || presets->is_null())
      return {};
    const std::string where = "rolling.presets." + name;
    if (!presets->is_object() || !presets->contains(name))
      throw InputError(pipeline_file, where, "(missing)",
                       "settings (or null) for every preset: fast, standard, accurate");
    const nlohmann::json &own = presets->at(name);
    if (own.is_null())
      return {};
    return settings_of(own, pipeline_file, where, mapping_or_null);
  }

  void apply_preset(nlohmann::json &scene, const PresetOverrides &overrides,
                    const std::string &pipeline_file)
  {
    for (const auto &[key, value] : overrides)
      set_key_path(scene, key, value, pipeline_file);
  }
}  // namespace clearjoint::fe
