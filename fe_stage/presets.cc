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
    PresetOverrides out;
    if (fe.is_null())
      return out;  // the preset leaves the FE scene as it is
    if (!fe.is_object())
      throw InputError(pipeline_file, "presets." + name + ".fe", fe.dump(),
                       "a mapping of scene key paths to values, or null");
    for (const auto &[k, v] : fe.items())
      out.emplace_back(k, v);
    return out;
  }

  PresetOverrides read_rolling_overrides(const std::string &pipeline_file)
  {
    const nlohmann::json doc = read_structured_file(pipeline_file);
    PresetOverrides out;
    if (const nlohmann::json *rolling = find_key_path(doc, "rolling.overrides"))
      {
        if (!rolling->is_object())
          throw InputError(pipeline_file, "rolling.overrides", rolling->dump(),
                           "a mapping of scene key paths to values");
        for (const auto &[k, v] : rolling->items())
          out.emplace_back(k, v);
      }
    return out;
  }

  PresetOverrides read_rolling_preset(const std::string &pipeline_file, const std::string &name)
  {
    const nlohmann::json doc = read_structured_file(pipeline_file);
    PresetOverrides out;
    const nlohmann::json *presets = find_key_path(doc, "rolling.presets");
    if (!presets || presets->is_null())
      return out;
    const std::string where = "rolling.presets." + name;
    if (!presets->is_object() || !presets->contains(name))
      throw InputError(pipeline_file, where, "(missing)",
                       "settings (or null) for every preset: fast, standard, accurate");
    const nlohmann::json &own = presets->at(name);
    if (own.is_null())
      return out;
    if (!own.is_object())
      throw InputError(pipeline_file, where, own.dump(),
                       "a mapping of scene key paths to values, or null");
    for (const auto &[k, v] : own.items())
      out.emplace_back(k, v);
    return out;
  }

  void apply_preset(nlohmann::json &scene, const PresetOverrides &overrides,
                    const std::string &pipeline_file)
  {
    for (const auto &[key, value] : overrides)
      set_key_path(scene, key, value, pipeline_file);
  }
}  // namespace clearjoint::fe
