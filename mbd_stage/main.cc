// mbd_stage: runs a multibody scene (schema clearjoint.mbd/1) with ideal and clearance joints.
//   mbd_stage SCENE.yaml --output DIR [--no-plots] [-q|-v]
//   mbd_stage SCENE.yaml --check      (read and validate the scene and its law files only)
// Writes DIR/timeseries.csv, DIR/summary.json, DIR/plots/, DIR/manifest.json. Everything is
// validated before any output exists; outputs are written into a temporary directory that is
// renamed to DIR at the end, and manifest.json (written last) records the status.
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/stage_main.h"
#include "mbd_stage/output.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char **argv)
{
  using namespace clearjoint;
  CLI::App app{"mbd_stage — multibody simulation with revolute clearance joints (clearjoint)"};
  std::string scene_path, output_dir;
  bool no_plots = false, quiet = false, verbose = false, check = false;
  app.add_option("scene", scene_path, "scene file (YAML or JSON, schema clearjoint.mbd/1)")
    ->required();
  app.add_option("--output,-o", output_dir,
                 "output directory (created; an existing one is replaced only if it is empty or "
                 "a previous mbd_stage output); required unless --check");
  app.add_flag("--check", check,
               "read and validate the scene (and its law files) and exit: 0 valid, 1 input "
               "error; writes nothing");
  app.add_flag("--no-plots", no_plots, "do not call scripts/plot.py on the outputs");
  app.add_flag("-q,--quiet", quiet, "warnings and errors only");
  app.add_flag("-v,--verbose", verbose, "debug messages");
  app.footer("Outputs: DIR/timeseries.csv (with a '# units:' line), DIR/summary.json, DIR/plots/, "
             "DIR/manifest.json.\nThe plotting script is found at <source>/scripts/plot.py or at "
             "$CLEARJOINT_PLOT_SCRIPT, run by /usr/bin/python3 or $CLEARJOINT_PYTHON.\n\nExit codes:\n  0  success\n  1  input error (bad "
             "scene, law file or command line; nothing is written)\n  2  numerical failure "
             "(integrator error, non-finite state, law range under 'error'); the partial "
             "outputs are kept and marked failed; also when the scene's budget (budget.wall_time, "
             "budget.steps) is exceeded; budget.output_rows is checked before the run)\n"
             "  3  an output could not be written (a full disk, an I/O error; nothing new is "
             "left)\n"
             "  130/143  interrupted by SIGINT/SIGTERM (DIR.tmp.PID "
             "removed, an earlier DIR left as it was)");
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError &e)
  {
    const int code = app.exit(e);
    return code == 0 ? exit_success : exit_input_error;
  }
  if (quiet)
    log::set_level(log::Level::warning);
  if (verbose)
    log::set_level(log::Level::debug);

  interrupt::install();  // SIGINT/SIGTERM: stop between steps, remove DIR.tmp.<pid>, exit 130/143

  interrupt::arm_hard_stop("mbd_stage", 1.0);  // a signal inside a long step: stopped within 1 s
  return run_stage_main("mbd_stage", [&]() -> int {
    mbd::Scene scene = mbd::read_scene(scene_path);  // validates everything first
    if (check)
    {
      log::info("mbd_stage: " + scene_path + " is a valid " + mbd::scene_schema + " scene");
      return exit_success;
    }
    if (output_dir.empty())
      throw InputError("", "--output", "(none)", "a directory",
                       "usage: mbd_stage SCENE.yaml --output DIR (or --check)");
    mbd::OutputWriter writer(output_dir, argc, argv);
    const mbd::SimulationResult result = mbd::simulate(scene);
    return writer.write(scene, result, !no_plots);
  });
}
