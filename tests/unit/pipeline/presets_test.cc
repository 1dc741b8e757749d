// The presets' measured errors: read strictly, printed per FE study, tabulated for the report.
#include "common/error.h"
#include "pipeline/pipeline_config.h"
#include "pipeline/presets.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;
using namespace clearjoint::pipeline;

namespace
{
  const std::string measured =
    "measured: {note: bench, fe_dofs: 3588, fe_case_time: 2.8, pipeline_time: null, "
    "error_F_max: {thickness: {percent: 4.8, where: t_B = 4 mm}, "
    "misalignment: {percent: null, where: to be measured}}}";

  std::string pipeline(const std::string &fast_measured)
  {
    return "schema: clearjoint.pipeline/1\nrun: r\npreset: fast\n"
           "presets:\n  fast: {fe: null, mbd: null, " + fast_measured + "}\n"
           "  standard: {fe: {mesh.level: 1}, mbd: null}\n  accurate: {fe: null, mbd: null}\n"
           "fe_studies:\n"
           "  - {name: thickness, scene: fe.yaml, parameter: {name: t_B, unit: m, key: geometry.t_B}, values: [0.004]}\n"
           "  - {name: misalignment, scene: fe.yaml, parameter: {name: theta, unit: deg, key: m.t}, values: [1.0]}\n"
           "fit: {weighting: absolute}\nmbd_runs: []\n";
  }

  std::string pipeline_text(const std::string &fast_measured) { return pipeline(fast_measured); }

  PipelineConfig read(const test_support::ScratchDir &dir, const std::string &fast_measured)
  {
    test_support::write_text(dir.file("p.yaml"), pipeline(fast_measured));
    return read_pipeline_config(dir.file("p.yaml"));
  }

  std::string error_for(const std::string &fast_measured)
  {
    test_support::ScratchDir dir("presets_bad");
    return test_support::input_error_of([&] { read(dir, fast_measured); });
  }
} // namespace

TEST(Presets, ErrorsPerStudyArePrintedWithWhereTheyWereMeasured)
{
  test_support::ScratchDir dir("presets_good");
  const auto c = read(dir, measured);
  const std::string text = describe_preset_errors(c, "fast");
  EXPECT_NE(text.find("preset fast"), std::string::npos) << text;
  EXPECT_NE(text.find("thickness: 4.8 % (t_B = 4 mm)"), std::string::npos) << text;
  EXPECT_NE(text.find("misalignment: NOT YET MEASURED (to be measured)"), std::string::npos) << text;
  const std::string other = describe_preset_errors(c, "standard");
  EXPECT_NE(other.find("thickness: not stated in pipeline.yaml"), std::string::npos) << other;
}

TEST(Presets, SummaryListsEveryPresetAndMarksTheChosenOne)
{
  test_support::ScratchDir dir("presets_summary");
  const auto s = presets_summary(read(dir, measured));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0]["name"], "fast");
  EXPECT_TRUE(s[0]["chosen"].get<bool>());
  EXPECT_FALSE(s[1]["chosen"].get<bool>());
  EXPECT_EQ(s[0]["measured"]["error_F_max"]["thickness"]["percent"], 4.8);
  EXPECT_TRUE(s[0]["measured"]["error_F_max"]["misalignment"]["percent"].is_null());
  EXPECT_EQ(s[0]["measured"]["fe_case_time"]["unit"], "s");
  EXPECT_TRUE(s[0]["measured"]["pipeline_time"].is_null());
  EXPECT_EQ(s[1]["fe"]["mesh.level"], 1);
  EXPECT_TRUE(s[1]["measured"].is_null());
}

TEST(Presets, BadMeasurementsNameTheKey)
{
  std::string m = error_for("measured: {note: x, error_F_max: {thickness: {percent: 4.8, where: a}, "
                            "radial: {percent: 1, where: b}}}");
  EXPECT_NE(m.find("presets.fast.measured.error_F_max.radial"), std::string::npos) << m;
  EXPECT_NE(m.find("thickness|misalignment"), std::string::npos) << m;
  m = error_for("measured: {note: x, error_F_max: {thickness: {percent: 480, where: a}}}");
  EXPECT_NE(m.find("error_F_max.thickness.percent"), std::string::npos) << m;
  EXPECT_NE(m.find("(0, 100) %"), std::string::npos) << m;
  // 100 % is no estimate (and fit_stage --discretisation-error takes [0, 100)).
  m = error_for("measured: {note: x, error_F_max: {thickness: {percent: 100, where: a}}}");
  EXPECT_NE(m.find("error_F_max.thickness.percent"), std::string::npos) << m;
  m = error_for("measured: {note: x, error_F_max: {thickness: {where: a}}}");
  EXPECT_NE(m.find("error_F_max.thickness.percent"), std::string::npos) << m;
  m = error_for("measured: {note: x, error_F_max: {thickness: {percent: 1}}}");
  EXPECT_NE(m.find("error_F_max.thickness.where"), std::string::npos) << m;
  m = error_for("measured: {note: x, fe_case_time: -2, error_F_max: {}}");
  EXPECT_NE(m.find("presets.fast.measured.fe_case_time"), std::string::npos) << m;
  m = error_for("measured: {note: x, error_F_max: {}, colour: red}");
  EXPECT_NE(m.find("presets.fast.measured.colour"), std::string::npos) << m;
}

// The rolling study's own measured time (rolling_time, null = not measured) and its error
// entry: `rolling` may name an error only when the pipeline has a rolling study.
TEST(Presets, RollingTimeAndErrorNeedTheRollingStudy)
{
  const std::string m = "measured: {note: x, rolling_time: 42, error_F_max: "
                        "{rolling: {percent: null, where: not yet}}}";
  const std::string without = error_for(m);
  EXPECT_NE(without.find("presets.fast.measured.error_F_max.rolling"), std::string::npos) << without;
  test_support::ScratchDir dir("presets_rolling");
  test_support::write_text(dir.file("p.yaml"), pipeline_text(m) + "rolling: {scene: r.yaml}\n");
  const auto c = read_pipeline_config(dir.file("p.yaml"));
  ASSERT_TRUE(c.preset_measured.at("fast").rolling_time.has_value());
  EXPECT_EQ(*c.preset_measured.at("fast").rolling_time, 42.0);
  const auto s = presets_summary(c);
  EXPECT_EQ(s[0]["measured"]["rolling_time"]["value"], 42.0);
  EXPECT_EQ(s[0]["measured"]["rolling_time"]["unit"], "s");
  EXPECT_TRUE(s[0]["measured"]["error_F_max"]["rolling"]["percent"].is_null());
  // null: not measured
  test_support::write_text(dir.file("q.yaml"),
                           pipeline_text("measured: {note: x, rolling_time: null, error_F_max: {}}") +
                             "rolling: {scene: r.yaml}\n");
  const auto q = read_pipeline_config(dir.file("q.yaml"));
  EXPECT_FALSE(q.preset_measured.at("fast").rolling_time.has_value());
  EXPECT_TRUE(presets_summary(q)[0]["measured"]["rolling_time"].is_null());
  const std::string bad = error_for("measured: {note: x, rolling_time: -1, error_F_max: {}}");
  EXPECT_NE(bad.find("presets.fast.measured.rolling_time"), std::string::npos) << bad;
}
