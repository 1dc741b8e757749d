// mbd_stage against hostile input and unattended runs (issue 16): impossible starting states
// are input errors before any integration (item 5), --check writes nothing (item 2), the
// step/wall-clock budget stops a run as a numerical failure with outputs marked (item 3), and
// SIGINT/SIGTERM at several moments leave nothing under the final name, no temporary folder
// and no plot.py behind (item 4).
#include "mbd_stage/scene.h"

#include "common/error.h"
#include "common/strict_reader.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  const std::string scenes = std::string(CLEARJOINT_SOURCE_DIR) + "/mbd_stage/scenes";

  nlohmann::json base()
  {
    nlohmann::json d = read_yaml_file(scenes + "/slider_crank_fe_law_damped.yaml");
    d["clearance_joints"][0]["normal"]["law_file"] = scenes + "/../../laws/paper_tB4.json";
    return d;
  }

  std::string error_of(const std::function<void(nlohmann::json &)> &mutate)
  {
    nlohmann::json d = base();
    mutate(d);
    return test_support::input_error_of([&] { mbd::scene_from_json(d, "s.yaml", scenes); });
  }

  bool has(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
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

  std::vector<std::string> entries_starting_with(const fs::path &dir, const std::string &prefix)
  {
    std::vector<std::string> out;
    for (const auto &e : fs::directory_iterator(dir))
      if (e.path().filename().string().rfind(prefix, 0) == 0)
        out.push_back(e.path().filename().string());
    return out;
  }
} // namespace

TEST(MbdHardening, ImpossibleStartingGeometryIsAnInputErrorNamingTheJournal)
{
  // The journal 2 mm off centre in a 0.5 mm clearance.
  const std::string off = error_of([](auto &d) {
    d["clearance_joints"][0]["journal"]["center"][2] = 0.002;
  });
  EXPECT_TRUE(has(off, "clearance_joints[0].journal")) << off;
  EXPECT_TRUE(has(off, "radial penetration")) << off;
  // Tilted 45°: its rims are far outside the bore.
  const std::string tilted = error_of([](auto &d) {
    d["clearance_joints"][0]["journal"]["axis"] = {1.0, 1.0, 0.0};
  });
  EXPECT_TRUE(has(tilted, "clearance_joints[0].journal")) << tilted;
  // Pushed 3 mm along the axis against a 1 mm axial clearance.
  const std::string axial = error_of([](auto &d) {
    d["clearance_joints"][0]["journal"]["center"][0] = 0.003;
  });
  EXPECT_TRUE(has(axial, "axial")) << axial;
  // Inside the clearance (0.4 mm off centre) is a legal start.
  EXPECT_EQ(error_of([](auto &d) { d["clearance_joints"][0]["journal"]["center"][2] = 0.0004; }),
            "(accepted)");
}

TEST(MbdHardening, AbsurdValuesAreInputErrorsNamingTheKey)
{
  EXPECT_TRUE(has(error_of([](auto &d) { d["gravity"] = {0.0, 0.0, -1e23}; }), "'gravity[2]'"));
  EXPECT_TRUE(has(error_of([](auto &d) {
                    d["clearance_joints"][0]["bearing"]["axis"] = {1e308, 1e308, 0.0};
                  }),
                  "clearance_joints[0].bearing.axis[0]"));
  EXPECT_TRUE(has(error_of([](auto &d) { d["bodies"][0]["position"][1] = 1e9; }),
                  "bodies[0].position[1]"));
  EXPECT_TRUE(has(error_of([](auto &d) { d["bodies"][1]["mass"] = 1e30; }), "bodies[1].mass"));
  EXPECT_TRUE(has(error_of([](auto &d) { d["clearance_joints"][0]["geometry"]["R_B"] = 1e300; }),
                  "geometry.R_B"));
  EXPECT_TRUE(has(error_of([](auto &d) { d["budget"] = {{"steps", 0}}; }), "budget.steps"));
  // A duration that would write more time-series rows than the output budget (1e7 by
  // default, ~5 GB): an input error before the run, not a full disk hours later.
  const std::string endless = error_of([](auto &d) { d["duration"] = 1e300; });
  EXPECT_TRUE(has(endless, "integrator.output_interval")) << endless;
  EXPECT_TRUE(has(endless, "budget.output_rows")) << endless;
  EXPECT_TRUE(has(error_of([](auto &d) { d["integrator"]["output_interval"] = 1e-12; }),
                  "integrator.output_interval"));
  EXPECT_TRUE(has(error_of([](auto &d) { d["budget"] = {{"output_rows", 1000}}; }),
                  "integrator.output_interval"));  // 0.1 s at 1e-5 s: 10001 rows
  EXPECT_EQ(error_of([](auto &d) { d["budget"] = {{"output_rows", 10001}}; }), "(accepted)");
  EXPECT_EQ(error_of([](auto &d) { d["duration"] = 10.0; }), "(accepted)");  // SPEC §6's 10 s
}

TEST(MbdHardening, CheckValidatesAndWritesNothing)
{
  test_support::ScratchDir dir("mbd_check");
  std::ofstream(dir.file("ok.json")) << base().dump();
  nlohmann::json bad = base();
  bad["clearance_joints"][0]["journal"]["center"][2] = 0.002;
  std::ofstream(dir.file("bad.json")) << bad.dump();
  const std::string exe = MBD_STAGE_EXECUTABLE;
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("ok.json") + " --check",
                                      dir.file("ok.log")),
            0)
    << test_support::read_text(dir.file("ok.log"));
  EXPECT_EQ(test_support::run_command(exe + " " + dir.file("bad.json") + " --check",
                                      dir.file("bad.log")),
            1);
  EXPECT_TRUE(has(test_support::read_text(dir.file("bad.log")), "clearance_joints[0].journal"));
  std::vector<std::string> names;
  for (const auto &e : fs::directory_iterator(dir.path()))
    names.push_back(e.path().filename().string());
  EXPECT_EQ(names.size(), 4u) << "only the two scenes and two logs";
}

TEST(MbdHardening, StepBudgetStopsTheRunWithExit2AndMarkedOutputs)
{
  test_support::ScratchDir dir("mbd_budget");
  nlohmann::json d = base();
  d["budget"] = {{"steps", 50}};  // the 0.1 s scene takes ~1000 steps (docs/benchmarks.md)
  std::ofstream(dir.file("s.json")) << d.dump();
  const int rc = test_support::run_command(std::string(MBD_STAGE_EXECUTABLE) + " " +
                                             dir.file("s.json") + " --output " +
                                             dir.file("out") + " --no-plots",
                                           dir.file("log"));
  EXPECT_EQ(rc, 2);
  EXPECT_TRUE(has(test_support::read_text(dir.file("log")), "step budget exceeded")) << test_support::read_text(dir.file("log"));
  EXPECT_EQ(read_json_file(dir.file("out/manifest.json"))["status"], "failed");
  EXPECT_TRUE(has(test_support::read_text(dir.file("out/timeseries.csv")),
                  "# status: incomplete: step budget exceeded"));
  EXPECT_EQ(read_json_file(dir.file("out/summary.json"))["status"], "failed");
}

TEST(MbdHardening, InterruptDuringIntegrationLeavesTheOldOutputsAndNoTemporaryFolder)
{
  test_support::ScratchDir dir("mbd_interrupt");
  // A first, complete run whose outputs must survive the interrupted reruns.
  nlohmann::json d = base();
  d["duration"] = 0.002;
  std::ofstream(dir.file("short.json")) << d.dump();
  ASSERT_EQ(test_support::run_command(std::string(MBD_STAGE_EXECUTABLE) + " " +
                                        dir.file("short.json") + " --output " + dir.file("out") +
                                        " --no-plots",
                                      dir.file("first.log")),
            0);
  const std::string old_manifest = test_support::read_text(dir.file("out/manifest.json"));
  d["duration"] = 100.0;  // s: runs far longer than the test waits
  d["integrator"]["output_interval"] = 1e-4;  // s: 1e6 rows, within budget.output_rows
  std::ofstream(dir.file("long.json")) << d.dump();
  // SIGINT early (setup or first steps) and later (well into the integration); SIGTERM.
  for (const auto &[sig, delay, code] :
       std::vector<std::tuple<int, double, int>>{{SIGINT, 0.05, 130}, {SIGINT, 1.0, 130},
                                                 {SIGTERM, 0.5, 143}})
  {
    const pid_t pid = test_support::start_process(
      MBD_STAGE_EXECUTABLE, {dir.file("long.json"), "--output", dir.file("out"), "--no-plots"},
      dir.file("run.log"));
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    kill(pid, sig);
    EXPECT_EQ(test_support::wait_exit_code(pid), code) << test_support::read_text(dir.file("run.log"));
    EXPECT_TRUE(has(test_support::read_text(dir.file("run.log")), "interrupted"))
      << test_support::read_text(dir.file("run.log"));
    EXPECT_EQ(test_support::read_text(dir.file("out/manifest.json")), old_manifest)
      << "the earlier output is untouched";
    EXPECT_TRUE(entries_starting_with(dir.path(), "out.tmp").empty()) << "no temporary folder";
  }
}

TEST(MbdHardening, InterruptWhilePlottingStopsPlotPyAndLeavesNoFinalFolder)
{
  test_support::ScratchDir dir("mbd_interrupt_plot");
  nlohmann::json d = base();
  d["duration"] = 0.002;
  std::ofstream(dir.file("s.json")) << d.dump();
  // A stand-in plot.py that records its pid and then takes long.
  test_support::write_text(dir.file("slow_plot.py"),
                           "import os, sys, time\n"
                           "open(os.environ['PLOT_PID_FILE'], 'w').write(str(os.getpid()))\n"
                           "time.sleep(60)\n");
  const std::string pid_file = dir.file("plot.pid");
  const pid_t pid = test_support::start_process(
    MBD_STAGE_EXECUTABLE, {dir.file("s.json"), "--output", dir.file("out")}, dir.file("run.log"),
    {"CLEARJOINT_PLOT_SCRIPT=" + dir.file("slow_plot.py"), "PLOT_PID_FILE=" + pid_file});
  ASSERT_TRUE(wait_for([&] { return !test_support::read_text(pid_file).empty(); }, 60.0))
    << test_support::read_text(dir.file("run.log"));
  const pid_t plot_pid = std::stoi(test_support::read_text(pid_file));
  kill(pid, SIGINT);
  EXPECT_EQ(test_support::wait_exit_code(pid), 130) << test_support::read_text(dir.file("run.log"));
  EXPECT_FALSE(fs::exists(dir.file("out"))) << "nothing under the final name";
  EXPECT_TRUE(entries_starting_with(dir.path(), "out.tmp").empty());
  // plot.py was stopped (and reaped by the stage): no such process any more.
  EXPECT_TRUE(wait_for([&] { return kill(plot_pid, 0) != 0; }, 5.0)) << "plot.py still running";
}

TEST(MbdHardening, ARerunReplacesTheOldOutputsAsAWhole)
{
  test_support::ScratchDir dir("mbd_rerun");
  nlohmann::json d = base();
  d["duration"] = 0.002;
  std::ofstream(dir.file("s.json")) << d.dump();
  const std::string cmd = std::string(MBD_STAGE_EXECUTABLE) + " " + dir.file("s.json") +
                          " --output " + dir.file("out") + " --no-plots";
  ASSERT_EQ(test_support::run_command(cmd, dir.file("1.log")), 0);
  test_support::write_text(dir.file("out/stale_extra_file.vtu"), "old");
  ASSERT_EQ(test_support::run_command(cmd, dir.file("2.log")), 0);
  EXPECT_FALSE(fs::exists(dir.file("out/stale_extra_file.vtu")));
  EXPECT_TRUE(fs::exists(dir.file("out/manifest.json")));
}

TEST(MbdHardening, PathsThatAreNotUtf8AreWrittenNotFatal)
{
  // A scene in a folder named with the byte 0xFF: its path goes into summary.json and the
  // manifest (as U+FFFD); the run used to end in "unexpected failure" (exit 2) on that write.
  test_support::ScratchDir dir("mbd_not_utf8_path");
  const std::string folder = dir.file("d\xff");
  fs::create_directories(folder);
  nlohmann::json d = base();
  d["duration"] = 0.002;
  std::ofstream(folder + "/s.json") << d.dump();
  ASSERT_EQ(test_support::run_command(std::string(MBD_STAGE_EXECUTABLE) + " '" + folder +
                                        "/s.json' --no-plots --output '" + folder + "/out'",
                                      dir.file("run.log")),
            0)
    << test_support::read_text(dir.file("run.log"));
  EXPECT_EQ(read_json_file(folder + "/out/manifest.json")["status"], "complete");
  EXPECT_TRUE(fs::is_regular_file(folder + "/out/summary.json"));
}
