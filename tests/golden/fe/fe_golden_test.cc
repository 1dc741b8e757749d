// fe_stage end to end: what the fit stage relies on (SPEC §1, issue 3 item 1) and golden forces.
#include "common/csv.h"
#include "common/strict_reader.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  fs::path run_fe_stage(const std::string &name, const std::string &scene_body, int &exit_code)
  {
    const fs::path dir = fs::temp_directory_path() / ("clearjoint_fe_golden_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "scene.yaml") << "schema: clearjoint.fe/1\n" << scene_body;
    const std::string cmd = std::string(FE_STAGE_EXE) + " " + (dir / "scene.yaml").string() +
                            " --output " + (dir / "out").string() + " -q > " +
                            (dir / "log.txt").string() + " 2>&1";
    const int status = std::system(cmd.c_str());
    exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return dir;
  }
} // namespace

// The coarse two-body end_faces curve. Golden values from this code on 2026-11-22 (quarter model,
// 16 x 1 x 3 coarse cells, Q2, frictionless). Tolerance 1e-6 relative: the linear solves are
// converged to 1e-10 and the active set is deterministic; a change beyond it is a change of the
// model or the mesh, not noise.
TEST(FeGolden, CoarseEndFacesCurveAndOutputContract)
{
  int code = -1;
  const fs::path dir = run_fe_stage(
    "end_faces",
    "contact: {mu: 0}\n"
    "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n"
    "loading: {journal: end_faces, n_increments: 3}\n",
    code);
  ASSERT_EQ(code, 0);
  const fs::path out = dir / "out";
  const CsvTable t = read_csv((out / "force_penetration.csv").string());
  EXPECT_EQ(t.status, "complete");
  ASSERT_TRUE(t.has_column("delta") && t.has_column("force"));
  EXPECT_EQ(t.unit_of("delta"), "m");
  EXPECT_EQ(t.unit_of("force"), "N");
  for (const char *c : {"contact_iterations", "linear_iterations", "active_contact_points",
                        "wall_time", "force_support", "force_load"})
    EXPECT_TRUE(t.has_column(c)) << c;
  ASSERT_EQ(t.rows.size(), 4u);  // origin + 3 increments
  const auto delta = t.column("delta"), force = t.column("force");
  EXPECT_EQ(delta[0], 0.0);
  EXPECT_EQ(force[0], 0.0);
  const double golden[] = {6008.658508, 12988.6965, 19968.7345};  // [N]
  for (int i = 0; i < 3; ++i)
    {
      EXPECT_NEAR(delta[i + 1], 0.05e-3 * (i + 1) / 3.0, 1e-15);
      EXPECT_NEAR(force[i + 1] / golden[i], 1.0, 1e-6) << "increment " << i + 1;
    }
  const auto manifest = read_json_file((out / "manifest.json").string());
  EXPECT_EQ(manifest.at("status"), "complete");
  EXPECT_FALSE(manifest.at("extra").at("friction_modelled").get<bool>());
  EXPECT_TRUE(fs::exists(out / "fields" / "solution.pvd"));
  EXPECT_TRUE(fs::exists(out / "fields" / "solution_0003.pvtu"));
  fs::remove_all(dir);
}

// A run that cannot converge keeps what it reached and says so: exit 2, CSV and manifest
// marked incomplete.
TEST(FeGolden, FailedRunIsMarkedIncomplete)
{
  int code = -1;
  const fs::path dir = run_fe_stage(
    "fail",
    "contact: {mu: 0, max_iterations: 1}\n"
    "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n"
    "loading: {journal: rigid, n_increments: 2, max_cuts: 1}\n"
    "output: {fields: false}\n",
    code);
  EXPECT_EQ(code, 2);
  const CsvTable t = read_csv((dir / "out" / "force_penetration.csv").string());
  EXPECT_NE(t.status.find("incomplete"), std::string::npos) << t.status;
  EXPECT_EQ(t.rows.size(), 1u);  // only the origin was reached
  const auto manifest = read_json_file((dir / "out" / "manifest.json").string());
  EXPECT_EQ(manifest.at("status"), "incomplete");
  fs::remove_all(dir);
}

// The thickness sweep in one command: one folder per case (CSV, manifest), DIR/sweep.csv and a
// top-level manifest; the force at δ_max grows with t_B (SPEC §2).
TEST(FeGolden, ThicknessSweepOneFolderPerCase)
{
  int code = -1;
  const fs::path dir = run_fe_stage(
    "sweep",
    "contact: {mu: 0}\n"
    "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n"
    "loading: {n_increments: 2}\n"
    "output: {fields: false}\n"
    "sweep: {t_B: [2.0e-3, 4.0e-3, 6.0e-3]}\n",
    code);
  ASSERT_EQ(code, 0);
  const fs::path out = dir / "out";
  double previous = 0.0;
  for (const char *name : {"t_B_2mm", "t_B_4mm", "t_B_6mm"})
    {
      const CsvTable t = read_csv((out / name / "force_penetration.csv").string());
      EXPECT_EQ(t.status, "complete") << name;
      const double F = t.column("force").back();
      EXPECT_GT(F, previous) << name;
      previous = F;
      EXPECT_EQ(read_json_file((out / name / "manifest.json").string()).at("status"), "complete");
    }
  const CsvTable sweep = read_csv((out / "sweep.csv").string());
  EXPECT_EQ(sweep.status, "complete");
  EXPECT_EQ(sweep.rows.size(), 3u);
  EXPECT_EQ(read_json_file((out / "manifest.json").string()).at("status"), "complete");
  fs::remove_all(dir);
}
