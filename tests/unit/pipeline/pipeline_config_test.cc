#include "common/error.h"
#include "pipeline/pipeline_config.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;
using namespace clearjoint::pipeline;

namespace
{
  const std::string good = R"(schema: clearjoint.pipeline/1
run: t
preset: fast
presets:
  fast: {fe: {mesh.level: 0}, mbd: null}
  standard: {fe: null, mbd: null}
  accurate: {fe: null, mbd: null}
fe_studies:
  - name: thickness
    scene: fe.yaml
    parameter: {name: t_B, unit: m, key: geometry.t_B}
    values: [0.002, 0.004]
fit: {weighting: absolute}
mbd_runs:
  - name: a
    scene: m.yaml
    laws:
      - {key: joint.law_file, study: thickness, value: 0.004}
  - name: b
    scene: m.yaml
)";

  std::string error_for(const std::string &from, const std::string &to)
  {
    test_support::ScratchDir dir("pipeline_config");
    std::string text = good;
    const auto p = text.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    text.replace(p, from.size(), to);
    test_support::write_text(dir.file("p.yaml"), text);
    try
    {
      read_pipeline_config(dir.file("p.yaml"));
    }
    catch (const InputError &e)
    {
      return e.what();
    }
    return "(accepted)";
  }
} // namespace

TEST(PipelineConfig, ReadsAGoodFile)
{
  test_support::ScratchDir dir("pipeline_config_good");
  test_support::write_text(dir.file("p.yaml"), good);
  const auto c = read_pipeline_config(dir.file("p.yaml"));
  EXPECT_EQ(c.fe_studies.at(0).values.size(), 2u);
  EXPECT_EQ(c.mbd_runs.at(0).laws.at(0).value.value(), 0.004);
  EXPECT_TRUE(c.mbd_runs.at(1).laws.empty());
  EXPECT_EQ(c.presets.at("fast").at("fe:mesh.level"), 0);
}

TEST(PipelineConfig, BadFilesNameTheKeyAndTheValidRange)
{
  std::string m = error_for("fit: {weighting: absolute}", "fit: {weighting: absolute, wieghting: 1}");
  EXPECT_NE(m.find("fit.wieghting"), std::string::npos) << m;
  m = error_for("preset: fast", "preset: quick");
  EXPECT_NE(m.find("fast|standard|accurate"), std::string::npos) << m;
  m = error_for("study: thickness, value: 0.004", "study: thickness, value: 0.005");
  EXPECT_NE(m.find("0.002, 0.004"), std::string::npos) << m;
  m = error_for("study: thickness, value", "study: misalignment, value");
  EXPECT_NE(m.find("one of the fe_studies: thickness"), std::string::npos) << m;
  m = error_for("values: [0.002, 0.004]", "values: [0.004, 0.002]");
  EXPECT_NE(m.find("strictly increasing"), std::string::npos) << m;
  m = error_for("schema: clearjoint.pipeline/1", "schema: clearjoint.pipeline/0");
  EXPECT_NE(m.find("clearjoint.pipeline/1"), std::string::npos) << m;
}

TEST(PipelineConfig, SetKeyPath)
{
  nlohmann::json j = {{"a", {{"b", 1}}}, {"c", 2}};
  set_key_path(j, "a.b", 5, "x");
  set_key_path(j, "a.d.e", "f", "x");
  EXPECT_EQ(j["a"]["b"], 5);
  EXPECT_EQ(j["a"]["d"]["e"], "f");
  EXPECT_THROW(set_key_path(j, "c.d", 1, "x"), InputError);
  j["list"] = {{{"law", "a"}}, {{"law", "b"}}};
  set_key_path(j, "list.1.law", "c", "x");
  EXPECT_EQ(j["list"][1]["law"], "c");
  EXPECT_THROW(set_key_path(j, "list.2.law", "c", "x"), InputError);
  EXPECT_THROW(set_key_path(j, "list.first.law", "c", "x"), InputError);
}
