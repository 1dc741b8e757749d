// fe_stage: the FE contact model of a revolute joint with clearance (SPEC §2).
//
//   fe_stage SCENE.yaml --output DIR [--preset fast|standard|accurate] [--full-model]
//            [--no-fields] [--no-plots]
//   fe_stage --print-defaults
//   fe_stage SCENE.yaml --check      (read and validate the scene and its mesh only)
//
// Writes DIR/force_penetration.csv (delta, force, solver statistics per increment),
// DIR/fields/ (VTU/PVTU + PVD), DIR/force_penetration.png and DIR/manifest.json; with a `sweep`
// block, one such folder per swept value under DIR plus DIR/manifest.json, DIR/sweep.csv and
// DIR/sweep.png (every case's curve). Study impact: force_penetration.csv is the quasi-static
// reference curve, and DIR/impact_history.csv (one row per time step) and DIR/impact.png are
// added; a sweep over impact.velocity writes DIR/impact_sweep.csv and DIR/impact_sweep.png.
// Everything is written into DIR.tmp.<pid> and renamed to DIR at the end (an earlier DIR is
// replaced as a whole).
// Exit codes: 0 success, 1 input error, 2 numerical failure (CSV and manifest marked incomplete),
// 130/143 interrupted by SIGINT/SIGTERM (after the current increment; DIR.tmp.<pid> removed).
#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/strict_reader.h"
#include "common/units.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/results/impact_output.h"
#include "fe_stage/results/rolling_output.h"
#include "fe_stage/presets.h"
#include "fe_stage/scene.h"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

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

  std::string label(const double v)
  {
    std::ostringstream o;
    o << v;
    return o.str();
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

  /// The yield check for the manifest: per body its volume, the volume above the yield stress
  /// and the largest von Mises stress with its place (SI, units stated).
  nlohmann::json yield_check_json(const fe::YieldCheck &y)
  {
    nlohmann::json bodies = nlohmann::json::array();
    for (const auto &b : y.bodies)
      bodies.push_back(
        {{"body", b.name},
         {"volume", {{"value", b.volume}, {"unit", "m^3"}}},
         {"volume_above_yield", {{"value", b.volume_above_yield}, {"unit", "m^3"}}},
         {"fraction_above_yield", b.volume > 0.0 ? b.volume_above_yield / b.volume : 0.0},
         {"max_von_mises", {{"value", b.max_von_mises}, {"unit", "Pa"}}},
         {"max_location", {{"value", b.max_location}, {"unit", "m"}}}});
    return {{"yield_stress", {{"value", y.yield_stress}, {"unit", "Pa"}}},
            {"exceeded", y.exceeded()},
            {"note", "linear-elastic model: von Mises above the yield stress means the result "
                     "is not valid there (field plastic_zone: volume fraction above yield)"},
            {"bodies", bodies}};
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

  /// How the scene was made: the preset of pipeline.yaml applied to it, if any.
  struct PresetUse
  {
    std::string name, file;
    fe::PresetOverrides overrides;
  };

  /// The signal any rank received (collective: every rank calls it after each increment), so
  /// that all ranks stop together at the same point instead of some waiting in a collective.
  int interrupted_anywhere()
  {
    int local = interrupt::signal_received(), any = 0;
    MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return any;
  }
  int signal_seen = 0;  ///< what interrupted_anywhere() returned last (for the exit code)

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
    if (rank_of(MPI_COMM_WORLD) == 0)
      {
        repoint_manifests(work, dir);
        std::error_code ec;
        fs::remove_all(dir, ec);
        fs::rename(work, dir, ec);
        if (ec)
          throw NumericalError("cannot rename " + work + " to " + dir + ": " + ec.message());
      }
    MPI_Barrier(MPI_COMM_WORLD);
  }

  /// One case: CSV + fields + manifest in `dir`. Returns true if complete.
  bool run_case(const fe::FeScene &scene, const std::string &dir, int argc, char **argv,
                const bool plots, const PresetUse &preset, double &force_at_max,
                fe::ImpactSummary *impact = nullptr)
  {
    const bool is_impact = scene.study == fe::Study::impact;
    const bool root = rank_of(MPI_COMM_WORLD) == 0;
    if (root)
      std::filesystem::create_directories(dir);
    MPI_Barrier(MPI_COMM_WORLD);
    std::unique_ptr<Manifest> manifest;
    std::unique_ptr<CsvWriter> csv;
    const std::string csv_path = dir + "/force_penetration.csv";
    if (root)
      {
        manifest = std::make_unique<Manifest>("fe_stage", dir + "/manifest.json", argc, argv);
        if (!scene.source_file.empty())
          manifest->add_input(scene.source_file);
        for (const auto &[k, v] : fe::fe_library_versions())
          manifest->set_library_version(k, v);
        if (!scene.geometry.mesh.empty())
          manifest->add_input(scene.geometry.mesh);
        if (!preset.name.empty())
          {
            manifest->add_input(preset.file);
            nlohmann::json o = nlohmann::json::object();
            for (const auto &[k, v] : preset.overrides)
              o[k] = v;
            manifest->extra()["preset"] = {{"name", preset.name}, {"file", preset.file},
                                           {"scene_keys", o}};
          }
        manifest->extra()["scene"] = fe::scene_to_json(scene);
        std::vector<std::string> comments = {
          "clearjoint fe_stage: force-penetration curve, study " + fe::to_string(scene.study) +
            ", journal loading " + fe::to_string(scene.loading.journal),
          "force = total contact force of the FULL body: the modelled part's nodal contact "
          "forces times the symmetry factor (4 for the quarter model, 2 for the half model of "
          "the misalignment study, 1 for --full-model)",
          "force_support = the same force measured as the reaction of the supports (equilibrium "
          "check); force_load = the reaction on the journal's loaded set (the paper's measure)",
          "delta = push of the rigid obstacle beyond first touch",
          "friction_* = Coulomb's law checked at every contact node of the converged increment, "
          "as fractions of mu*lambda_max: cone_excess = max(|t_T| - mu*lambda)+, slip_law_error = "
          "max ||t_T| - mu*lambda| at slipping nodes, direction_error = max 1 + cos(t_T, slip); "
          "0 without friction"};
        comments.push_back(scene.contact.mu > 0.0 ?
                             "Coulomb friction mu = " + format_value(scene.contact.mu) +
                               " (stick/slip active set); slipping_contact_points of the active "
                               "points slip, the rest stick" :
                             "frictionless contact (mu = 0)");
        csv = std::make_unique<CsvWriter>(
          csv_path,
          std::vector<std::string>{"delta", "force", "force_support", "force_load", "contact_iterations",
                                   "linear_iterations", "active_contact_points",
                                   "slipping_contact_points", "max_penetration", "pressure_min",
                                   "pressure_max", "wall_time", "friction_cone_excess",
                                   "friction_slip_law_error", "friction_direction_error"},
          std::vector<std::string>{"m", "N", "N", "N", "1", "1", "1", "1", "m", "Pa", "Pa", "s",
                                   "1", "1", "1"},
          comments);
        csv->write_row({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
      }
    // Study impact: force_penetration.csv holds the quasi-static reference curve of the same
    // mesh; the time history goes to impact_history.csv.
    std::unique_ptr<CsvWriter> history;
    const std::string history_path = dir + "/impact_history.csv";
    if (root && is_impact)
      {
        history = std::make_unique<CsvWriter>(history_path, fe::impact_history_columns(),
                                              fe::impact_history_units(),
                                              fe::impact_history_comments(scene));
        history->write_row(fe::impact_history_start(scene));
      }
    // Study rolling: the time history and, at the end, the strain profile.
    const bool is_rolling = scene.study == fe::Study::rolling;
    std::unique_ptr<CsvWriter> rolling_history;
    const std::string rolling_path = dir + "/rolling_history.csv";
    if (root && is_rolling)
      {
        const auto table = fe::rolling_history_table();
        rolling_history = std::make_unique<CsvWriter>(rolling_path, table.columns, table.units,
                                                      fe::rolling_history_comments(scene));
        rolling_history->write_row(fe::rolling_history_start());
      }
    fe::RunOptions options;
    options.output_dir = dir;
    options.write_fields = scene.output.fields;
    options.on_increment = [&](const fe::IncrementRecord &r) {
      if (csv)
        csv->write_row({r.delta, r.force, r.force_support, r.force_load, double(r.contact_iterations),
                        double(r.linear_iterations), double(r.n_active), double(r.n_slip),
                        r.max_penetration,
                        r.pressure_min, r.pressure_max, r.wall_time, r.friction_cone_excess,
                        r.friction_slip_law_error, r.friction_direction_error});
      if ((signal_seen = interrupted_anywhere()) != 0)
        throw interrupt::Interrupted("after the increment to delta = " + format_value(r.delta) +
                                     " m");
    };
    options.on_dynamic_step = [&](const fe::DynamicStepRecord &r) {
      if (history)
        history->write_row(fe::impact_history_row(r));
      if ((signal_seen = interrupted_anywhere()) != 0)
        throw interrupt::Interrupted("after the time step to t = " + format_value(r.time) + " s");
    };
    options.on_rolling_step = [&](const fe::RollingStepRecord &r) {
      if (rolling_history)
        rolling_history->write_row(fe::rolling_history_row(r));
    };
    fe::RunResult result = fe::run_scene(scene, options);
    if (impact)
      *impact = result.impact;
    // No run is "complete" with a NaN or Inf in its curve (issue 16): it is a numerical failure.
    for (const auto &r : result.increments)
      for (const double v : {r.delta, r.force, r.force_support, r.force_load, r.max_penetration,
                             r.pressure_min, r.pressure_max})
        if (result.complete && !std::isfinite(v))
          {
            result.complete = false;
            result.message = "non-finite value (" + format_value(v) +
                             ") in the increment to delta = " + format_value(r.delta) + " m";
          }
    force_at_max = result.increments.empty() ? 0.0 : result.increments.back().force;
    if (root)
      {
        if (result.complete)
          csv->commit();
        else
          csv->commit_incomplete(result.message);
        manifest->add_output(csv_path);
        if (history)
          {
            if (result.complete)
              history->commit();
            else
              history->commit_incomplete(result.message);
            manifest->add_output(history_path);
            manifest->extra()["impact"] = fe::impact_summary_json(result.impact);
            // F(t), δ(t), F(δ) over the quasi-static curve, and the energies
            if (plots && !result.dynamic_steps.empty() &&
                run_plot_script("fe_impact", {dir + "/impact.png", dir}))
              manifest->add_output(dir + "/impact.png");
          }
        if (rolling_history)
          {
            if (result.complete)
              rolling_history->commit();
            else
              rolling_history->commit_incomplete(result.message);
            manifest->add_output(rolling_path);
            const std::string profile_path = dir + "/rolling_strain_profile.csv";
            const auto table = fe::strain_profile_table();
            CsvWriter profile(profile_path, table.columns, table.units,
                              {"clearjoint fe_stage: the bore's (body 0) and a deformable "
                               "journal's (body 1) strains across the contact zone at the end "
                               "of the rolling study (paper Fig. 12), axial mid-plane, angle "
                               "from the contact point about the body's own axis "
                               "(counter-clockwise, fixed frame), arc = R_B or R_J times it; "
                               "strains are total, von_mises from the cell's mean plastic "
                               "strain"});
            for (const auto &p : result.strain_profile)
              profile.write_row(fe::strain_profile_row(p));
            if (result.complete)
              profile.commit();
            else
              profile.commit_incomplete(result.message);
            manifest->add_output(profile_path);
            manifest->extra()["rolling"] = fe::rolling_summary_json(
              result.rolling, result.rolling_steps.empty() ? nullptr : &result.rolling_steps.back());
            // the slip stages go to the plot as text: the manifest is written after it
            if (plots && !result.rolling_steps.empty() &&
                run_plot_script("fe_rolling", {dir + "/rolling.png", dir,
                                               manifest->extra()["rolling"].dump()}))
              manifest->add_output(dir + "/rolling.png");
          }
        for (const auto &f : result.field_files)
          manifest->add_output(f);
        // F–δ, linear and log–log (a warning, not a failure, if Python/matplotlib is missing)
        if (plots && !result.increments.empty() &&
            run_plot_script("fe", {dir + "/force_penetration.png", dir}))
          manifest->add_output(dir + "/force_penetration.png");
        auto &x = manifest->extra();
        if (!result.adaptive_cycles.empty())
          {
            // One row per adaptive mesh: what a convergence plot needs (the last row is the
            // recorded curve's mesh), and the error estimate from the sequence.
            const std::string path = dir + "/adaptive_cycles.csv";
            CsvWriter cycles(path,
                             {"cycle", "n_cells", "n_dofs", "force_at_delta_max",
                              "contact_iterations", "wall_time"},
                             {"1", "1", "1", "N", "1", "s"},
                             {"clearjoint fe_stage: adaptive refinement, mesh.adaptive_cycles = " +
                                std::to_string(scene.mesh.adaptive_cycles) +
                                ", adaptive_fraction = " +
                                format_value(scene.mesh.adaptive_fraction) +
                                " (Kelly indicator, fixed fraction of the cells)",
                              "force_at_delta_max = F at delta_max on that mesh (full body; "
                              "marking meshes pushed in mesh.adaptive_increments = " +
                                std::to_string(scene.mesh.adaptive_increments) +
                                " steps); the last row is the recorded curve's mesh" +
                                (scene.mesh.adaptive_target_error > 0.0 ?
                                   std::string("; target error ") +
                                     format_value(scene.mesh.adaptive_target_error) +
                                     (result.adaptive_target_reached ? " reached" :
                                                                       " NOT reached") :
                                   std::string())});
            nlohmann::json rows = nlohmann::json::array();
            for (std::size_t k = 0; k < result.adaptive_cycles.size(); ++k)
              {
                const auto &c = result.adaptive_cycles[k];
                cycles.write_row({double(k), double(c.n_cells), double(c.n_dofs), c.force,
                                  double(c.contact_iterations), c.wall_time});
                rows.push_back({{"n_cells", c.n_cells}, {"n_dofs", c.n_dofs},
                                {"force_at_delta_max", {{"value", c.force}, {"unit", "N"}}},
                                {"contact_iterations", c.contact_iterations},
                                {"wall_time", {{"value", c.wall_time}, {"unit", "s"}}}});
              }
            cycles.commit();
            manifest->add_output(path);
            x["adaptive"] = {{"cycles", rows}, {"fraction", scene.mesh.adaptive_fraction},
                             {"marking_increments", scene.mesh.adaptive_increments}};
            if (scene.mesh.adaptive_target_error > 0.0)
              x["adaptive"]["target_error"] = {
                {"value", scene.mesh.adaptive_target_error}, {"unit", "1"},
                {"reached", result.adaptive_target_reached},
                {"max_cycles", scene.mesh.adaptive_cycles}};
            if (result.adaptive_error >= 0.0)
              x["adaptive"]["estimated_error_F_max"] = {
                {"value", result.adaptive_error}, {"unit", "1"},
                {"method", result.adaptive_error_method}};
            if (result.adaptive_order > 0.0)
              x["adaptive"]["extrapolated_force"] = {
                {"value", result.adaptive_extrapolated_force}, {"unit", "N"}};
          }
        if (scene.contact.sliding == fe::Contact::Sliding::finite)
          x["finite_sliding"] = {{"pattern_rebuilds", result.sliding_rebuilds},
                                 {"increments_solved_again", result.sliding_resolves}};
        x["n_dofs"] = result.n_dofs;
        x["n_cells"] = result.n_cells;
        x["n_mpi_ranks"] = result.n_ranks;
        x["symmetry_factor"] = result.symmetry_factor;
        x["h_min"] = {{"value", result.h_min}, {"unit", "m"}};
        x["setup_time"] = {{"value", result.setup_time}, {"unit", "s"}};
        // what the VTU's contact fields hold (docs/fe.md): Abaqus's CSTATUS codes
        x["contact_fields"] = {
          {"status_codes", {{"0", "open"}, {"1", "slip"}, {"2", "stick"}}},
          {"note", "contact_shear is the friction traction (zero without friction); "
                   "contact_slip is nonzero only at contact points"}};
        x["friction"] = {{"mu", scene.contact.mu}, {"model", scene.contact.mu > 0.0 ?
                                                              "Coulomb, stick/slip active set" :
                                                              "frictionless"}};
        if (!result.increments.empty())
          {
            x["force_at_delta_max"] = {{"value", result.increments.back().force}, {"unit", "N"}};
            x["yield_check"] = yield_check_json(result.yield_check);
          }
        manifest->write(result.complete ? "complete" : "incomplete", result.message);
        log::info("fe_stage: " + shown(dir) + ": F(" + format_value(result.increments.empty() ?
                                                               0.0 :
                                                               result.increments.back().delta) +
                  " m) = " + format_value(force_at_max) + " N, " +
                  log::format_duration(result.wall_time));
        if (!result.field_files.empty())
          log::info("fe_stage: fields: open " + shown(dir) +
                    "/fields/solution.pvd in ParaView (displacement, stress, von_mises_stress, " +
                    (scene.study == fe::Study::rolling ?
                       "principal strains, equivalent_plastic_strain, von_mises_stress_max, "
                       "contact fields; each body in its own frame turning with it "
                       "(the bearing's co-rotating frame; a deformable journal as meshed, its "
                       "displacement in its frame), every " +
                         std::to_string(scene.rolling.field_stride) + " steps and at the end)" :
                       std::string("plastic_zone, contact_pressure, contact_status, "
                                   "contact_shear, contact_slip; one step per increment)")));
      }
    return result.complete;
  }
} // namespace

int main(int argc, char **argv)
{
  const auto runtime = fe::make_runtime(argc, argv);
  const bool root = rank_of(MPI_COMM_WORLD) == 0;
  // SIGINT/SIGTERM (mpirun passes them on to every rank): stop after the current increment.
  interrupt::install();
  if (!root)
    log::set_level(log::Level::error);

  CLI::App app{"fe_stage: FE contact model of a revolute joint with clearance (clearjoint): "
               "force-penetration curves (study radial, misalignment, hertz, patch), the "
               "journal's impact (study impact, HHT-alpha dynamics) and its rolling in the "
               "turning elastoplastic bearing (study rolling).\n"
               "Exit codes: 0 success, 1 input error, 2 numerical failure, 130/143 interrupted "
               "by SIGINT/SIGTERM."};
  std::string scene_path, output_dir, final_dir;
  bool print_defaults = false, full_model = false, no_fields = false, no_plots = false,
       quiet = false, verbose = false, check = false;
  PresetUse preset;
  app.add_option("scene", scene_path, "scene file (YAML or JSON, schema clearjoint.fe/1)");
  app.add_option("--output,-o", output_dir, "output directory");
  app.add_flag("--print-defaults", print_defaults, "print the default scene with units and exit");
  app.add_option("--preset", preset.name,
                 "the mesh of a pipeline preset, fast | standard | accurate, as run_pipeline "
                 "uses it (its measured cost and error: docs/benchmarks.md)");
  app.add_option("--presets-file", preset.file,
                 "the pipeline file whose presets --preset reads (default: the source tree's "
                 "pipeline.yaml)");
  app.add_flag("--full-model", full_model, "model the full joint instead of the quarter model");
  app.add_flag("--no-fields", no_fields, "do not write VTU fields");
  app.add_flag("--no-plots", no_plots, "do not draw the force-penetration plots (PNG)");
  app.add_flag("--quiet,-q", quiet, "warnings and errors only");
  app.add_flag("--verbose,-v", verbose,
               "debug messages: every active-set iteration's changed nodes and Coulomb "
               "slip-law residual");
  app.add_flag("--check", check,
               "read and validate the scene (and its mesh) and exit: 0 valid, 1 input error; "
               "writes nothing");
  try
    {
      app.parse(argc, argv);
    }
  catch (const CLI::ParseError &e)
    {
      return app.exit(e) == 0 ? exit_success : exit_input_error;
    }
  if (quiet)
    log::set_level(log::Level::warning);
  if (verbose && root)
    log::set_level(log::Level::debug);
  if (print_defaults)
    {
      if (root)
        std::cout << fe::default_scene_yaml();
      return exit_success;
    }
  try
    {
      if (scene_path.empty())
        throw InputError("", "scene", "(none)", "a scene file", "usage: fe_stage SCENE.yaml --output DIR");
      if (output_dir.empty() && !check)
        throw InputError("", "--output", "(none)", "a directory", "usage: fe_stage SCENE.yaml --output DIR");
      // all input errors before any output: the scene, with the preset's keys set as
      // run_pipeline sets them
      nlohmann::json scene_doc = read_structured_file(scene_path);
      if (!preset.name.empty())
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
            }
          fe::apply_preset(scene_doc, preset.overrides, preset.file);
          if (root)
            log::info("fe_stage: preset " + preset.name + " (" + preset.file + "): " + keys);
        }
      else if (!preset.file.empty())
        throw InputError("", "--presets-file", preset.file, "only together with --preset");
      fe::FeScene scene = fe::scene_from_json(scene_doc, scene_path);
      if (full_model)
        scene.full_model = true;
      if (no_fields)
        scene.output.fields = false;
      fe::validate_scene(scene);
      if (check)
        {
          log::info("fe_stage: " + scene_path + " is a valid scene");
          return exit_success;
        }
      check_output_replaceable(output_dir, "fe_stage");
      final_dir = output_dir;
      output_dir = work_dir_for(output_dir);
      work_root = output_dir;
      final_root = final_dir;
      // the work folder, made by rank 0: one that cannot be made (a file in the way, no
      // permission) is an input error naming --output on every rank (the others would
      // otherwise wait for rank 0 in the next collective call)
      std::string work_error;
      if (root)
        try
          {
            create_work_folder(output_dir, final_dir);
          }
        catch (const InputError &e)
          {
            work_error = e.what();
          }
      int work_ok = work_error.empty() ? 1 : 0;
      MPI_Bcast(&work_ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
      if (!work_ok)
        {
          if (root)
            log::error(work_error);
          return exit_input_error;  // nothing was made: no folder to remove
        }

      bool complete = true;
      // One case per swept value (t_B [m] or θ [deg]), each in its own folder.
      struct Case
      {
        fe::FeScene scene;
        std::string folder;
        double value;
      };
      std::vector<Case> cases;
      for (const double t : scene.sweep_t_B)
        {
          Case c{scene, output_dir + "/t_B_" + label(units::to_mm(t)) + "mm", t};
          c.scene.geometry.t_B = t;
          cases.push_back(c);
        }
      for (const double th : scene.sweep_theta_deg)
        {
          Case c{scene, output_dir + "/theta_" + label(th) + "deg", th};
          c.scene.misalignment.theta_deg = th;
          cases.push_back(c);
        }
      for (const double v : scene.sweep_velocity)
        {
          Case c{scene, output_dir + "/v_" + label(v) + "mps", v};
          c.scene.impact.velocity = v;
          cases.push_back(c);
        }
      const bool by_theta = !scene.sweep_theta_deg.empty();
      const bool by_velocity = !scene.sweep_velocity.empty();
      if (cases.empty())
        {
          double f;
          complete = run_case(scene, output_dir, argc, argv, !no_plots, preset, f);
        }
      else
        {
          std::unique_ptr<Manifest> top;
          std::unique_ptr<CsvWriter> table;
          if (root)
            {
              std::filesystem::create_directories(output_dir);
              top = std::make_unique<Manifest>("fe_stage", output_dir + "/manifest.json", argc, argv);
              top->add_input(scene_path);
              if (by_velocity)
                table = std::make_unique<CsvWriter>(
                  output_dir + "/impact_sweep.csv", fe::impact_sweep_columns(),
                  fe::impact_sweep_units(),
                  std::vector<std::string>{
                    "fe_stage impact sweep (paper 3.2); one folder per velocity",
                    "dynamic_gap = peak force / quasi-static force at the same delta - 1; "
                    "restitution = journal speed away / speed in (0 if it had not left the "
                    "bearing: separated = 0)",
                    "bearing_energy_left = kinetic + strain energy of the bearing's vibration "
                    "when the journal left"});
              else
                table = std::make_unique<CsvWriter>(
                  output_dir + "/sweep.csv",
                  std::vector<std::string>{by_theta ? "theta" : "t_B", "force_at_delta_max"},
                  std::vector<std::string>{by_theta ? "deg" : "m", "N"},
                  std::vector<std::string>{std::string("fe_stage ") +
                                           (by_theta ? "misalignment" : "thickness") +
                                           " sweep; one folder per case"});
            }
          for (std::size_t k = 0; k < cases.size(); ++k)
            {
              auto &c = cases[k];
              if (root)
                log::info("fe_stage: case " + std::to_string(k + 1) + " of " +
                          std::to_string(cases.size()) + ": " + shown(c.folder));
              c.scene.sweep_t_B.clear();
              c.scene.sweep_theta_deg.clear();
              c.scene.sweep_velocity.clear();
              double f = 0.0;
              fe::ImpactSummary impact;
              const bool ok =
                run_case(c.scene, c.folder, argc, argv, !no_plots, preset, f, &impact);
              complete = complete && ok;
              if (root)
                {
                  if (by_velocity)
                    table->write_row(fe::impact_sweep_row(impact));
                  else
                    table->write_row({c.value, f});
                  top->add_output(c.folder + "/manifest.json");
                }
              if (!ok)
                break;
            }
          if (root)
            {
              if (complete)
                table->commit();
              else
                table->commit_incomplete("a case failed; see its manifest");
              const std::string table_path =
                output_dir + (by_velocity ? "/impact_sweep.csv" : "/sweep.csv");
              top->add_output(table_path);
              if (by_velocity)
                {
                  if (!no_plots && run_plot_script("fe_impact", {output_dir + "/impact_sweep.png",
                                                                 "--sweep", table_path}))
                    top->add_output(output_dir + "/impact_sweep.png");
                }
              else
                {
                  // every case's curve in one figure, labelled by its value
                  std::vector<std::string> plot_args = {output_dir + "/sweep.png"};
                  for (const auto &c : cases)
                    if (std::filesystem::exists(c.folder + "/force_penetration.csv"))
                      plot_args.push_back(c.folder + "=" +
                                          (by_theta ? "theta " + label(c.value) + " deg" :
                                                      "t_B " + label(units::to_mm(c.value)) +
                                                        " mm"));
                  if (!no_plots && run_plot_script("fe", plot_args))
                    top->add_output(output_dir + "/sweep.png");
                }
              top->write(complete ? "complete" : "incomplete");
            }
        }
      publish(output_dir, final_dir);
      return complete ? exit_success : exit_numerical_error;
    }
  catch (const interrupt::Interrupted &e)
    {
      if (root)
        {
          std::error_code ec;
          std::filesystem::remove_all(output_dir, ec);
          log::error(std::string(e.what()) + "; " + output_dir + " removed" +
                     (final_dir.empty() ? "" : ", " + final_dir + " left as it was"));
        }
      const int code = 128 + (signal_seen != 0 ? signal_seen : interrupt::signal_received());
      if (signal_seen == 0)  // seen by rank 0 alone (while plotting): the others may wait
        abort_other_ranks(code);
      return code;
    }
  catch (const InputError &e)
    {
      if (root)
        log::error(e.what());
      if (root && !final_dir.empty())  // e.g. a mesh rejected while setting up a case
        {
          std::error_code ec;
          std::filesystem::remove_all(output_dir, ec);
        }
      return exit_input_error;
    }
  catch (const NumericalError &e)
    {
      log::error(e.what());
      abort_other_ranks(exit_numerical_error);
      return exit_numerical_error;
    }
  catch (const std::exception &e)
    {
      log::error(std::string("fe_stage: ") + e.what());
      abort_other_ranks(exit_numerical_error);
      return exit_numerical_error;
    }
}
