// fe_stage against hostile input and interrupts (issue 16 items 1, 2, 4), through the
// executable: --check writes nothing; SIGINT/SIGTERM at several moments leave no VTU/PVD/CSV
// under the final name and no temporary folder, and an earlier complete output untouched; a
// rerun replaces the old outputs as a whole; a folder fe_stage did not write is refused.
#include "common/strict_reader.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  /// The coarsest mesh (preset fast) with many small increments: a few seconds in all, long
  /// enough to be interrupted part-way.
  std::string scene(const int n_increments)
  {
    return "schema: clearjoint.fe/1\nstudy: radial\ngeometry: {t_B: 0.004}\ncontact: {mu: 0}\n"
           "loading: {delta_max: 5.0e-5, n_increments: " +
           std::to_string(n_increments) +
           "}\nmesh: {n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1, "
           "global_refinements: 0}\n";
  }

  std::vector<std::string> temporaries(const fs::path &dir)
  {
    std::vector<std::string> out;
    for (const auto &e : fs::directory_iterator(dir))
      if (e.path().filename().string().find(".tmp.") != std::string::npos)
        out.push_back(e.path().filename().string());
    return out;
  }
} // namespace

TEST(FeHardening, CheckValidatesAndWritesNothing)
{
  test_support::ScratchDir dir("fe_check");
  test_support::write_text(dir.file("ok.yaml"), scene(3));
  test_support::write_text(dir.file("bad.yaml"),
                           "schema: clearjoint.fe/1\ngeometry: {t_B: 1e400}\n");
  const std::string exe = FE_STAGE_EXE;
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("ok.yaml") + " --check",
                                      dir.file("ok.log")),
            0)
    << test_support::read_text(dir.file("ok.log"));
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("bad.yaml") + " --check",
                                      dir.file("bad.log")),
            1);
  const std::string m = test_support::read_text(dir.file("bad.log"));
  EXPECT_NE(m.find("key 'geometry.t_B'"), std::string::npos) << m;
  EXPECT_NE(m.find("finite"), std::string::npos) << m;
  std::size_t n = 0;
  for ([[maybe_unused]] const auto &e : fs::directory_iterator(dir.path()))
    ++n;
  EXPECT_EQ(n, 4u) << "only the two scenes and two logs";
}

// --check and --print-defaults do not start MPI (its start is most of a check's time, and
// run_pipeline checks every scene before its first task): with an MPI that cannot start (a
// component that does not exist), they still work, while a run fails.
TEST(FeHardening, CheckAndPrintDefaultsDoNotStartMpi)
{
  test_support::ScratchDir dir("fe_check_no_mpi");
  test_support::write_text(dir.file("ok.yaml"), scene(3));
  const std::string exe = "env OMPI_MCA_pml=no_such_component " + std::string(FE_STAGE_EXE);
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("ok.yaml") + " --check",
                                      dir.file("check.log")),
            0)
    << test_support::read_text(dir.file("check.log"));
  EXPECT_NE(test_support::read_text(dir.file("check.log")).find("is a valid scene"),
            std::string::npos);
  EXPECT_EQ(test_support::run_command(exe + " --print-defaults", dir.file("defaults.log")), 0);
  EXPECT_NE(test_support::read_text(dir.file("defaults.log")).find("schema: clearjoint.fe/1"),
            std::string::npos);
  // The same environment does stop a run: the check above did not pass by accident.
  EXPECT_NE(test_support::run_command(exe + " " + dir.file("ok.yaml") + " -o " + dir.file("out") +
                                        " --no-plots --no-fields",
                                      dir.file("run.log")),
            0);
}

TEST(FeHardening, InterruptsLeaveNothingUnderTheFinalNameAndTheOldOutputIntact)
{
  test_support::ScratchDir dir("fe_interrupt");
  test_support::write_text(dir.file("short.yaml"), scene(2));
  test_support::write_text(dir.file("long.yaml"), scene(400));
  const std::string out = dir.file("out");
  ASSERT_EQ(test_support::run_command(std::string(FE_STAGE_EXE) + " " + dir.file("short.yaml") +
                                        " --output " + out + " --no-plots",
                                      dir.file("first.log")),
            0)
    << test_support::read_text(dir.file("first.log"));
  const std::string manifest = test_support::read_text(out + "/manifest.json");
  // Moments: as soon as the work folder exists (setup, before the first increment ends), and
  // two seconds later (increments under way); SIGTERM as a batch system sends it.
  for (const auto &[sig, delay, code] : std::vector<std::tuple<int, double, int>>{
         {SIGINT, 0.0, 130}, {SIGINT, 2.0, 130}, {SIGTERM, 1.0, 143}})
  {
    const pid_t pid = test_support::start_process(
      FE_STAGE_EXE, {dir.file("long.yaml"), "--output", out, "--no-plots"}, dir.file("run.log"));
    for (int i = 0; i < 3000 && temporaries(dir.path()).empty(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_FALSE(temporaries(dir.path()).empty()) << test_support::read_text(dir.file("run.log"));
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    kill(pid, sig);
    EXPECT_EQ(test_support::wait_exit_code(pid), code) << test_support::read_text(dir.file("run.log"));
    EXPECT_TRUE(temporaries(dir.path()).empty()) << "the work folder is removed";
    EXPECT_EQ(test_support::read_text(out + "/manifest.json"), manifest)
      << "the earlier output is untouched";
    EXPECT_TRUE(fs::exists(out + "/fields/solution.pvd"));
  }
}

TEST(FeHardening, ARerunReplacesTheOutputsAsAWholeAndForeignFoldersAreRefused)
{
  test_support::ScratchDir dir("fe_rerun");
  test_support::write_text(dir.file("s.yaml"), scene(2));
  const std::string cmd = std::string(FE_STAGE_EXE) + " " + dir.file("s.yaml") + " --no-plots --output ";
  ASSERT_EQ(test_support::run_command(cmd + dir.file("out"), dir.file("1.log")), 0);
  test_support::write_text(dir.file("out/fields/solution_0099.pvtu"), "an older run's field");
  ASSERT_EQ(test_support::run_command(cmd + dir.file("out"), dir.file("2.log")), 0);
  EXPECT_FALSE(fs::exists(dir.file("out/fields/solution_0099.pvtu"))) << "no stale VTU";
  const auto m = read_json_file(dir.file("out/manifest.json"));
  EXPECT_EQ(m["status"], "complete");
  EXPECT_EQ(m.dump().find(".tmp."), std::string::npos) << "paths point at the final folder";

  fs::create_directories(dir.file("foreign"));
  test_support::write_text(dir.file("foreign/notes.txt"), "mine");
  EXPECT_EQ(test_support::run_command(cmd + dir.file("foreign"), dir.file("3.log")), 1);
  EXPECT_EQ(test_support::read_text(dir.file("foreign/notes.txt")), "mine");
}

// An --output that cannot be made (a regular file where a folder must go) is an input error
// naming --output, exit 1 (was exit 2, "unexpected failure: filesystem error"), and nothing is
// created beside the file.
TEST(FeHardening, AnOutputFolderThatCannotBeMadeIsAnInputError)
{
  test_support::ScratchDir dir("fe_output_under_file");
  test_support::write_text(dir.file("ok.yaml"), scene(3));
  test_support::write_text(dir.file("blocker"), "a file, not a folder\n");
  const std::string exe = FE_STAGE_EXE;
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("ok.yaml") + " -o " +
                                        dir.file("blocker") + "/run --no-plots",
                                      dir.file("run.log")),
            1);
  const std::string m = test_support::read_text(dir.file("run.log"));
  EXPECT_NE(m.find("--output"), std::string::npos) << m;
  EXPECT_EQ(m.find("unexpected"), std::string::npos) << m;
  std::size_t n = 0;
  for ([[maybe_unused]] const auto &e : fs::directory_iterator(dir.path()))
    ++n;
  EXPECT_EQ(n, 3u) << "only the scene, the blocking file and the log";
}
