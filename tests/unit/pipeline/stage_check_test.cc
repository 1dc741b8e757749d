// StageChecks (pipeline/stage_check.h): the stages' --check runs of a pipeline's generated
// inputs run a few at once; every one runs, and the first failure in the order they were added
// is reported, traced back to the pipeline key that made the failing value. Stand-in stages
// are shell scripts.
#include "common/error.h"
#include "pipeline/stage_check.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>

using namespace clearjoint;
using namespace clearjoint::pipeline;
namespace fs = std::filesystem;

namespace
{
  /// An executable shell script `name` in `dir` with `body`; returns its path.
  std::string script(const test_support::ScratchDir &dir, const std::string &name,
                     const std::string &body)
  {
    const std::string path = dir.file(name);
    test_support::write_text(path, "#!/bin/sh\n" + body + "\n");
    fs::permissions(path, fs::perms::owner_all);
    return path;
  }

  /// A stage that rejects `key` as fe_stage does (an input error naming the key).
  std::string rejecting(const test_support::ScratchDir &dir, const std::string &key)
  {
    return script(dir, "reject.sh",
                  "echo \"error: input error in s.yaml: key '" + key +
                    "' has value '0'; allowed: 1 to 10\"\nexit 1");
  }
}  // namespace

TEST(StageChecks, EveryCheckRunsAndTheFirstFailureInOrderIsReported)
{
  test_support::ScratchDir dir("stage_checks_order");
  const std::string ok = script(dir, "ok.sh", "sleep 0.2\nexit 0");
  const std::string crash = script(dir, "crash.sh", "echo 'out of memory'\nexit 2");
  const std::string reject = rejecting(dir, "mesh.n_radial");
  StageChecks checks(2);
  checks.add({"fe_stage", ok, "p.yaml"}, {"a.yaml"}, dir.file("a.log"), {}, "k.a", "case A");
  checks.add({"fe_stage", crash, "p.yaml"}, {"b.yaml"}, dir.file("b.log"), {}, "k.b", "case B");
  checks.add({"fe_stage", reject, "p.yaml"}, {"c.yaml"}, dir.file("c.log"), {}, "k.c", "case C");
  checks.add({"fe_stage", ok, "p.yaml"}, {"d.yaml"}, dir.file("d.log"), {}, "k.d", "case D");
  try
    {
      checks.finish();
      FAIL() << "two checks failed";
    }
  catch (const NumericalError &e)
    {
      // B's failure, added before C's: not an input error, so the stage's exit status is named.
      const std::string m = e.what();
      EXPECT_NE(m.find("case B"), std::string::npos) << m;
      EXPECT_NE(m.find("exit status 2"), std::string::npos) << m;
      EXPECT_NE(m.find("out of memory"), std::string::npos) << m;
    }
  for (const char *log : {"a.log", "b.log", "c.log", "d.log"})
    EXPECT_TRUE(fs::exists(dir.file(log))) << log << ": every check ran";
}

TEST(StageChecks, AnInputErrorNamesThePipelineKeyThatSetTheValue)
{
  test_support::ScratchDir dir("stage_checks_key");
  const std::string ok = script(dir, "ok.sh", "exit 0");
  const std::string reject = rejecting(dir, "mesh.n_radial");
  StageChecks checks(3);
  checks.add({"fe_stage", ok, "p.yaml"}, {"a.yaml"}, dir.file("a.log"), {}, "k.a", "case A");
  const std::vector<Origin> origins = {
    {"mesh", "presets.fast.fe.mesh", 1},  // an earlier setting of a key above it
    {"mesh.n_radial", "fe_sweeps[0].presets.fast.mesh.n_radial", 0},
    {"loading.journal", "fe_sweeps[0].overrides.loading.journal", "core"}};
  checks.add({"fe_stage", reject, "p.yaml"}, {"b.yaml"}, dir.file("b.log"), origins,
             "fe_sweeps[0].scene", "case B");
  try
    {
      checks.finish();
      FAIL() << "B was rejected";
    }
  catch (const InputError &e)
    {
      const std::string m = e.what();
      EXPECT_NE(m.find("fe_sweeps[0].presets.fast.mesh.n_radial"), std::string::npos) << m;
      EXPECT_NE(m.find("case B"), std::string::npos) << m;
      EXPECT_NE(m.find("key 'mesh.n_radial'"), std::string::npos) << m;
    }
}

TEST(StageChecks, AllAcceptedFinishesQuietly)
{
  test_support::ScratchDir dir("stage_checks_ok");
  const std::string ok = script(dir, "ok.sh", "exit 0");
  StageChecks checks(2);
  for (int i = 0; i < 5; ++i)
    checks.add({"mbd_stage", ok, "p.yaml"}, {"s.yaml"}, dir.file(std::to_string(i) + ".log"), {},
               "k", "run " + std::to_string(i));
  EXPECT_NO_THROW(checks.finish());
}

// An error of the pipeline file's own keys ends the check before finish(): the checks still
// running are ended and reaped, not left behind.
TEST(StageChecks, ChecksStillRunningAreEndedWhenTheCheckStopsEarly)
{
  test_support::ScratchDir dir("stage_checks_early");
  const std::string slow = script(dir, "slow.sh", "echo $$ > \"$0.pid\"\nexec sleep 60");
  {
    StageChecks checks(2);
    checks.add({"fe_stage", slow, "p.yaml"}, {"a.yaml"}, dir.file("a.log"), {}, "k", "case A");
    for (int i = 0; i < 100 && !fs::exists(slow + ".pid"); ++i)
      ::usleep(50000);
  }
  ASSERT_TRUE(fs::exists(slow + ".pid"));
  const pid_t pid = std::stoi(test_support::read_text(slow + ".pid"));
  EXPECT_EQ(::kill(pid, 0), -1) << "the check's process " << pid << " is still there";
  EXPECT_EQ(errno, ESRCH);
}
