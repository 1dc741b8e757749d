#include "common/manifest.h"
#include "common/sha256.h"
#include "common/strict_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace clearjoint;

TEST(Manifest, RecordsInputsOutputsVersionsAndWallTime)
{
  test_support::ScratchDir dir("manifest_ok");
  test_support::write_text(dir.file("in.txt"), "abc");
  test_support::write_text(dir.file("out.txt"), "xyz");
  const char *argv[] = {"stage", "in.txt"};
  Manifest m("test_stage", dir.file("manifest.json"), 2, argv);
  m.add_input(dir.file("in.txt"));
  m.add_output(dir.file("out.txt"));
  m.set_library_version("thing", "1.2.3");
  m.extra()["answer"] = 42;
  m.write("complete");
  const auto j = read_json_file(dir.file("manifest.json"));
  EXPECT_EQ(j["schema"], "clearjoint.manifest/1");
  EXPECT_EQ(j["status"], "complete");
  EXPECT_EQ(j["inputs"][0]["sha256"], sha256_hex("abc"));
  EXPECT_EQ(j["outputs"][0]["sha256"], sha256_hex("xyz"));
  EXPECT_EQ(j["libraries"]["thing"], "1.2.3");
  EXPECT_EQ(j["wall_time"]["unit"], "s");
  EXPECT_GE(j["wall_time"]["value"].get<double>(), 0.0);
  EXPECT_EQ(j["command_line"][1], "in.txt");
  EXPECT_EQ(j["extra"]["answer"], 42);
}

TEST(Manifest, WrittenAsFailedWhenTheStageDiesFirst)
{
  test_support::ScratchDir dir("manifest_fail");
  try
  {
    Manifest m("test_stage", dir.file("manifest.json"));
    throw std::runtime_error("boom");
  }
  catch (const std::runtime_error &)
  {
  }
  const auto j = read_json_file(dir.file("manifest.json"));
  EXPECT_EQ(j["status"], "failed");
}
