// Bearing geometry from a file (issue 6, "geometry swap"): an FE scene's `geometry.mesh` names
// either a Gmsh MSH 2.2 mesh (used as it is; its content enters the FE task's identity through
// the scene's file inputs) or a Gmsh .geo, which run_pipeline first meshes in a task of its
// own with scripts/make_mesh and then substitutes by the .msh it wrote.
#pragma once

#include "pipeline/task_runner.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  /// The scene's geometry.mesh if it names a .geo file (absolute), nullopt if the scene has no
  /// geometry.mesh or it names an existing .msh. InputError naming `scene_file` and the key
  /// for anything else (not a string, a missing file, another extension).
  std::optional<std::string> geo_to_mesh(const nlohmann::json &scene, const std::string &scene_file);

  /// The .geo and every file it Includes (recursively, relative to the including file): their
  /// contents are the mesh task's inputs.
  std::vector<std::string> geo_files(const std::string &geo);

  /// scripts/make_mesh: $CLEARJOINT_MAKE_MESH, else the source tree's copy.
  std::string make_mesh_script();

  /// True if `gmsh` is an executable on $PATH.
  bool gmsh_on_path();

  /// The task `make_mesh GEO {out}/mesh.msh -setnumber NAME VALUE ...` with NAME VALUE the
  /// joint's R_B, t_B, L_B, c_r, c_a [m] (so the mesh is the joint the scene describes) and then
  /// `parameters`. Its output folder is <run_dir>/mesh/<geo stem>-<hash of the arguments>, so
  /// cases that need the same mesh share one task. msh_check is taken from build_dir.
  Task make_mesh_task(const std::string &geo, const std::map<std::string, double> &joint,
                      const std::map<std::string, double> &parameters, const std::string &run_dir,
                      const std::string &build_dir);

  /// run_pipeline --check (and every run's check): the mesh task's .geo is parsed by Gmsh with
  /// the task's -setnumber values (`gmsh -0`: read and written back unrolled, not meshed, ~0.2 s)
  /// so that a .geo Gmsh cannot read is an input error before the first task rather than a
  /// failed mesh task. InputError naming `where` and geometry.mesh with Gmsh's first error.
  void check_geo_parses(const Task &mesh_task, const std::string &where);
} // namespace clearjoint::pipeline
