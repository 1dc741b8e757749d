// The default pipeline.yaml with the fast preset, end to end: FE thickness and misalignment
// sweeps, fits, law families, MBD scenes (the tilted one on the misalignment family), report. Then a second run must do no FE or fit work.
#include "common/strict_reader.h"
#include "laws/law_family.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;
namespace fs = std::filesystem;

TEST(PipelineEndToEnd, FastPresetRunsTheDefaultPipelineThenReusesIt)
{
  test_support::ScratchDir dir("pipeline_e2e");
  const std::string cmd = std::string("cd ") + CLEARJOINT_SOURCE_DIR + " && " + RUN_PIPELINE_EXE +
                          " pipeline.yaml --preset fast --output-root " + dir.path().string();
  const int rc = test_support::run_command(cmd, dir.file("log1.txt"));
  ASSERT_EQ(rc, 0) << test_support::read_text(dir.file("log1.txt"));
  const fs::path run = dir.path() / "default";
  EXPECT_TRUE(fs::exists(run / "report.html"));
  EXPECT_EQ(read_json_file((run / "manifest.json").string())["status"], "complete");

  // Every fitted law fits well (the paper: R² ≥ 0.999) and the force at δ_max grows with the
  // bearing thickness (SPEC §2: what we take as physical).
  const auto family = laws::read_law_family((run / "fit/thickness/family/family.json").string());
  ASSERT_EQ(family.members().size(), 5u);
  double previous = 0.0;
  for (const auto &m : family.members())
  {
    ASSERT_TRUE(m.law.diagnostics.has_value());
    EXPECT_GT(m.law.diagnostics->r_squared, 0.999) << "t_B = " << m.value;
    const double F = m.law.law.force(m.law.delta_max);
    EXPECT_GT(F, previous) << "t_B = " << m.value;
    previous = F;
  }
  // The misalignment sweep: five laws (1, 1.5, 2, 2.5° and θ_max) in one family over θ in rad,
  // which the tilted scene evaluates. No trend is asserted (SPEC §2: report the trend found).
  const auto tilt = laws::read_law_family((run / "fit/misalignment/family/family.json").string());
  EXPECT_EQ(tilt.unit(), "rad");
  ASSERT_EQ(tilt.members().size(), 5u);
  // θ_max of the default geometry, 3.2842259° (docs/geometry.md); 1e-8 rad covers the 7 digits
  // written here (±5e-8° = 9e-10 rad) with room, and is far below the 0.5° member spacing.
  EXPECT_NEAR(tilt.members().back().value, 3.2842259 * 3.14159265358979 / 180.0, 1e-8);
  const auto tilted = read_json_file((run / "mbd/tilted_1deg/summary.json").string());
  EXPECT_EQ(tilted["clearance_joints"][0]["normal_model"]["name"], "law_family");

  for (const auto &name : {"fe_law", "johnson", "ideal", "tilted_1deg", "fe_law_damped_paper"})
    EXPECT_TRUE(fs::exists(run / "mbd" / name / "timeseries.csv")) << name;

  // Second run: nothing changed, so no task runs.
  ASSERT_EQ(test_support::run_command(cmd, dir.file("log2.txt")), 0);
  const auto summary = read_json_file((run / "pipeline_summary.json").string());
  int ran = 0;
  for (const auto &t : summary["tasks"])
    ran += t["outcome"] == "ran";
  EXPECT_EQ(ran, 0) << test_support::read_text(dir.file("log2.txt"));
}
