// The presets' measured errors: read strictly, printed per FE sweep, tabulated for the report.
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
           "fe_sweeps:\n"
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

TEST(Presets, ErrorsPerSweepArePrintedWithWhereTheyWereMeasured)
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

// The summary lists a block's own settings per preset beside the preset's `fe` map: the rolling
// study's (rolling.presets.<p>) under `rolling`, {} for a null entry, null without them.
TEST(Presets, SummaryListsTheRollingStudysOwnSettings)
{
  test_support::ScratchDir dir("presets_rolling_own");
  test_support::write_text(
    dir.file("p.yaml"), pipeline_text("measured: {note: x, error_F_max: {}}") +
                          "rolling:\n  scene: r.yaml\n  overrides: {rolling.n_steps: 8}\n"
                          "  presets: {fast: {mesh.contact_refinements: 0, rolling.n_steps: 32}, "
                          "standard: {rolling.n_steps: 64}, accurate: null}\n");
  const auto s = presets_summary(read_pipeline_config(dir.file("p.yaml")));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0]["rolling"],
            (nlohmann::json{{"mesh.contact_refinements", 0}, {"rolling.n_steps", 32}}))
    << s[0].dump();
  EXPECT_EQ(s[1]["rolling"], (nlohmann::json{{"rolling.n_steps", 64}})) << s[1].dump();
  EXPECT_EQ(s[2]["rolling"], nlohmann::json::object()) << "null: nothing extra; " << s[2].dump();
  EXPECT_TRUE(s[0]["fe"].empty()) << "not mixed into the preset's own map: " << s[0].dump();
  // Without the block's presets, or without a rolling study: null.
  test_support::write_text(dir.file("q.yaml"),
                           pipeline_text("measured: {note: x, error_F_max: {}}") +
                             "rolling: {scene: r.yaml}\n");
  EXPECT_TRUE(presets_summary(read_pipeline_config(dir.file("q.yaml")))[0]["rolling"].is_null());
  EXPECT_TRUE(presets_summary(read(dir, measured))[0]["rolling"].is_null());
}

// ... and the impact study's (impact.presets.<p>) under `impact`, the same way.
TEST(Presets, SummaryListsTheImpactStudysOwnSettings)
{
  test_support::ScratchDir dir("presets_impact_own");
  const std::string impact = "impact:\n  scene: i.yaml\n  law: {file: l.json}\n";
  test_support::write_text(dir.file("p.yaml"),
                           pipeline_text("measured: {note: x, error_F_max: {}}") + impact +
                             "  presets: {fast: null, standard: {mesh.adaptive_cycles: 2}, "
                             "accurate: {mesh.adaptive_cycles: 3}}\n");
  const auto s = presets_summary(read_pipeline_config(dir.file("p.yaml")));
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0]["impact"], nlohmann::json::object()) << "null: nothing extra; " << s[0].dump();
  EXPECT_EQ(s[1]["impact"], (nlohmann::json{{"mesh.adaptive_cycles", 2}})) << s[1].dump();
  EXPECT_EQ(s[2]["impact"], (nlohmann::json{{"mesh.adaptive_cycles", 3}})) << s[2].dump();
  EXPECT_TRUE(s[1]["rolling"].is_null()) << "not the rolling study's: " << s[1].dump();
  test_support::write_text(dir.file("q.yaml"),
                           pipeline_text("measured: {note: x, error_F_max: {}}") + impact);
  EXPECT_TRUE(presets_summary(read_pipeline_config(dir.file("q.yaml")))[0]["impact"].is_null());
}

// Issue 32 item 2: what bench/measure_presets.py writes besides the figures above — per-sweep
// case times and DoFs, the machine and the date — read strictly; a bad value names its key.
TEST(Presets, MeasuredMachineDateAndPerSweepFigures)
{
  test_support::ScratchDir dir("presets_per_sweep");
  const auto c = read(dir, "measured: {note: x, date: '2026-11-28 10:00 UTC', "
                           "machine: {cpu: Some CPU, cores: 2}, fe_case_time: 2.3, "
                           "case_times: {misalignment: 1.9}, dofs: {thickness: 3588, misalignment: 2418}, "
                           "error_F_max: {}}");
  const auto &m = c.preset_measured.at("fast");
  EXPECT_EQ(m.date, "2026-11-28 10:00 UTC");
  EXPECT_EQ(m.machine_cpu, "Some CPU");
  EXPECT_EQ(*m.machine_cores, 2);
  EXPECT_EQ(m.case_times.at("misalignment"), 1.9);
  EXPECT_EQ(m.dofs.at("misalignment"), 2418.0);
  // an FE case's figure: its sweep's own case time, else fe_case_time
  EXPECT_EQ(task_figure(c, "fe_stage", "misalignment")->first, "case_times.misalignment");
  EXPECT_EQ(task_figure(c, "fe_stage", "misalignment")->second, 1.9);
  EXPECT_EQ(task_figure(c, "fe_stage", "thickness")->first, "fe_case_time");
  EXPECT_FALSE(task_figure(c, "fe_impact").has_value());  // not measured
  EXPECT_FALSE(task_figure(c, "fit_stage").has_value());  // no figure of its own
  const auto s = presets_summary(c);
  EXPECT_EQ(s[0]["measured"]["case_times"]["misalignment"]["value"], 1.9);
  EXPECT_EQ(s[0]["measured"]["dofs"]["thickness"]["unit"], "1");
  EXPECT_EQ(s[0]["measured"]["machine"]["cores"], 2);
  EXPECT_EQ(s[0]["measured"]["date"], "2026-11-28 10:00 UTC");

  // negative time, unknown sweep, non-numeric values: input errors naming the key
  std::string e = error_for("measured: {note: x, case_times: {misalignment: -1}, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.case_times.misalignment"), std::string::npos) << e;
  e = error_for("measured: {note: x, case_times: {radial: 2}, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.case_times.radial"), std::string::npos) << e;
  EXPECT_NE(e.find("thickness|misalignment"), std::string::npos) << e;
  e = error_for("measured: {note: x, dofs: {impact: 1782}, error_F_max: {}}");  // no impact study
  EXPECT_NE(e.find("presets.fast.measured.dofs.impact"), std::string::npos) << e;
  e = error_for("measured: {note: x, case_times: {thickness: fast}, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.case_times.thickness"), std::string::npos) << e;
  e = error_for("measured: {note: x, fe_case_time: two, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.fe_case_time"), std::string::npos) << e;
  e = error_for("measured: {note: x, impact_time: -14, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.impact_time"), std::string::npos) << e;
  // the deformable impact's time without its study (issue 31 item 2)
  e = error_for("measured: {note: x, impact_deformable_time: 40, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.impact_deformable_time"), std::string::npos) << e;
  e = error_for("measured: {note: x, case_times: 3, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.case_times"), std::string::npos) << e;
  e = error_for("measured: {note: x, machine: {cpu: c, cores: 0}, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.machine.cores"), std::string::npos) << e;
  e = error_for("measured: {note: x, machine: {cpu: c}, error_F_max: {}}");
  EXPECT_NE(e.find("presets.fast.measured.machine.cores"), std::string::npos) << e;
}

// A figure is stale when the run misses it by more than 1.5x either way.
TEST(Presets, FigureMissedEitherWay)
{
  EXPECT_FALSE(figure_missed(10.0, 10.0));
  EXPECT_FALSE(figure_missed(15.0, 10.0));
  EXPECT_TRUE(figure_missed(15.1, 10.0));   // the run slower
  EXPECT_FALSE(figure_missed(10.0, 15.0));
  EXPECT_TRUE(figure_missed(10.0, 15.1));   // the figure too high
  EXPECT_EQ(describe_against_figure("fast", 2.4, 2.3), "preset fast measured 2.3 s");
  const std::string stale = describe_against_figure("standard", 449.0, 260.0);
  EXPECT_NE(stale.find("preset standard measured"), std::string::npos) << stale;
  EXPECT_NE(stale.find("1.7x that: figure stale?"), std::string::npos) << stale;
}

// fe_stage's own estimate of the error of F(delta_max) (issue 32 item 4): read from an adaptive
// case's manifest as fe_stage writes it (fe_stage/results/case_output.cc), its kind named, and
// set beside the preset's measured figure, or named the figure to use where there is none.
TEST(Presets, OwnErrorEstimateOfAnAdaptiveCase)
{
  const auto manifest = [](const std::string &method) {
    return nlohmann::json::parse(R"({"status": "complete", "extra": {"adaptive": {
      "cycles": [{"n_dofs": 9315}, {"n_dofs": 22992}, {"n_dofs": 57501}],
      "estimated_error_F_max": {"value": 0.0085, "unit": "1", "method": ")" +
                                 method + R"("}, "fraction": 0.2}}})");
  };
  const auto e = read_own_error_estimate(
    manifest("last two cycles extrapolated with F = F_inf + C N^-q, q = 0.667"));
  ASSERT_TRUE(e.has_value());
  EXPECT_DOUBLE_EQ(e->relative, 0.0085);
  EXPECT_FALSE(e->last_change);
  EXPECT_EQ(e->n_meshes, 3);
  EXPECT_EQ(*e->n_dofs, 57501.0);
  EXPECT_EQ(describe_own_estimate(*e), "0.85 % (extrapolated)");
  // the last cycle's change: not extrapolated and no bound either way, said with how it
  // compared with the error on the recorded sequences (bench/adaptive_estimate_table.py)
  const auto b =
    read_own_error_estimate(manifest("change in the last cycle (not extrapolated; not a bound)"));
  ASSERT_TRUE(b.has_value());
  EXPECT_TRUE(b->last_change);
  EXPECT_EQ(describe_own_estimate(*b),
            "~0.85 % (the change in the last cycle, not extrapolated: on the recorded sequences "
            "it was 0.05-29x the error, median 1.12)");
  EXPECT_EQ(describe_own_estimate(*b).find("bound"), std::string::npos);
  // a manifest written before the relabelling ("(a lower bound)") is read the same way
  const auto old = read_own_error_estimate(manifest("change in the last cycle (a lower bound)"));
  ASSERT_TRUE(old.has_value());
  EXPECT_TRUE(old->last_change);
  EXPECT_EQ(describe_own_estimate(*old), describe_own_estimate(*b));
  // no adaptive cycles, a single mesh (no estimate), not a manifest: none
  EXPECT_FALSE(read_own_error_estimate(nlohmann::json::parse(R"({"extra": {"n_dofs": 3588}})")));
  EXPECT_FALSE(read_own_error_estimate(
    nlohmann::json::parse(R"({"extra": {"adaptive": {"cycles": [{"n_dofs": 3588}]}}})")));
  EXPECT_FALSE(read_own_error_estimate(nlohmann::json::array()));

  // beside the preset's figure (thickness: 4.8 %), or the figure to use (misalignment: null;
  // standard states none for either)
  test_support::ScratchDir dir("presets_own_estimate");
  auto c = read(dir, measured);
  const std::map<std::string, OwnErrorEstimate> estimates = {{"t_B=0.004", *e},
                                                             {"t_B=0.006", *b}};
  std::string text = describe_own_estimates(c, "thickness", estimates);
  EXPECT_EQ(text, "own estimate of the error of F(delta_max): t_B=0.004 0.85 % (extrapolated), "
                  "t_B=0.006 ~0.85 % (the change in the last cycle, not extrapolated: on the "
                  "recorded sequences it was 0.05-29x the error, median 1.12); preset fast "
                  "measured 4.8 %");
  text = describe_own_estimates(c, "misalignment", estimates);
  EXPECT_NE(text.find("; preset fast: not measured for this sweep, so the run's own estimate is "
                      "the figure to use"),
            std::string::npos)
    << text;
  c.preset = "standard";
  text = describe_own_estimates(c, "thickness", estimates);
  EXPECT_NE(text.find("preset standard: not measured for this sweep"), std::string::npos) << text;
}
