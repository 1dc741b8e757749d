#include "pipeline/sweep_values.h"

#include "common/error.h"
#include "common/units.h"
#include "pipeline/scene_builder.h"

#include <cmath>

namespace clearjoint::pipeline
{
  geometry::JointGeometry scene_joint_geometry(const nlohmann::json &scene,
                                               const std::string &scene_file)
  {
    geometry::JointGeometry g;  // the FE stage's defaults (fe_stage/scene.h agrees)
    const nlohmann::json *G = find_key_path(scene, "geometry");
    if (G && !G->is_null())
    {
      if (!G->is_object())
        throw InputError(scene_file, "geometry", G->dump(), "a mapping of geometry keys");
      for (const auto &[key, field] : {std::pair{"R_B", &g.R_B}, {"t_B", &g.t_B},
                                       {"L_B", &g.L_B}, {"c_r", &g.c_r}, {"c_a", &g.c_a}})
        if (G->contains(key))
        {
          const auto &v = (*G)[key];
          if (!v.is_number())
            throw InputError(scene_file, std::string("geometry.") + key, v.dump(),
                             "a number in m, > 0");
          *field = v.get<double>();
        }
    }
    g.validate(scene_file, "geometry");
    return g;
  }

  namespace
  {
    double resolve_theta_max(const PipelineConfig &config, const FeSweep &sweep,
                             const std::string &values_key)
    {
      for (const std::string k : {"geometry.R_B", "geometry.L_B", "geometry.c_r", "geometry.c_a"})
        if (sweep.key == k)
          throw InputError(config.source, values_key, theta_max_keyword,
                           "numbers only, in a sweep of " + sweep.key,
                           "theta_max depends on " + sweep.key + ", so it differs per case");
      if (sweep.unit != "deg" && sweep.unit != "rad")
        throw InputError(config.source, values_key, theta_max_keyword,
                         "numbers in " + sweep.unit + ", or theta_max only in a sweep whose "
                         "parameter unit is deg or rad",
                         "theta_max is an angle");
      const Overrides overrides = sweep_overrides(sweep, config.preset);
      const std::string where = sweep.scene + " (preset " + config.preset +
                                (overrides.empty() ? "" : ", with the sweep's overrides") + ")";
      const auto scene = compose_scene(config, sweep.scene, "fe", overrides);
      const auto g = scene_joint_geometry(scene, where);
      const auto theta = geometry::theta_max(g);
      if (!theta)
        throw InputError(config.source, values_key, theta_max_keyword,
                         "numbers in " + sweep.unit + ", or theta_max for a joint where paper "
                         "Eq. 3 has a root",
                         "Eq. 3 has no root for the geometry of " + where + " (R_B = " +
                           format_value(g.R_B) + " m, c_r = " + format_value(g.c_r) +
                           " m, L_B = " + format_value(g.L_B) + " m, c_a = " +
                           format_value(g.c_a) + " m): the journal can turn over inside the "
                           "bearing, so there is no largest tilt (docs/geometry.md)");
      return sweep.unit == "deg" ? geometry::degrees(*theta) : *theta;
    }
  } // namespace

  void resolve_value_keywords(PipelineConfig &config)
  {
    for (std::size_t s = 0; s < config.fe_sweeps.size(); ++s)
    {
      FeSweep &sweep = config.fe_sweeps[s];
      const std::string key = config.fe_sweeps_key + "[" + std::to_string(s) + "].values";
      for (std::size_t i = 0; i < sweep.values.size(); ++i)
        if (sweep.keywords[i] == theta_max_keyword)
          sweep.values[i] = resolve_theta_max(config, sweep, key + "[" + std::to_string(i) + "]");
      for (std::size_t i = 1; i < sweep.values.size(); ++i)
        if (!(sweep.values[i] > sweep.values[i - 1]))
        {
          std::string shown;
          for (std::size_t j = 0; j < sweep.values.size(); ++j)
            shown += (j ? ", " : "") + (sweep.keywords[j].empty()
                                          ? value_label(sweep.values[j])
                                          : sweep.keywords[j] + " = " + value_label(sweep.values[j]));
          throw InputError(config.source, key, "[" + shown + "] " + sweep.unit,
                           "strictly increasing values (after resolving keywords)");
        }
    }
    for (auto &run : config.mbd_runs)
      for (auto &law : run.laws)
        if (!law.value_keyword.empty())
          for (const auto &sweep : config.fe_sweeps)
            if (law.sweep && sweep.name == *law.sweep)
              for (std::size_t i = 0; i < sweep.values.size(); ++i)
                if (sweep.keywords[i] == law.value_keyword)
                  law.value = sweep.values[i];
  }

  SiValue to_si(const double value, const std::string &unit)
  {
    if (unit == "deg")
      return {value * units::deg, "rad"};
    if (unit == "mm")
      return {value * units::mm, "m"};
    return {value, unit};
  }
} // namespace clearjoint::pipeline
