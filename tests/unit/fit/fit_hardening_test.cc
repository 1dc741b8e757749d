// fit_stage against hostile input and interrupts (issue 16 items 1, 4): an input error leaves
// nothing behind (no law, no manifest, no folder it created); SIGINT/SIGTERM while plotting
// stop plot.py and leave the earlier run's outputs as they were, with no temporary file; a
// rerun replaces the outputs as a whole; paths that are not UTF-8 do not stop the run.
#include "common/document_reader.h"
#include "laws/law_file.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <thread>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  std::string csv(const double K)
  {
    std::string s = "# units: m,N\ndelta,force\n0,0\n";
    for (int i = 1; i <= 10; ++i)
      s += std::to_string(5e-6 * i) + "," + std::to_string(K * std::pow(5e-6 * i, 1.0114)) + "\n";
    return s;
  }

  bool wait_for(const std::function<bool()> &condition, const double seconds)
  {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until)
    {
      if (condition())
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return condition();
  }

  /// Names in `dir` that contain ".tmp.": temporaries left behind.
  std::vector<std::string> temporaries(const fs::path &dir)
  {
    std::vector<std::string> out;
    for (const auto &e : fs::recursive_directory_iterator(dir))
      if (e.path().filename().string().find(".tmp.") != std::string::npos)
        out.push_back(e.path().string());
    return out;
  }
} // namespace

TEST(FitHardening, InputErrorsLeaveNothingBehind)
{
  test_support::ScratchDir dir("fit_input_errors");
  std::string overflow = csv(3.6e8);
  overflow.replace(overflow.rfind("\n", overflow.size() - 2) + 1, std::string::npos,
                   "5e-05,1e400\n");
  test_support::write_text(dir.file("overflow.csv"), overflow);
  test_support::write_text(dir.file("not_utf8.csv"), "# units: m,N\ndelta,force\xff\n0,0\n");
  test_support::write_text(dir.file("twice.csv"), "delta,force,force\n0,0,0\n1e-5,3,3\n");
  for (const std::string name : {"overflow", "not_utf8", "twice"})
  {
    const std::string out = dir.file("out_" + name);
    const int rc = test_support::run_command(std::string(FIT_STAGE_EXE) + " " +
                                               dir.file(name + ".csv") + " --output " + out +
                                               "/a/law.json",
                                             dir.file("log.txt"));
    const std::string log = test_support::read_text(dir.file("log.txt"));
    EXPECT_EQ(rc, 1) << name << ": " << log;
    EXPECT_NE(log.find(name + ".csv"), std::string::npos) << "names the file: " << log;
    EXPECT_FALSE(fs::exists(out)) << name << ": no folder, no manifest: " << log;
  }
  // An output folder that cannot be made (a file is in the way): input error naming --output.
  test_support::write_text(dir.file("a_file"), "x");
  test_support::write_text(dir.file("good.csv"), csv(3.6e8));
  EXPECT_EQ(test_support::run_command(std::string(FIT_STAGE_EXE) + " " + dir.file("good.csv") +
                                        " --no-plots --output " + dir.file("a_file/law.json"),
                                      dir.file("log.txt")),
            1)
    << test_support::read_text(dir.file("log.txt"));
  EXPECT_NE(test_support::read_text(dir.file("log.txt")).find("--output"), std::string::npos);
  EXPECT_EQ(test_support::read_text(dir.file("a_file")), "x");
}

TEST(FitHardening, InterruptWhilePlottingLeavesTheEarlierOutputs)
{
  test_support::ScratchDir dir("fit_interrupt");
  test_support::write_text(dir.file("old.csv"), csv(3.6e8));
  test_support::write_text(dir.file("new.csv"), csv(7.2e8));
  ASSERT_EQ(test_support::run_command(std::string(FIT_STAGE_EXE) + " " + dir.file("old.csv") +
                                        " --no-plots --output " + dir.file("out/law.json"),
                                      dir.file("first.log")),
            0);
  test_support::write_text(dir.file("out/law.png"), "the earlier run's plot");
  const std::string old_law = test_support::read_text(dir.file("out/law.json"));
  const std::string old_manifest = test_support::read_text(dir.file("out/law.manifest.json"));
  // A stand-in plot.py that records its pid and then takes long.
  test_support::write_text(dir.file("slow_plot.py"),
                           "import os, sys, time\n"
                           "open(os.environ['PLOT_PID_FILE'], 'w').write(str(os.getpid()))\n"
                           "time.sleep(60)\n");
  for (const auto &[sig, code] : std::vector<std::pair<int, int>>{{SIGINT, 130}, {SIGTERM, 143}})
  {
    const std::string pid_file = dir.file("plot.pid");
    fs::remove(pid_file);
    const pid_t pid = test_support::start_process(
      FIT_STAGE_EXE, {dir.file("new.csv"), "--output", dir.file("out/law.json")},
      dir.file("run.log"),
      {"CLEARJOINT_PLOT_SCRIPT=" + dir.file("slow_plot.py"), "PLOT_PID_FILE=" + pid_file});
    ASSERT_TRUE(wait_for([&] { return !test_support::read_text(pid_file).empty(); }, 60.0))
      << test_support::read_text(dir.file("run.log"));
    const pid_t plot_pid = std::stoi(test_support::read_text(pid_file));
    kill(pid, sig);
    EXPECT_EQ(test_support::wait_exit_code(pid), code)
      << test_support::read_text(dir.file("run.log"));
    EXPECT_EQ(test_support::read_text(dir.file("out/law.json")), old_law) << "law untouched";
    EXPECT_EQ(test_support::read_text(dir.file("out/law.manifest.json")), old_manifest);
    EXPECT_EQ(test_support::read_text(dir.file("out/law.png")), "the earlier run's plot");
    EXPECT_TRUE(temporaries(dir.file("out")).empty()) << temporaries(dir.file("out")).front();
    EXPECT_TRUE(wait_for([&] { return kill(plot_pid, 0) != 0; }, 5.0)) << "plot.py still running";
  }
  // A rerun without a plot replaces the outputs as a whole: the earlier plot goes with them.
  ASSERT_EQ(test_support::run_command(std::string(FIT_STAGE_EXE) + " " + dir.file("new.csv") +
                                        " --no-plots --output " + dir.file("out/law.json"),
                                      dir.file("third.log")),
            0);
  EXPECT_FALSE(fs::exists(dir.file("out/law.png"))) << "a plot of the earlier law";
  EXPECT_NEAR(laws::read_law_file(dir.file("out/law.json")).law.K / 7.2e8, 1.0, 1e-3);
  EXPECT_EQ(read_json_file(dir.file("out/law.manifest.json"))["status"], "complete");
}

TEST(FitHardening, PathsThatAreNotUtf8AreWrittenNotFatal)
{
  test_support::ScratchDir dir("fit_not_utf8_path");
  const std::string folder = dir.file("d\xff");
  fs::create_directories(folder);
  test_support::write_text(folder + "/data.csv", csv(3.6e8));
  ASSERT_EQ(test_support::run_command(std::string(FIT_STAGE_EXE) + " '" + folder +
                                        "/data.csv' --no-plots --output '" + folder + "/law.json'",
                                      dir.file("log.txt")),
            0)
    << test_support::read_text(dir.file("log.txt"));
  EXPECT_NEAR(laws::read_law_file(folder + "/law.json").law.n, 1.0114, 1e-4);
  EXPECT_EQ(read_json_file(folder + "/law.manifest.json")["status"], "complete");
}
