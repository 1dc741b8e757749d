// The scene file, schema clearjoint.mbd/1 (YAML or JSON), read strictly: unknown or missing
// keys, values out of range, bodies named by joints that do not exist, a law file that is
// missing or of the wrong schema → InputError naming the file, key path, value and range.
// See mbd_stage/scenes/*.yaml for complete examples and docs/mbd.md for every key.
//
// schema: clearjoint.mbd/1
// name: slider_crank_fe_law            # used in outputs
// description: "..."                   # optional
// duration: 0.1                        # s
// gravity: [0, 0, -9.81]               # m/s²
// bodies:        [{name, mass (kg), inertia [Ixx,Iyy,Izz] (kg·m², principal, body axes),
//                  position [m], euler_parameters [e0..e3], velocity [m/s, ground],
//                  angular_velocity [rad/s, ground]}]
// joints:        [{name, type: revolute|translational|spherical|fixed, body_i, body_j,
//                  point [m, ground, at t=0], axis [1, ground, at t=0]}]
// drivers:       [{name, joint (a revolute joint), speed (rad/s)}]         # optional
// clearance_joints: [{name, bearing: {body, center [m], axis}, journal: {body, center, axis},
//                  geometry: {R_B, R_J, L_B, L_J} (m), material: {E_bearing, nu_bearing,
//                  E_journal, nu_journal} (Pa, 1), normal: {...}, axial: {...},
//                  friction: {mu, v0, v1}}]                                # optional
// integrator:    {method: dopri5|bdf, rtol, atol_position (m), atol_velocity (m/s),
//                  max_step (s, 0 = none), output_interval (s)}
// stabilization: {alpha, beta} (1/s)                                       # optional
// outputs:       {slider: {body, axis}, crank: {body, axis}}               # optional
// budget:        {wall_time (s, default 14400), steps (default 1e7),
//                  output_rows (default 1e7: duration / output_interval)}  # optional
#pragma once

#include "mbd_stage/integrator.h"
#include "mbd_stage/multibody_system.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::mbd
{
  inline constexpr const char *scene_schema = "clearjoint.mbd/1";

  struct MonitoredAxis
  {
    std::string body;
    Vector3 axis = Vector3::UnitY();  ///< [1] ground frame
  };

  struct Scene
  {
    std::string file;  ///< where it was read from (for messages and the manifest)
    std::string name, description;
    double duration = 0.0;         ///< [s]
    double output_interval = 0.0;  ///< [s]
    IntegratorSettings integrator;
    std::vector<std::string> input_files;  ///< law files it uses
    std::optional<MonitoredAxis> slider, crank;
    /// A run that exceeds either stops as a numerical failure with its partial outputs marked
    /// incomplete, instead of running unattended for days. The shipped 0.1 s scenes take
    /// < 1 s and ~1000 steps (docs/benchmarks.md), a 10 s run ~1e5 steps: the defaults are
    /// 100 times beyond that.
    double max_wall_time = 14400.0;  ///< [s] budget.wall_time (4 h)
    long max_steps = 10'000'000;     ///< budget.steps: accepted integrator steps
    /// budget.output_rows: rows of timeseries.csv (duration / output_interval + 1), checked
    /// before the run; 1e7 rows are ~5 GB, 10 times a 10 s run at the shipped 1e-5 s.
    long max_output_rows = 10'000'000;
    nlohmann::json raw;  ///< the scene as read (for the summary)
    /// The assembled, finalised system (initial velocities made consistent).
    std::shared_ptr<MultibodySystem> system;
  };

  /// Reads, validates and assembles a scene file.
  Scene read_scene(const std::string &path);
  /// The same from an already parsed document; relative law-file paths are resolved against
  /// base_dir. `file` is used in messages.
  Scene scene_from_json(const nlohmann::json &doc, const std::string &file,
                        const std::string &base_dir);
} // namespace clearjoint::mbd
