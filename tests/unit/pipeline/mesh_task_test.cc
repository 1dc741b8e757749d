// geometry.mesh in an FE scene: which files are accepted, and the make_mesh task for a .geo.
#include "common/error.h"
#include "pipeline/mesh_task.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace clearjoint;
using namespace clearjoint::pipeline;
namespace fs = std::filesystem;

namespace
{
  const std::string geometries = std::string(CLEARJOINT_SOURCE_DIR) + "/fe_stage/geometries";

  std::string error_for(const nlohmann::json &mesh)
  {
    return test_support::input_error_of(
      [&] { geo_to_mesh({{"geometry", {{"mesh", mesh}}}}, "scene.yaml"); });
  }
} // namespace

TEST(MeshTask, WhatGeometryMeshMayName)
{
  test_support::ScratchDir dir("mesh_task_names");
  test_support::write_text(dir.file("a.msh"), "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
  test_support::write_text(dir.file("a.stl"), "solid\n");
  EXPECT_FALSE(geo_to_mesh(nlohmann::json::object(), "s.yaml")) << "no mesh: generated";
  EXPECT_FALSE(geo_to_mesh({{"geometry", {{"t_B", 0.004}}}}, "s.yaml"));
  EXPECT_FALSE(geo_to_mesh({{"geometry", {{"mesh", dir.file("a.msh")}}}}, "s.yaml"))
    << "a .msh is used as it is";
  const auto geo = geo_to_mesh({{"geometry", {{"mesh", geometries + "/default_joint.geo"}}}}, "s.yaml");
  ASSERT_TRUE(geo);
  EXPECT_EQ(*geo, geometries + "/default_joint.geo");
  for (const auto &[mesh, needle] :
       std::vector<std::pair<nlohmann::json, std::string>>{
         {dir.file("missing.msh"), "no such file"},
         {"relative/a.msh", "no such file"},  // still relative: it named no existing file
         {dir.file("a.stl"), "unknown extension '.stl'"},
         {3, "an existing Gmsh file"}})
  {
    const std::string m = error_for(mesh);
    EXPECT_NE(m.find("scene.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("geometry.mesh"), std::string::npos) << m;
    EXPECT_NE(m.find(needle), std::string::npos) << m;
  }
}

TEST(MeshTask, GeoInputsIncludeItsIncludes)
{
  const auto files = geo_files(geometries + "/default_joint.geo");
  EXPECT_EQ(files.front(), fs::canonical(geometries + "/default_joint.geo").string());
  EXPECT_NE(std::find(files.begin(), files.end(),
                      fs::canonical(geometries + "/journal.geo_inc").string()),
            files.end())
    << "changing the included journal must re-mesh";
}

TEST(MeshTask, TheTaskPassesTheJointAndTheSweepsNumbers)
{
  const std::map<std::string, double> joint = {
    {"R_B", 0.01}, {"t_B", 0.006}, {"L_B", 0.02}, {"c_r", 5e-4}, {"c_a", 1e-3}};
  const Task t = make_mesh_task(geometries + "/flanged_bearing.geo", joint, {{"h", 2e-3}},
                                "/tmp/run", "/b");
  const std::string args = [&] {
    std::string s;
    for (const auto &a : t.args)
      s += a + " ";
    return s;
  }();
  EXPECT_EQ(t.args.at(1), "{out}/mesh.msh");
  EXPECT_NE(args.find("-setnumber t_B 0.006 "), std::string::npos) << args;
  EXPECT_NE(args.find("-setnumber h 0.002 "), std::string::npos) << args;
  EXPECT_NE(args.find("-setnumber c_r 0.0005 "), std::string::npos) << args;
  EXPECT_EQ(t.launcher.back(), "MSH_CHECK=/b/geometry/msh_check");
  EXPECT_EQ(fs::path(t.output_dir).parent_path(), "/tmp/run/mesh");
  EXPECT_EQ(fs::path(t.output_dir).filename().string().rfind("flanged_bearing-", 0), 0u);
  // The same numbers share a folder (and a task); other numbers get another one.
  EXPECT_EQ(make_mesh_task(geometries + "/flanged_bearing.geo", joint, {{"h", 2e-3}}, "/tmp/run", "/b")
              .output_dir,
            t.output_dir);
  EXPECT_NE(make_mesh_task(geometries + "/flanged_bearing.geo", joint, {{"h", 1e-3}}, "/tmp/run", "/b")
              .output_dir,
            t.output_dir);
  // A sweep's number for a joint key wins (the user asked for it explicitly).
  const Task u = make_mesh_task(geometries + "/flanged_bearing.geo", joint, {{"t_B", 0.005}},
                                "/tmp/run", "/b");
  std::string uargs;
  for (const auto &a : u.args)
    uargs += a + " ";
  EXPECT_NE(uargs.find("-setnumber t_B 0.005 "), std::string::npos) << uargs;
  EXPECT_EQ(uargs.find("0.006"), std::string::npos) << uargs;
}
