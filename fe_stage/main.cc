// fe_stage: the FE contact model of a revolute joint with clearance (SPEC §2).
//
//   fe_stage SCENE.yaml --output DIR [--preset fast|standard|accurate] [--full-model]
//            [--no-fields] [--no-plots]
//   fe_stage --print-defaults
//   fe_stage SCENE.yaml --check      (read and validate the scene and its mesh only)
//   fe_stage ROLLING.yaml --output DIR --write-restart RDIR [--restart-every N]
//   fe_stage ROLLING.yaml --output DIR --resume RDIR   (continue a run cut short)
//
// Writes DIR/force_penetration.csv (delta, force, solver statistics per increment),
// DIR/fields/ (VTU/PVTU + PVD), DIR/force_penetration.png and DIR/manifest.json; with a `sweep`
// block, one such folder per swept value under DIR plus DIR/manifest.json, DIR/sweep.csv and
// DIR/sweep.png (every case's curve). Study impact: force_penetration.csv is the quasi-static
// reference curve, and DIR/impact_history.csv (one row per time step) and DIR/impact.png are
// added; a sweep over impact.velocity and/or impact.journal_mass (every pair; folders
// m_<m>kg_v_<v>mps) writes DIR/impact_sweep.csv, DIR/impact_sweep.png and the paper's Fig. 5a
// and 5b (DIR/fig5a.png, DIR/fig5b.png).
// Everything is written into DIR.tmp.<pid> and renamed to DIR at the end (an earlier DIR is
// replaced as a whole).
// Exit codes: 0 success, 1 input error, 2 numerical failure (CSV and manifest marked incomplete),
// 3 an output could not be written (a full disk: one line naming the file and the OS reason,
// DIR.tmp.<pid> removed), 130/143 interrupted by SIGINT/SIGTERM (after the current increment,
// or within 0.7 s inside a long setup or solve: common/interrupt.h; DIR.tmp.<pid> removed).
//
// The steps: add_options (the command line) → read_scene (apply_preset, validate) →
// make_work_folder → run_case, or run_sweep over sweep_cases → publish. What a case and a sweep
// write: results/case_output.h, results/sweep_output.h.
#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/units.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/presets.h"
#include "fe_stage/results/collective_write.h"
#include "fe_stage/results/case_output.h"
#include "fe_stage/results/sweep_output.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/rolling_restart.h"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>

#include <unistd.h>

using namespace clearjoint;

namespace
{
  int rank_of(MPI_Comm comm)
  {
    int r = 0;
    MPI_Comm_rank(comm, &r);
    return r;
  }

  /// An unexpected error may be thrown on one rank only, while the others wait in a collective
  /// call: with several ranks, end them all rather than hang.
  void abort_other_ranks(const int code)
  {
    int n = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    if (n > 1)
      MPI_Abort(MPI_COMM_WORLD, code);
  }

  /// The work folder a run writes into and the final folder it becomes (publish): messages
  /// name the final folder, where the user will find the files.
  std::string work_root, final_root;
  std::string shown(const std::string &path)
  {
    if (!work_root.empty() && path.compare(0, work_root.size(), work_root) == 0)
      return final_root + path.substr(work_root.size());
    return path;
  }

  /// The signal any rank received (collective: every rank calls it after each increment), so
  /// that all ranks stop together at the same point instead of some waiting in a collective.
  int interrupted_anywhere()
  {
    int local = interrupt::signal_received(), any = 0;
    MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return any;
  }
  int signal_seen = 0;  ///< what interrupted_anywhere() returned last (for the exit code)

  /// The work folder, registered on rank 0 so that a hard stop (a signal inside a long setup
  /// or solve, common/interrupt.h) removes it too.
  interrupt::Temporary work_temporary;

  /// A folder made on rank 0; a full disk or an I/O error is a WriteError naming it.
  void make_folder(const std::string &dir)
  {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      throw WriteError(dir, ec.message());
  }

  // Outputs are written into "<DIR>.tmp.<pid of rank 0>" and renamed to DIR as a whole when the
  // run ends (complete, or incomplete after a numerical failure: then marked so): an
  // interrupted run never leaves VTU/PVD or CSV files under DIR, and a rerun replaces every old
  // output (no stale VTU files beside a new PVD).
  std::string work_dir_for(std::string dir)
  {
    long pid = static_cast<long>(::getpid());
    MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    while (dir.size() > 1 && dir.back() == '/')
      dir.pop_back();
    return dir + ".tmp." + std::to_string(pid);
  }

  /// Manifests record paths as written (inside the work folder): point them at DIR before the
  /// rename (the hashes are of the contents, which the rename does not change).
  void repoint_manifests(const std::string &work, const std::string &dir)
  {
    namespace fs = std::filesystem;
    for (const auto &entry : fs::recursive_directory_iterator(work))
      if (entry.is_regular_file() && entry.path().filename() == "manifest.json")
        {
          std::string text = read_file(entry.path().string());
          for (std::size_t p; (p = text.find(work)) != std::string::npos;)
            text.replace(p, work.size(), dir);
          write_file_atomically(entry.path().string(), text);
        }
  }

  /// Rank 0 replaces DIR by the finished work folder.
  void publish(const std::string &work, const std::string &dir)
  {
    namespace fs = std::filesystem;
    fe::write_collectively(MPI_COMM_WORLD, [&] {
      if (rank_of(MPI_COMM_WORLD) != 0)
        return;
      repoint_manifests(work, dir);
      std::error_code ec;
      fs::remove_all(dir, ec);
      fs::rename(work, dir, ec);
      if (ec)
        throw NumericalError("cannot rename " + work + " to " + dir + ": " + ec.message());
      work_temporary.release();
    });
  }

  /// No run is "complete" with a NaN or Inf in its curve (issue 16): it is a numerical failure.
  void fail_on_non_finite(fe::RunResult &result)
  {
    for (const auto &r : result.increments)
      for (const double v : {r.delta, r.force, r.force_support, r.force_load, r.max_penetration,
                             r.pressure_min, r.pressure_max})
        if (result.complete && !std::isfinite(v))
          {
            result.complete = false;
            result.message = "non-finite value (" + format_value(v) +
                             ") in the increment to delta = " + format_value(r.delta) + " m";
          }
  }

  /// One case: CSV + fields + manifest in `dir` (written by rank 0's CaseOutput). Returns true
  /// if complete.
  bool run_case(const fe::FeScene &scene, const std::string &dir, int argc, char **argv,
                const bool plots, const fe::PresetUse &preset, double &force_at_max,
                fe::ImpactSummary *impact = nullptr, const fe::RunOptions::Restart &restart = {})
  {
    const bool root = rank_of(MPI_COMM_WORLD) == 0;
    // What rank 0 writes, every rank learns about (a full disk: all ranks stop together).
    const auto on_root = [&](const std::function<void()> &write) {
      fe::write_collectively(MPI_COMM_WORLD, [&] {
        if (root)
          write();
      });
    };
    std::unique_ptr<fe::CaseOutput> output;
    on_root([&] {
      make_folder(dir);
      output = std::make_unique<fe::CaseOutput>(scene, dir, argc, argv, preset);
    });
    fe::RunOptions options;
    options.restart = restart;
    options.output_dir = dir;
    options.write_fields = scene.output.fields;
    options.on_increment = [&](const fe::IncrementRecord &r) {
      on_root([&] { output->write_increment(r); });
      if ((signal_seen = interrupted_anywhere()) != 0)
        throw interrupt::Interrupted("after the increment to delta = " + format_value(r.delta) +
                                     " m");
    };
    options.on_dynamic_step = [&](const fe::DynamicStepRecord &r) {
      on_root([&] { output->write_dynamic_step(r); });
      if ((signal_seen = interrupted_anywhere()) != 0)
        throw interrupt::Interrupted("after the time step to t = " + format_value(r.time) + " s");
    };
    options.on_rolling_step = [&](const fe::RollingStepRecord &r) {
      on_root([&] { output->write_rolling_step(r); });
    };
    fe::RunResult result = fe::run_scene(scene, options);
    if (impact)
      *impact = result.impact;
    fail_on_non_finite(result);
    force_at_max = result.increments.empty() ? 0.0 : result.increments.back().force;
    on_root([&] { output->finish(result, plots, shown(dir)); });
    return result.complete;
  }

  /// The command line: its options, and the folders a run writes.
  struct CommandLine
  {
    std::string scene_path;
    std::string output_dir;  ///< --output; the work folder once it is made
    std::string final_dir;   ///< --output once the work folder is made (empty before)
    bool print_defaults = false, full_model = false, no_fields = false, no_plots = false,
         quiet = false, verbose = false, check = false;
    fe::PresetUse preset;
    fe::RunOptions::Restart restart;  ///< --write-restart, --restart-every, --resume
  };

  void add_options(CLI::App &app, CommandLine &cl)
  {
    app.add_option("scene", cl.scene_path, "scene file (YAML or JSON, schema clearjoint.fe/1)");
    app.add_option("--output,-o", cl.output_dir, "output directory");
    app.add_flag("--print-defaults", cl.print_defaults,
                 "print the default scene with units and exit");
    app.add_option("--preset", cl.preset.name,
                   "the mesh of a pipeline preset, fast | standard | accurate, as run_pipeline "
                   "uses it (its measured cost and error: docs/benchmarks.md)");
    app.add_option("--presets-file", cl.preset.file,
                   "the pipeline file whose presets --preset reads (default: the source tree's "
                   "pipeline.yaml)");
    app.add_flag("--full-model", cl.full_model,
                 "model the full joint instead of the quarter model");
    app.add_flag("--no-fields", cl.no_fields, "do not write VTU fields");
    app.add_flag("--no-plots", cl.no_plots, "do not draw the force-penetration plots (PNG)");
    app.add_flag("--quiet,-q", cl.quiet, "warnings and errors only");
    app.add_flag("--verbose,-v", cl.verbose,
                 "debug messages: every active-set iteration's changed nodes and Coulomb "
                 "slip-law residual");
    app.add_flag("--check", cl.check,
                 "read and validate the scene (and its mesh) and exit: 0 valid, 1 input error; "
                 "writes nothing");
    app.add_option("--write-restart", cl.restart.write_dir,
                   "study rolling: write the run's state to this folder after every converged "
                   "step (--restart-every), so that --resume can continue it; outside --output");
    app.add_option("--restart-every", cl.restart.every,
                   "with --write-restart: every how many steps (>= 1; default 1; the last "
                   "step's state is always written)");
    app.add_option("--resume", cl.restart.resume_dir,
                   "study rolling: continue the run whose state --write-restart wrote to this "
                   "folder (the same scene, output.* aside, and the same number of MPI ranks); "
                   "its state is written there again unless --write-restart names another");
  }

  /// A folder as an absolute path without . and .. (it need not exist).
  std::filesystem::path absolute_folder(const std::string &dir)
  {
    return std::filesystem::weakly_canonical(std::filesystem::absolute(dir));
  }

  /// Whether `inner` is `outer` or a folder below it.
  bool folder_within(const std::filesystem::path &inner, const std::filesystem::path &outer)
  {
    const auto mismatch = std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
    return mismatch.first == outer.end();
  }

  /// The restart options against the scene and --output: the rolling study only, a folder
  /// apart from the outputs (which a run replaces as a whole).
  void check_restart_options(CommandLine &cl, const fe::FeScene &scene)
  {
    auto &r = cl.restart;
    if (r.every == 0)
      throw InputError("", "--restart-every", "0", ">= 1 steps");
    if (r.write_dir.empty() && r.resume_dir.empty())
      return;
    const std::string flag = r.resume_dir.empty() ? "--write-restart" : "--resume";
    if (scene.study != fe::Study::rolling)
      throw InputError("", flag, r.resume_dir.empty() ? r.write_dir : r.resume_dir,
                       "only with study: rolling (the other studies run in minutes)");
    if (!r.resume_dir.empty() && fe::detail::RestartFolder::complete_state(r.resume_dir).empty())
      throw InputError("", "--resume", r.resume_dir,
                       "a folder that fe_stage --write-restart wrote a state to",
                       "it has no state/ (nor previous/) folder");
    if (r.write_dir.empty())
      r.write_dir = r.resume_dir;  // a chain of runs keeps one folder
    if (!cl.output_dir.empty())
      for (const std::string *dir : {&r.write_dir, &r.resume_dir})
        if (!dir->empty())
          {
            const auto a = absolute_folder(*dir), b = absolute_folder(cl.output_dir);
            if (folder_within(a, b) || folder_within(b, a))
              throw InputError("", dir == &r.write_dir ? "--write-restart" : "--resume", *dir,
                               "a folder apart from --output " + cl.output_dir,
                               "a run replaces its output folder as a whole");
          }
  }

  /// --preset: the preset's keys set on the scene document as run_pipeline sets them.
  void apply_preset(nlohmann::json &scene_doc, fe::PresetUse &preset, const bool root)
  {
    if (preset.file.empty())
      preset.file = fe::default_presets_file();
    preset.overrides = fe::read_fe_preset(preset.file, preset.name);
    const auto list = [](const fe::PresetOverrides &overrides) {
      std::string keys;
      for (const auto &[k, v] : overrides)
        keys += (keys.empty() ? "" : ", ") + k + " = " + v.dump();
      return keys.empty() ? std::string("no FE keys") : keys;
    };
    std::string keys = list(preset.overrides);
    // a rolling scene also gets the file's rolling.overrides, as run_pipeline sets them
    const auto study = scene_doc.find("study");
    if (study != scene_doc.end() && *study == "rolling")
      {
        const fe::PresetOverrides rolling = fe::read_rolling_overrides(preset.file);
        if (!rolling.empty())
          keys += "; then rolling.overrides: " + list(rolling);
        preset.overrides.insert(preset.overrides.end(), rolling.begin(), rolling.end());
        const fe::PresetOverrides own = fe::read_rolling_preset(preset.file, preset.name);
        if (!own.empty())
          keys += "; then rolling.presets." + preset.name + ": " + list(own);
        preset.overrides.insert(preset.overrides.end(), own.begin(), own.end());
      }
    fe::apply_preset(scene_doc, preset.overrides, preset.file);
    if (root)
      log::info("fe_stage: preset " + preset.name + " (" + preset.file + "): " + keys);
  }

  /// All input errors before any output: the scene, with the preset's keys set as
  /// run_pipeline sets them, and the command line's flags.
  fe::FeScene read_scene(CommandLine &cl, const bool root)
  {
    if (cl.scene_path.empty())
      throw InputError("", "scene", "(none)", "a scene file",
                       "usage: fe_stage SCENE.yaml --output DIR");
    if (cl.output_dir.empty() && !cl.check)
      throw InputError("", "--output", "(none)", "a directory",
                       "usage: fe_stage SCENE.yaml --output DIR");
    nlohmann::json scene_doc = read_structured_file(cl.scene_path);
    if (!cl.preset.name.empty())
      apply_preset(scene_doc, cl.preset, root);
    else if (!cl.preset.file.empty())
      throw InputError("", "--presets-file", cl.preset.file, "only together with --preset");
    fe::FeScene scene = fe::scene_from_json(scene_doc, cl.scene_path);
    if (cl.full_model)
      scene.full_model = true;
    if (cl.no_fields)
      scene.output.fields = false;
    fe::validate_scene(scene);
    check_restart_options(cl, scene);
    return scene;
  }

  /// The work folder, made by rank 0: one that cannot be made (a file in the way, no
  /// permission) is an input error naming --output on every rank (the others would otherwise
  /// wait for rank 0 in the next collective call). Returns false (logged) if it failed.
  bool make_work_folder(CommandLine &cl, const bool root)
  {
    check_output_replaceable(cl.output_dir, "fe_stage");
    cl.final_dir = cl.output_dir;
    cl.output_dir = work_dir_for(cl.output_dir);
    work_root = cl.output_dir;
    final_root = cl.final_dir;
    std::string work_error;
    if (root)
      try
        {
          create_work_folder(cl.output_dir, cl.final_dir);
          work_temporary.set(cl.output_dir);
        }
      catch (const InputError &e)
        {
          work_error = e.what();
        }
    int work_ok = work_error.empty() ? 1 : 0;
    MPI_Bcast(&work_ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!work_ok && root)
      log::error(work_error);
    return work_ok;
  }

  /// One case per swept value (t_B [m], θ [deg]) or, for the impact study, per pair of velocity
  /// [m/s] and journal mass [kg], each in its own folder (value: t_B, θ or v).
  struct Case
  {
    fe::FeScene scene;
    std::string folder;
    double value;
  };

  std::vector<Case> sweep_cases(const fe::FeScene &scene, const std::string &output_dir)
  {
    std::vector<Case> cases;
    for (const double t : scene.sweep_t_B)
      {
        Case c{scene, output_dir + "/t_B_" + fe::short_number(units::to_mm(t)) + "mm", t};
        c.scene.geometry.t_B = t;
        cases.push_back(c);
      }
    for (const double th : scene.sweep_theta_deg)
      {
        Case c{scene, output_dir + "/theta_" + fe::short_number(th) + "deg", th};
        c.scene.misalignment.theta_deg = th;
        cases.push_back(c);
      }
    // study impact: every velocity at every journal mass (the masses outside); a list that is
    // not given is the scene's one value
    const bool by_mass = !scene.sweep_journal_mass.empty(), by_v = !scene.sweep_velocity.empty();
    const std::vector<double> masses = by_mass ? scene.sweep_journal_mass : std::vector<double>{0.0};
    const std::vector<double> velocities =
      by_v ? scene.sweep_velocity : std::vector<double>{scene.impact.velocity};
    if (by_mass || by_v)
      for (const double m : masses)
        for (const double v : velocities)
          {
            std::string name = by_mass ? "m_" + fe::short_number(m) + "kg" : "";
            if (by_v)
              name += (name.empty() ? "" : "_") + std::string("v_") + fe::short_number(v) + "mps";
            Case c{scene, output_dir + "/" + name, v};
            c.scene.impact.velocity = v;
            if (by_mass)
              c.scene.impact.journal_mass = m;
            cases.push_back(c);
          }
    for (auto &c : cases)
      {
        c.scene.sweep_t_B.clear();
        c.scene.sweep_theta_deg.clear();
        c.scene.sweep_velocity.clear();
        c.scene.sweep_journal_mass.clear();
      }
    return cases;
  }

  /// The cases one after the other (stopping at the first that fails), the sweep table and the
  /// top manifest. Returns true if every case is complete.
  bool run_sweep(const fe::FeScene &scene, const CommandLine &cl, int argc, char **argv,
                 const bool root)
  {
    std::vector<Case> cases = sweep_cases(scene, cl.output_dir);
    std::unique_ptr<fe::SweepOutput> output;
    const auto on_root = [&](const std::function<void()> &write) {
      fe::write_collectively(MPI_COMM_WORLD, [&] {
        if (root)
          write();
      });
    };
    on_root([&] {
      output = std::make_unique<fe::SweepOutput>(cl.output_dir, fe::sweep_kind(scene),
                                                 cl.scene_path, argc, argv);
    });
    bool complete = true;
    for (std::size_t k = 0; k < cases.size(); ++k)
      {
        const auto &c = cases[k];
        if (root)
          log::info("fe_stage: case " + std::to_string(k + 1) + " of " +
                    std::to_string(cases.size()) + ": " + shown(c.folder));
        fe::SweepCase result;
        result.folder = c.folder;
        result.value = c.value;
        const bool ok = run_case(c.scene, c.folder, argc, argv, !cl.no_plots, cl.preset,
                                 result.force_at_delta_max, &result.impact);
        complete = complete && ok;
        on_root([&] { output->add_case(result); });
        if (!ok)
          break;
      }
    on_root([&] { output->finish(complete, !cl.no_plots); });
    return complete;
  }

  /// --print-defaults and --check: nothing parallel, so MPI is not started (under mpirun the
  /// ranks other than 0 stay silent). Returns the exit code.
  int without_mpi(CommandLine &cl)
  {
    const bool root = fe::launcher_rank().value_or(0) == 0;
    if (!root)
      log::set_level(log::Level::error);
    try
      {
        if (cl.print_defaults)
          {
            if (root)
              std::cout << fe::default_scene_yaml();
            return exit_success;
          }
        read_scene(cl, root);
        if (root)
          log::info("fe_stage: " + cl.scene_path + " is a valid scene");
        return exit_success;
      }
    catch (const InputError &e)
      {
        if (root)
          log::error(e.what());
        return exit_input_error;
      }
    catch (const std::exception &e)
      {
        log::error(std::string("fe_stage: ") + e.what());
        return exit_numerical_error;
      }
  }

  /// After the command line: the scene, the work folder, the case or the sweep, and the
  /// folder published. Returns the exit code.
  int run(CommandLine &cl, int argc, char **argv, const bool root)
  {
    const fe::FeScene scene = read_scene(cl, root);
    if (!make_work_folder(cl, root))
      return exit_input_error;  // nothing was made: no folder to remove
    bool complete = true;
    if (!fe::has_sweep(scene))
      {
        double f;
        complete = run_case(scene, cl.output_dir, argc, argv, !cl.no_plots, cl.preset, f, nullptr,
                            cl.restart);
      }
    else
      complete = run_sweep(scene, cl, argc, argv, root);
    publish(cl.output_dir, cl.final_dir);
    return complete ? exit_success : exit_numerical_error;
  }
}  // namespace

int main(int argc, char **argv)
{
  // A signal during MPI's start-up (seconds on a loaded machine) is noted too, not fatal; the
  // handlers are installed again after it in case MPI set its own.
  interrupt::install();
  CLI::App app{"fe_stage: FE contact model of a revolute joint with clearance (clearjoint): "
               "force-penetration curves (study radial, misalignment, hertz, patch), the "
               "journal's impact (study impact, HHT-alpha dynamics) and its rolling in the "
               "turning elastoplastic bearing (study rolling).\n"
               "Exit codes: 0 success, 1 input error, 2 numerical failure, 130/143 interrupted "
               "by SIGINT/SIGTERM."};
  CommandLine cl;
  add_options(app, cl);
  // The command line is read before MPI starts: --help, --print-defaults and --check need no
  // MPI, and Open MPI's start alone takes ~1.3 s of a 1.4 s check (run_pipeline checks every
  // generated scene before its first task; docs/benchmarks.md "The pipeline's start").
  try
    {
      app.parse(argc, argv);
    }
  catch (const CLI::ParseError &e)
    {
      return app.exit(e) == 0 ? exit_success : exit_input_error;
    }
  if (cl.quiet)
    log::set_level(log::Level::warning);
  if (cl.verbose)
    log::set_level(log::Level::debug);
  if (cl.print_defaults || cl.check)
    return without_mpi(cl);

  const auto runtime = fe::make_runtime(argc, argv);
  const bool root = rank_of(MPI_COMM_WORLD) == 0;
  // SIGINT/SIGTERM: stop after the current increment (all ranks together), or, inside a long
  // setup or solve, at once after a grace. Rank 0, which removes the work folder, goes first
  // (0.3 s): an interrupted mpirun sends its ranks SIGCONT, SIGTERM 1 s later and SIGKILL 1 s
  // after that, but kills the others at once when one rank exits. The other ranks wait 1.5 s
  // (mpirun ends them when rank 0 exits; without mpirun they exit by themselves).
  interrupt::install();
  interrupt::arm_hard_stop("fe_stage", root ? 0.3 : 1.5, root);
  if (!root)
    log::set_level(log::Level::error);
  try
    {
      return run(cl, argc, argv, root);
    }
  catch (const interrupt::Interrupted &e)
    {
      if (root)
        {
          std::error_code ec;
          std::filesystem::remove_all(cl.output_dir, ec);
          log::error(std::string(e.what()) + "; " + cl.output_dir + " removed" +
                     (cl.final_dir.empty() ? "" : ", " + cl.final_dir + " left as it was"));
        }
      const int code = 128 + (signal_seen != 0 ? signal_seen : interrupt::signal_received());
      if (signal_seen == 0 && !fe::failed_together())  // rank 0 alone: the others may wait
        abort_other_ranks(code);
      return code;
    }
  catch (const WriteError &e)
    {
      // A full disk or an I/O error: one line naming the file and the reason; nothing left.
      if (root)
        {
          std::error_code ec;
          if (!cl.final_dir.empty())
            std::filesystem::remove_all(cl.output_dir, ec);
          log::error(std::string("fe_stage: ") + e.what() +
                     (cl.final_dir.empty() ? std::string() :
                                             "; " + cl.output_dir + " removed, " + cl.final_dir +
                                               " left as it was"));
        }
      if (!fe::failed_together())
        abort_other_ranks(exit_write_error);
      return exit_write_error;
    }
  catch (const fe::StoppedElsewhere &e)
    {
      // The rank that failed reports it; rank 0 removes the work folder.
      if (root && !cl.final_dir.empty())
        {
          std::error_code ec;
          std::filesystem::remove_all(cl.output_dir, ec);
        }
      return e.exit_code();
    }
  catch (const InputError &e)
    {
      if (root)
        log::error(e.what());
      if (root && !cl.final_dir.empty())  // e.g. a mesh rejected while setting up a case
        {
          std::error_code ec;
          std::filesystem::remove_all(cl.output_dir, ec);
        }
      return exit_input_error;
    }
  catch (const NumericalError &e)
    {
      log::error(e.what());
      if (!fe::failed_together())
        abort_other_ranks(exit_numerical_error);
      return exit_numerical_error;
    }
  catch (const std::exception &e)
    {
      log::error(std::string("fe_stage: ") + e.what());
      if (!fe::failed_together())
        abort_other_ranks(exit_numerical_error);
      return exit_numerical_error;
    }
}
