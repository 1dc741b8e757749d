// run_pipeline with stand-in FE and MBD stages (tests/data/fake_stages) and the real fit_stage:
// a build directory of them, a small pipeline file, and running it. Shared by the pipeline's
// end-to-end tests (pipeline_runner_test.cc, tasks at once, the Slurm executor).
#pragma once

#include "common/document_reader.h"
#include "common/sha256.h"
#include "common/strict_reader.h"
#include "test_support.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace fake_pipeline
{
  using namespace clearjoint;
  namespace fs = std::filesystem;

  /// A build directory whose fe_stage and mbd_stage are the stand-ins.
  struct FakeBuild
  {
    /// real_mbd: the real mbd_stage instead of the stand-in (it needs no FE either).
    explicit FakeBuild(const test_support::ScratchDir &dir, const bool real_mbd = false)
      : root(dir.file("build"))
    {
      const fs::path fakes = fs::path(CLEARJOINT_TEST_DATA_DIR) / "fake_stages";
      const std::vector<std::pair<fs::path, fs::path>> links = {
        {"fe_stage/fe_stage", fakes / "fake_fe_stage.py"},
        {"mbd_stage/mbd_stage", real_mbd ? fs::path(MBD_STAGE_EXE) : fakes / "fake_mbd_stage.py"},
        {"fit_stage/fit_stage", FIT_STAGE_EXE},
        {"geometry/msh_check", MSH_CHECK_EXE}};
      for (const auto &[link, target] : links)
      {
        fs::create_directories((fs::path(root) / link).parent_path());
        fs::create_symlink(target, fs::path(root) / link);
      }
    }
    std::string root;
  };

  inline std::string pipeline_yaml(const std::string &dir, const std::string &values,
                            const std::string &extra_fe = "")
  {
    test_support::write_text(dir + "/fe.yaml",
                             "{\"geometry\": {\"t_B\": 0.004}" + extra_fe + "}\n");
    test_support::write_text(dir + "/mbd.yaml",
                             "{\"joint\": {\"law_file\": \"none\"}, \"extra_file\": \"law.json\"}\n");
    test_support::write_text(dir + "/law.json", test_support::read_text(
                                                  std::string(CLEARJOINT_SOURCE_DIR) +
                                                  "/laws/paper_tB4.json"));
    return "schema: clearjoint.pipeline/1\nrun: r\noutput_root: " + dir + "/out\npreset: fast\n" +
           "presets: {fast: {fe: null, mbd: null}, standard: {fe: null, mbd: null}, "
           "accurate: {fe: null, mbd: null}}\n"
           "fe_sweeps:\n  - name: thickness\n    scene: " + dir + "/fe.yaml\n"
           "    parameter: {name: t_B, unit: m, key: geometry.t_B}\n    values: " + values + "\n"
           "fit: {weighting: absolute}\n"
           "mbd_runs:\n"
           "  - {name: fitted, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, sweep: thickness, value: 0.002}], band: true}\n"
           "  - {name: family, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, sweep: thickness}]}\n"
           "  - {name: paper, scene: " + dir + "/mbd.yaml, laws: [{key: joint.law_file, file: " + dir + "/law.json}]}\n"
           "report: false\n";
  }

  struct Outcome
  {
    int exit_code;
    std::string log;
    std::map<std::string, std::string> tasks;  // name → ran | reused
  };

  inline Outcome run(const test_support::ScratchDir &dir, const FakeBuild &build,
              const std::string &extra_args = "", const std::string &env = "")
  {
    const int rc = test_support::run_command(env + " " + RUN_PIPELINE_EXE + " " +
                                               dir.file("p.yaml") + " --no-plots --build-dir " +
                                               build.root + " " + extra_args,
                                             dir.file("log.txt"));
    Outcome o{rc, test_support::read_text(dir.file("log.txt")), {}};
    const std::string summary = dir.file("out/r/pipeline_summary.json");
    const nlohmann::json j = rc == 0 && fs::exists(summary) ? read_json_file(summary) : nlohmann::json();
    if (j.is_object())
      for (const auto &t : j["tasks"])
        o.tasks[t["name"].get<std::string>()] = t["outcome"].get<std::string>();
    return o;
  }

  inline std::set<std::string> with(const Outcome &o, const std::string &what)
  {
    std::set<std::string> s;
    for (const auto &[name, outcome] : o.tasks)
      if (outcome == what)
        s.insert(name);
    return s;
  }

  /// Every result file of a run (relative path → sha256 of its text with the run's own root
  /// replaced by ROOT), without what records times, machines or commands: manifests, logs,
  /// command lines, stamps and the summary.
  inline std::map<std::string, std::string> result_hashes(const std::string &root)
  {
    std::map<std::string, std::string> h;
    for (const auto &e : fs::recursive_directory_iterator(root))
    {
      const std::string name = e.path().filename().string();
      if (!e.is_regular_file() || name == "manifest.json" || name == "stage.log" ||
          name == "command.txt" || name == ".task.json" || name == "pipeline_summary.json" ||
          name.find(".manifest.json") != std::string::npos)
        continue;
      std::string text = test_support::read_text(e.path().string());
      for (std::size_t p; (p = text.find(root)) != std::string::npos;)
        text.replace(p, root.size(), "ROOT");
      h[fs::relative(e.path(), root).string()] = sha256_hex(text);
    }
    return h;
  }
} // namespace fake_pipeline
