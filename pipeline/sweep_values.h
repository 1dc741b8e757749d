// The values of an FE sweep: the `theta_max` keyword resolved from the sweep's scene geometry
// (paper Eq. 3), and the SI form in which a law family stores them.
#pragma once

#include "geometry/joint_geometry.h"
#include "pipeline/pipeline_config.h"

#include <nlohmann/json.hpp>

#include <string>

namespace clearjoint::pipeline
{
  /// The joint an FE scene describes: geometry.R_B, t_B, L_B, c_r, c_a [m]; a key the scene
  /// does not set takes the FE stage's default, which is geometry::JointGeometry's (R_B 10 mm,
  /// t_B 4 mm, L_B 20 mm, c_r 0.5 mm, c_a 1 mm). Validated; InputError names `scene_file` and
  /// the key. (geometry.mesh does not change these: the FE contract keeps them as the joint's
  /// description.)
  geometry::JointGeometry scene_joint_geometry(const nlohmann::json &scene,
                                               const std::string &scene_file);

  /// Replaces each keyword in the sweeps' values by its number and sets the laws' values that
  /// name a keyword. `theta_max` is geometry::theta_max() of the sweep's scene after the preset
  /// and the sweep's overrides, in the sweep's unit (deg or rad), at full precision. Throws
  /// InputError naming the pipeline file and key when the unit is not an angle, when Eq. 3 has
  /// no root for that geometry, when the swept key changes that geometry, or when the values
  /// are then not strictly increasing.
  void resolve_value_keywords(PipelineConfig &config);

  /// A value in a sweep's unit converted to SI, as law families store their parameter
  /// (fit_stage --family takes SI; mbd_stage evaluates a family at the tilt θ in rad):
  /// deg → rad, mm → m; any other unit is taken as SI already and kept.
  struct SiValue
  {
    double value;
    std::string unit;
  };
  SiValue to_si(double value, const std::string &unit);
} // namespace clearjoint::pipeline
