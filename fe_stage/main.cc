// fe_stage: the FE contact model of a revolute joint with clearance (SPEC §2).
//
//   fe_stage SCENE.yaml --output DIR [--preset fast|standard|accurate] [--full-model]
//            [--no-fields] [--no-plots]
//   fe_stage --print-defaults
//
// Writes DIR/force_penetration.csv (delta, force, solver statistics per increment),
// DIR/fields/ (VTU/PVTU + PVD), DIR/force_penetration.png and DIR/manifest.json; with a `sweep`
// block, one such folder per swept value under DIR plus DIR/manifest.json, DIR/sweep.csv and
// DIR/sweep.png (every case's curve).
// Exit codes: 0 success, 1 input error, 2 numerical failure (CSV and manifest marked incomplete).
#include "common/csv.h"
#include "common/error.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/strict_reader.h"
#include "common/units.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/presets.h"
#include "fe_stage/scene.h"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

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

  /// How the scene was made: the preset of pipeline.yaml applied to it, if any.
  struct PresetUse
  {
    std::string name, file;
    fe::PresetOverrides overrides;
  };

  /// One case: CSV + fields + manifest in `dir`. Returns true if complete.
  bool run_case(const fe::FeScene &scene, const std::string &dir, int argc, char **argv,
                const bool plots, const PresetUse &preset, double &force_at_max)
  {
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
          "delta = push of the rigid obstacle beyond first touch"};
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
                                   "pressure_max", "wall_time"},
          std::vector<std::string>{"m", "N", "N", "N", "1", "1", "1", "1", "m", "Pa", "Pa", "s"},
          comments);
        csv->write_row({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
      }
    fe::RunOptions options;
    options.output_dir = dir;
    options.write_fields = scene.output.fields;
    options.on_increment = [&](const fe::IncrementRecord &r) {
      if (csv)
        csv->write_row({r.delta, r.force, r.force_support, r.force_load, double(r.contact_iterations),
                        double(r.linear_iterations), double(r.n_active), double(r.n_slip),
                        r.max_penetration,
                        r.pressure_min, r.pressure_max, r.wall_time});
    };
    const fe::RunResult result = fe::run_scene(scene, options);
    force_at_max = result.increments.empty() ? 0.0 : result.increments.back().force;
    if (root)
      {
        if (result.complete)
          csv->commit();
        else
          csv->commit_incomplete(result.message);
        manifest->add_output(csv_path);
        for (const auto &f : result.field_files)
          manifest->add_output(f);
        // F–δ, linear and log–log (a warning, not a failure, if Python/matplotlib is missing)
        if (plots && !result.increments.empty() &&
            run_plot_script("fe", {dir + "/force_penetration.png", dir}))
          manifest->add_output(dir + "/force_penetration.png");
        auto &x = manifest->extra();
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
        log::info("fe_stage: " + dir + ": F(" + format_value(result.increments.empty() ?
                                                               0.0 :
                                                               result.increments.back().delta) +
                  " m) = " + format_value(force_at_max) + " N, " +
                  log::format_duration(result.wall_time));
        if (!result.field_files.empty())
          log::info("fe_stage: fields: open " + dir +
                    "/fields/solution.pvd in ParaView (displacement, stress, von_mises_stress, "
                    "plastic_zone, contact_pressure, contact_status, contact_shear, "
                    "contact_slip; one step per increment)");
      }
    return result.complete;
  }
} // namespace

int main(int argc, char **argv)
{
  const auto runtime = fe::make_runtime(argc, argv);
  const bool root = rank_of(MPI_COMM_WORLD) == 0;
  if (!root)
    log::set_level(log::Level::error);

  CLI::App app{"fe_stage: FE contact model of a revolute joint with clearance (clearjoint).\n"
               "Exit codes: 0 success, 1 input error, 2 numerical failure."};
  std::string scene_path, output_dir;
  bool print_defaults = false, full_model = false, no_fields = false, no_plots = false,
       quiet = false;
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
      if (output_dir.empty())
        throw InputError("", "--output", "(none)", "a directory", "usage: fe_stage SCENE.yaml --output DIR");
      // all input errors before any output: the scene, with the preset's keys set as
      // run_pipeline sets them
      nlohmann::json scene_doc = read_structured_file(scene_path);
      if (!preset.name.empty())
        {
          if (preset.file.empty())
            preset.file = fe::default_presets_file();
          preset.overrides = fe::read_fe_preset(preset.file, preset.name);
          fe::apply_preset(scene_doc, preset.overrides, preset.file);
          std::string keys;
          for (const auto &[k, v] : preset.overrides)
            keys += (keys.empty() ? "" : ", ") + k + " = " + v.dump();
          if (root)
            log::info("fe_stage: preset " + preset.name + " (" + preset.file + "): " +
                      (keys.empty() ? "no FE keys" : keys));
        }
      else if (!preset.file.empty())
        throw InputError("", "--presets-file", preset.file, "only together with --preset");
      fe::FeScene scene = fe::scene_from_json(scene_doc, scene_path);
      if (full_model)
        scene.full_model = true;
      if (no_fields)
        scene.output.fields = false;
      fe::validate_scene(scene);

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
      const bool by_theta = !scene.sweep_theta_deg.empty();
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
              table = std::make_unique<CsvWriter>(
                output_dir + "/sweep.csv",
                std::vector<std::string>{by_theta ? "theta" : "t_B", "force_at_delta_max"},
                std::vector<std::string>{by_theta ? "deg" : "m", "N"},
                std::vector<std::string>{std::string("fe_stage ") +
                                         (by_theta ? "misalignment" : "thickness") +
                                         " sweep; one folder per case"});
            }
          for (auto &c : cases)
            {
              c.scene.sweep_t_B.clear();
              c.scene.sweep_theta_deg.clear();
              double f = 0.0;
              const bool ok = run_case(c.scene, c.folder, argc, argv, !no_plots, preset, f);
              complete = complete && ok;
              if (root)
                {
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
              top->add_output(output_dir + "/sweep.csv");
              // every case's curve in one figure, labelled by its value
              std::vector<std::string> plot_args = {output_dir + "/sweep.png"};
              for (const auto &c : cases)
                if (std::filesystem::exists(c.folder + "/force_penetration.csv"))
                  plot_args.push_back(c.folder + "=" +
                                      (by_theta ? "theta " + label(c.value) + " deg" :
                                                  "t_B " + label(units::to_mm(c.value)) + " mm"));
              if (!no_plots && run_plot_script("fe", plot_args))
                top->add_output(output_dir + "/sweep.png");
              top->write(complete ? "complete" : "incomplete");
            }
        }
      return complete ? exit_success : exit_numerical_error;
    }
  catch (const InputError &e)
    {
      if (root)
        log::error(e.what());
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
