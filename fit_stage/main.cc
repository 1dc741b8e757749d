// fit_stage: fits F = K·δ^n to force–penetration data and writes a clearjoint.law/1 file
// (or a clearjoint.law_family/1 file with --family). See --help.
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/stage_main.h"
#include "fit_stage/fit_command.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char **argv)
{
  using namespace clearjoint;
  CLI::App app{
    "fit_stage — fit F = K*delta^n (SI: delta in m, F in N) to force-penetration data.\n"
    "\n"
    "  fit_stage DATA.csv --output LAW.json [--range A:B] [--weighting absolute|relative]\n"
    "            [--start K,n] [--delta-ref D] [--scene SCENE.yaml] [--no-plots]\n"
    "            [--discretisation-error PERCENT [--discretisation-error-source TEXT]\n"
    "             | --discretisation-error-from FE_MANIFEST.json...]\n"
    "  fit_stage --family PARAM FILE1.csv=VALUE1 FILE2.csv=VALUE2 ... --output FAMILY.json\n"
    "            [--parameter-unit UNIT] [--family-out-of-range error|clamp|extend]\n"
    "\n"
    "DATA.csv has columns 'delta' [m] and 'force' [N] (other columns are ignored; '#' comment\n"
    "lines and a '# units:' line are allowed; the origin row (0, 0) is skipped). Nonlinear least\n"
    "squares (Ceres) from a log-log linear start; diagnostics: R^2, residual std, standard\n"
    "errors and 95% intervals, K-n correlation, condition number, residuals. Writes LAW.json\n"
    "atomically, LAW.manifest.json, and LAW.png (data, fit, residuals).\n"
    "\n"
    "Exit codes: 0 success, 1 input error (bad file, column, value or option), 2 numerical\n"
    "failure (the fit did not converge), 3 an output could not be written (a full disk),\n"
    "130/143 interrupted by SIGINT/SIGTERM."};
  fit::FitCommand command;
  std::string range, start, weighting = "absolute", family;
  double delta_ref = 0;
  app.add_option("inputs", command.inputs, "DATA.csv, or FILE=VALUE pairs with --family")
    ->required();
  app.add_option("-o,--output", command.output, "law file to write (JSON)")->required();
  app.add_option("--range", range, "fit only A <= delta <= B, in metres (A:B)");
  app.add_option("--weighting", weighting, "absolute (N) or relative (%) residuals")
    ->check(CLI::IsMember({"absolute", "relative"}));
  app.add_option("--start", start, "start K,n (K in N/m^n) instead of the log-log fit");
  auto *ref = app.add_option("--delta-ref", delta_ref,
                             "reference penetration for F_ref, m (default: top of fit range)");
  app.add_option("--scene", command.scene_file, "scene parameters to record in the law");
  double discretisation_percent = 0;
  std::string discretisation_source;
  auto *disc = app.add_option(
    "--discretisation-error", discretisation_percent,
    "measured relative error of the FE force on this mesh, % in [0, 100) (run_pipeline passes "
    "the preset's); recorded in the law, widens the MBD band");
  app.add_option("--discretisation-error-source", discretisation_source,
                 "where that error was measured (recorded beside it)");
  std::vector<std::string> estimate_manifests;
  app.add_option("--discretisation-error-from", estimate_manifests,
                 "fe_stage manifest(s) of adaptive runs: the law's discretisation error is their "
                 "own estimate of the error of F(delta_max), the largest of them (run_pipeline "
                 "passes the cases' where the preset has no measured figure)");
  app.add_option("--family", family, "write a law family over parameter PARAM (e.g. theta)");
  app.add_option("--parameter-unit", command.family_unit,
                 "unit of the family parameter (default: rad for theta, m for t_B)");
  app.add_option("--family-out-of-range", command.family_policy,
                 "what the family does for a parameter outside its values")
    ->check(CLI::IsMember({"error", "clamp", "extend"}));
  app.add_flag("--no-plots", [&](std::int64_t) { command.plots = false; }, "skip the plot");
  bool check = false;
  app.add_flag("--check", check,
               "validate the options, the data files that exist and the scene, then exit: 0 "
               "valid, 1 input error; writes nothing (no fit is made)");
  app.add_flag("-q,--quiet", [](std::int64_t) { log::set_level(log::Level::warning); },
               "only warnings and errors");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError &e)
  {
    return app.exit(e) == 0 ? exit_success : exit_input_error;
  }

  interrupt::install();  // SIGINT/SIGTERM: plot.py stopped, exit 130/143

  interrupt::arm_hard_stop("fit_stage", 1.0);  // a signal inside a long step: stopped within 1 s
  return run_stage_main("fit_stage", [&]() -> int {
    command.options.weighting =
      weighting == "relative" ? fit::Weighting::relative : fit::Weighting::absolute;
    if (!range.empty())
      fit::parse_range(range, command.options);
    if (!start.empty())
      command.options.start = fit::parse_start(start);
    if (ref->count() > 0)
    {
      if (!(delta_ref > 0))
        throw InputError("", "--delta-ref", format_value(delta_ref), "(0, inf) m");
      command.delta_ref = delta_ref;
    }
    if (disc->count() > 0)
    {
      if (!(discretisation_percent >= 0.0 && discretisation_percent < 100.0))
        throw InputError("", "--discretisation-error", format_value(discretisation_percent),
                         "[0, 100) %");
      command.discretisation_error = laws::DiscretisationError{
        discretisation_percent / 100.0,
        discretisation_source.empty() ? "given with --discretisation-error" : discretisation_source};
    }
    else if (!discretisation_source.empty())
      throw InputError("", "--discretisation-error-source", discretisation_source,
                       "only together with --discretisation-error");
    if (!estimate_manifests.empty())
    {
      if (disc->count() > 0)
        throw InputError("", "--discretisation-error-from", estimate_manifests.front(),
                         "not together with --discretisation-error (one source of the error)");
      // (--check before the FE cases ran: the manifests that exist are read, the rest skipped)
      command.discretisation_error = fit::own_estimate_error(estimate_manifests, check);
    }
    if (!family.empty())
    {
      command.family_parameter = family;
      if (command.family_unit.empty())
      {
        if (family == "theta")
          command.family_unit = "rad";
        else if (family == "t_B")
          command.family_unit = "m";
        else
          throw InputError("", "--parameter-unit", "(missing)",
                           "a unit for family parameter '" + family + "', e.g. m or rad");
      }
    }
    if (check)
    {
      fit::check_fit_command(command);
      log::info("fit_stage: the command line and its existing input files are valid");
      return exit_success;
    }
    return fit::run_fit_command(command, argc, argv);
  });
}
