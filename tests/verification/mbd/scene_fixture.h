// Helpers for MBD verification/extreme tests: load a shipped scene, change it, run it.
#pragma once

#include "common/log.h"
#include "common/strict_reader.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <cmath>
#include <functional>
#include <string>

namespace clearjoint::mbd::testing
{
  /// Simulations log progress and warnings; the scene tests keep only errors on the console.
  struct QuietLogs
  {
    QuietLogs() { log::set_level(log::Level::error); }
  };
  inline const QuietLogs quiet_logs;

  inline std::string scenes_dir()
  {
    return std::string(CLEARJOINT_SOURCE_DIR) + "/mbd_stage/scenes";
  }

  inline nlohmann::json load_scene(const std::string &name)
  {
    return read_yaml_file(scenes_dir() + "/" + name + ".yaml");
  }

  inline SimulationResult run(const nlohmann::json &doc)
  {
    Scene scene = scene_from_json(doc, "test scene", scenes_dir());
    return simulate(scene);
  }

  /// True if every value of every output row is finite.
  inline bool all_finite(const SimulationResult &r)
  {
    for (const auto &row : r.rows)
      for (const double v : row)
        if (!std::isfinite(v))
          return false;
    return true;
  }

  /// Multiplies every body's initial velocity and angular velocity by `factor`.
  inline void scale_speed(nlohmann::json &doc, const double factor)
  {
    for (auto &b : doc["bodies"])
      for (const char *k : {"velocity", "angular_velocity"})
        for (auto &v : b[k])
          v = v.get<double>() * factor;
  }
} // namespace clearjoint::mbd::testing
