#include "common/error.h"
#include "common/strict_reader.h"

#include "test_support.h"

#include <gtest/gtest.h>


using namespace clearjoint;

namespace
{
  using test_support::input_error_of;

  const char *scene = R"(
schema: clearjoint.test/1
geometry:
  t_B: 0.004
  name: "007"
  flag: true
list: [1, 2.5, 3]
)";
} // namespace

TEST(StrictReader, ReadsTypedValuesFromYaml)
{
  const auto j = parse_yaml_string(scene, "scene.yaml");
  StrictObject top(j, "scene.yaml");
  top.expect_schema("clearjoint.test/1");
  auto g = top.object("geometry");
  EXPECT_DOUBLE_EQ(g.number("t_B", Range::positive("m")), 0.004);
  EXPECT_EQ(g.string("name"), "007") << "quoted scalars stay strings";
  EXPECT_TRUE(g.boolean("flag"));
  EXPECT_DOUBLE_EQ(g.number_or("c_r", 5e-4, Range::positive("m")), 5e-4);
  g.finish();
  EXPECT_EQ(top.number_array("list", Range::any()).size(), 3u);
  top.finish();
}

TEST(StrictReader, UnknownKeyIsNamedWithItsPath)
{
  const auto j = parse_yaml_string("geometry:\n  t_B: 1\n  tB: 2\n", "s.yaml");
  StrictObject top(j, "s.yaml");
  auto g = top.object("geometry");
  g.number("t_B", Range::positive("m"));
  const std::string m = input_error_of([&] { g.finish(); });
  EXPECT_NE(m.find("s.yaml"), std::string::npos) << m;
  EXPECT_NE(m.find("geometry.tB"), std::string::npos) << m;
  EXPECT_NE(m.find("t_B"), std::string::npos) << "lists the valid keys: " << m;
}

TEST(StrictReader, MissingKeyAndOutOfRangeValue)
{
  const auto j = parse_yaml_string("t_B: -1\n", "s.yaml");
  StrictObject top(j, "s.yaml");
  std::string m = input_error_of([&] { top.number("c_r", Range::positive("m")); });
  EXPECT_NE(m.find("'c_r'"), std::string::npos) << m;
  EXPECT_NE(m.find("missing"), std::string::npos) << m;
  m = input_error_of([&] { top.number("t_B", Range::positive("m")); });
  EXPECT_NE(m.find("'-1'"), std::string::npos) << m;
  EXPECT_NE(m.find("(0, inf) m"), std::string::npos) << m;
}

TEST(StrictReader, WrongSchemaVersionAndWrongType)
{
  const auto j = nlohmann::json::parse(R"({"schema": "clearjoint.law/2", "K": "big"})");
  StrictObject top(j, "law.json");
  std::string m = input_error_of([&] { top.expect_schema("clearjoint.law/1"); });
  EXPECT_NE(m.find("clearjoint.law/2"), std::string::npos) << m;
  EXPECT_NE(m.find("clearjoint.law/1"), std::string::npos) << m;
  m = input_error_of([&] { top.number("K", Range::positive()); });
  EXPECT_NE(m.find("a number"), std::string::npos) << m;
}

TEST(StrictReader, MalformedYamlAndDuplicateKeys)
{
  EXPECT_THROW(parse_yaml_string("a: [1, 2\n", "bad.yaml"), InputError);
  const std::string m = input_error_of([] { parse_yaml_string("a: 1\na: 2\n", "dup.yaml"); });
  EXPECT_NE(m.find("key 'a'"), std::string::npos) << m;
  EXPECT_NE(m.find("duplicate key"), std::string::npos) << m;
}

TEST(StrictReader, StringChoices)
{
  const auto j = parse_yaml_string("loading: sideways\n", "s.yaml");
  StrictObject top(j, "s.yaml");
  const std::string m =
    input_error_of([&] { top.string("loading", {"axis_line", "end_faces", "rigid"}); });
  EXPECT_NE(m.find("one of axis_line|end_faces|rigid"), std::string::npos) << m;
}
