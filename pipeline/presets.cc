#include "pipeline/presets.h"

#include "common/log.h"

#include <cstdio>
#include <optional>

namespace clearjoint::pipeline
{
  std::string describe_preset_errors(const PipelineConfig &config, const std::string &preset)
  {
    const auto m = config.preset_measured.find(preset);
    std::string out = "preset " + preset + ": estimated error of F(delta_max) per FE sweep:";
    if (config.fe_sweeps.empty())
      return out + " (no FE sweeps)";
    for (const auto &sweep : config.fe_sweeps)
    {
      out += "\n    " + sweep.name + ": ";
      const PresetError *e = nullptr;
      if (m != config.preset_measured.end())
        if (const auto it = m->second.error_F_max.find(sweep.name); it != m->second.error_F_max.end())
          e = &it->second;
      if (!e)
        out += "not stated in pipeline.yaml";
      else
      {
        if (e->percent)
        {
          char buf[32];
          std::snprintf(buf, sizeof(buf), "%.3g %%", *e->percent);
          out += buf;
        }
        else
          out += "NOT YET MEASURED";
        out += " (" + e->where + ")";
      }
    }
    return out;
  }

  nlohmann::json presets_summary(const PipelineConfig &config)
  {
    nlohmann::json out = nlohmann::json::array();
    for (const auto &name : preset_names())
    {
      nlohmann::json p = {{"name", name}, {"chosen", name == config.preset}};
      p["fe"] = nlohmann::json::object();
      p["mbd"] = nlohmann::json::object();
      if (const auto it = config.presets.find(name); it != config.presets.end())
        for (const auto &[key, value] : it->second)
        {
          const auto colon = key.find(':');
          p[key.substr(0, colon)][key.substr(colon + 1)] = value;
        }
      // A block's own settings for this preset ({key path: value}; {} for a null entry).
      const auto settings = [&name](const PresetOverrides &own) -> std::optional<nlohmann::json> {
        const auto it = own.find(name);
        if (it == own.end())
          return std::nullopt;
        nlohmann::json out = nlohmann::json::object();
        for (const auto &[key, value] : it->second)
          out[key] = value;
        return out;
      };
      // A sweep's own settings for this preset (fe_sweeps[i].presets.<name>), set after its
      // overrides in that sweep's cases only.
      p["sweeps"] = nlohmann::json::object();
      for (const auto &sweep : config.fe_sweeps)
        if (const auto own = settings(sweep.preset_overrides))
          p["sweeps"][sweep.name] = *own;
      // The rolling study's (rolling.presets.<name>), set after rolling.overrides in its scene
      // only; null without a rolling study or without its presets.
      p["rolling"] = nullptr;
      if (config.rolling)
        if (const auto own = settings(config.rolling->preset_overrides))
          p["rolling"] = *own;
      // The rigid journal's impact scene's (impact.presets.<name>), the same way.
      p["impact"] = nullptr;
      if (config.impact)
        if (const auto own = settings(config.impact->preset_overrides))
          p["impact"] = *own;
      p["measured"] = nullptr;
      if (const auto it = config.preset_measured.find(name); it != config.preset_measured.end())
      {
        const PresetMeasured &m = it->second;
        const auto opt = [](const std::optional<double> &v, const char *unit) -> nlohmann::json {
          if (!v)
            return nullptr;
          return {{"value", *v}, {"unit", unit}};
        };
        nlohmann::json errors = nlohmann::json::object();
        for (const auto &[name, e] : m.error_F_max)
          errors[name] = {{"percent", e.percent ? nlohmann::json(*e.percent) : nlohmann::json()},
                           {"where", e.where}};
        p["measured"] = {{"note", m.note},
                         {"fe_dofs", opt(m.fe_dofs, "1")},
                         {"fe_case_time", opt(m.fe_case_time, "s")},
                         {"impact_time", opt(m.impact_time, "s")},
                         {"impact_deformable_time", opt(m.impact_deformable_time, "s")},
                         {"rolling_time", opt(m.rolling_time, "s")},
                         {"pipeline_time", opt(m.pipeline_time, "s")},
                         {"error_F_max", errors}};
        nlohmann::json case_times = nlohmann::json::object(), dofs = nlohmann::json::object();
        for (const auto &[name, seconds] : m.case_times)
          case_times[name] = {{"value", seconds}, {"unit", "s"}};
        for (const auto &[name, n] : m.dofs)
          dofs[name] = {{"value", n}, {"unit", "1"}};
        p["measured"]["case_times"] = case_times;
        p["measured"]["dofs"] = dofs;
        p["measured"]["date"] = m.date.empty() ? nlohmann::json() : nlohmann::json(m.date);
        p["measured"]["machine"] =
          m.machine_cpu.empty() ?
            nlohmann::json() :
            nlohmann::json{{"cpu", m.machine_cpu},
                           {"cores", m.machine_cores ? nlohmann::json(*m.machine_cores) :
                                                       nlohmann::json()}};
      }
      out.push_back(p);
    }
    return out;
  }

  std::string describe_own_estimates(const PipelineConfig &config, const std::string &sweep,
                                     const std::map<std::string, OwnErrorEstimate> &estimates)
  {
    std::string out = "own estimate of the error of F(delta_max):";
    bool first = true;
    for (const auto &[label, e] : estimates)
    {
      out += (first ? " " : ", ") + label + " " + describe_own_estimate(e);
      first = false;
    }
    const PresetError *measured = nullptr;
    if (const auto m = config.preset_measured.find(config.preset); m != config.preset_measured.end())
      if (const auto it = m->second.error_F_max.find(sweep); it != m->second.error_F_max.end())
        measured = &it->second;
    if (measured && measured->percent)
    {
      char buf[32];
      std::snprintf(buf, sizeof(buf), "%.3g %%", *measured->percent);
      return out + "; preset " + config.preset + " measured " + buf;
    }
    return out + "; preset " + config.preset +
           ": not measured for this sweep, so the run's own estimate is the figure to use";
  }

  std::optional<std::pair<std::string, double>> task_figure(const PipelineConfig &config,
                                                            const std::string &stage,
                                                            const std::string &sweep)
  {
    const auto it = config.preset_measured.find(config.preset);
    if (it == config.preset_measured.end())
      return std::nullopt;
    const PresetMeasured &m = it->second;
    const auto named = [](const char *key, const std::optional<double> &v)
      -> std::optional<std::pair<std::string, double>> {
      if (!v)
        return std::nullopt;
      return std::pair<std::string, double>{key, *v};
    };
    if (stage == "fe_stage")
    {
      if (const auto c = m.case_times.find(sweep); c != m.case_times.end())
        return std::pair<std::string, double>{"case_times." + sweep, c->second};
      return named("fe_case_time", m.fe_case_time);
    }
    if (stage == "fe_impact")
      return named("impact_time", m.impact_time);
    if (stage == "fe_impact_deformable")
      return named("impact_deformable_time", m.impact_deformable_time);
    if (stage == "fe_rolling")
      return named("rolling_time", m.rolling_time);
    return std::nullopt;
  }

  std::string describe_against_figure(const std::string &preset, const double run_seconds,
                                      const double figure_seconds)
  {
    std::string out = "preset " + preset + " measured " + log::format_duration(figure_seconds);
    if (figure_missed(run_seconds, figure_seconds))
    {
      char buf[96];
      std::snprintf(buf, sizeof(buf), ", this run %.2gx that: figure stale? (bench/measure_presets.py)",
                    run_seconds / figure_seconds);
      out += buf;
    }
    return out;
  }
} // namespace clearjoint::pipeline
