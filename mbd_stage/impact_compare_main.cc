// impact_compare: the FE impact sweep (fe_stage study impact, impact_sweep.csv) against the MBD
// contact law of the same geometry, one single impact per velocity and damping model
// (mbd_stage/single_impact.h), and the c_e that makes each damping model return the FE's
// restitution (issue 12 item 4).
//
//   impact_compare --law LAW.json --fe-sweep impact_sweep.csv --output DIR
//                  [--restitution 0.9] [--no-plots] [--check]
//
// Writes DIR/impact_comparison.csv (per velocity: FE and each model's peak force, δ_max,
// contact duration, restitution, and the models' peak-force error against FE),
// DIR/restitution_fit.csv (per velocity: the fitted c_e of each damping model),
// DIR/impact_compare.png and DIR/manifest.json (the fitted c_e per model, its spread over v).
// Everything goes to DIR.tmp.<pid> first and replaces DIR when complete.
// Exit codes: 0 success, 1 input error, 2 numerical failure, 3 write error (a full disk),
// 130/143 interrupted.
#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/stage_main.h"
#include "laws/law_file.h"
#include "mbd_stage/single_impact.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <unistd.h>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  struct FeRow
  {
    double v, mass, peak, delta_max, duration, restitution;
  };

  std::vector<FeRow> read_sweep(const std::string &path)
  {
    const CsvTable t = read_csv(path);
    if (t.status.rfind("complete", 0) != 0 && !t.status.empty())
      throw InputError(path, "status", t.status, "complete", "the FE impact sweep is incomplete");
    std::vector<FeRow> rows;
    const auto v = t.column("v_in_m_per_s"), m = t.column("journal_mass_kg"),
               p = t.column("peak_force_N"), d = t.column("delta_max_m"),
               c = t.column("contact_duration_s"), e = t.column("restitution");
    for (std::size_t i = 0; i < v.size(); ++i)
      {
        if (!(v[i] > 0.0 && m[i] > 0.0))
          throw InputError(path, "row " + std::to_string(i + 1), format_value(v[i]),
                           "v_in_m_per_s > 0 and journal_mass_kg > 0");
        rows.push_back({v[i], m[i], p[i], d[i], c[i], e[i]});
      }
    if (rows.empty())
      throw InputError(path, "rows", "(none)", "at least one impact");
    return rows;
  }

  const std::vector<laws::DampingModel> models = {
    laws::DampingModel::none, laws::DampingModel::lankarani_nikravesh,
    laws::DampingModel::hunt_crossley, laws::DampingModel::flores, laws::DampingModel::gonthier};
} // namespace

int main(int argc, char **argv)
{
  CLI::App app{"impact_compare: the FE impact sweep against the MBD contact law, per damping "
               "model, and the c_e that reproduces the FE restitution (clearjoint).\n"
               "Exit codes: 0 success, 1 input error, 2 numerical failure, 3 an output could not be "
               "written (a full disk), 130/143 interrupted."};
  std::string law_path, sweep_path, output;
  double ce = 0.9;
  bool no_plots = false, check = false;
  app.add_option("--law", law_path, "law file (clearjoint.law/1) of the same geometry")->required();
  app.add_option("--fe-sweep", sweep_path,
                 "fe_stage's impact_sweep.csv (v_in_m_per_s, journal_mass_kg, peak_force_N, "
                 "delta_max_m, contact_duration_s, restitution)")
    ->required();
  app.add_option("--output,-o", output, "output directory");
  app.add_option("--restitution", ce,
                 "[1] the damping models' c_e in the comparison (0, 1], default 0.9");
  app.add_flag("--no-plots", no_plots, "do not draw impact_compare.png");
  app.add_flag("--check", check, "read and validate the inputs and exit; writes nothing");
  try
    {
      app.parse(argc, argv);
    }
  catch (const CLI::ParseError &e)
    {
      return app.exit(e) == 0 ? exit_success : exit_input_error;
    }
  interrupt::install();
  interrupt::arm_hard_stop("impact_compare", 1.0);  // a signal inside a long step: stopped within 1 s
  return run_stage_main("impact_compare", [&]() -> int {
    if (!(ce > 0.0 && ce <= 1.0))
      throw InputError("", "--restitution", format_value(ce), "(0, 1]");
    const laws::LawFile law = laws::read_law_file(law_path);
    const std::vector<FeRow> fe = read_sweep(sweep_path);
    if (check)
      {
        log::info("impact_compare: the law and the FE sweep are valid");
        return exit_success;
      }
    if (output.empty())
      throw InputError("", "--output", "(none)", "a directory");
    check_output_replaceable(output, "impact_compare");
    const std::string work = output + ".tmp." + std::to_string(::getpid());
    create_work_folder(work, output);
    try
      {
        std::vector<std::string> cols = {"v_in", "journal_mass", "fe_peak_force",
                                         "fe_delta_max", "fe_contact_duration",
                                         "fe_restitution"},
                                 units = {"m/s", "kg", "N", "m", "s", "1"};
        for (const auto m : models)
          {
            const std::string n = laws::to_string(m);
            for (const auto &[c, u] : std::vector<std::pair<std::string, std::string>>{
                   {"_peak_force", "N"}, {"_delta_max", "m"}, {"_contact_duration", "s"},
                   {"_restitution", "1"}, {"_peak_force_error", "1"}})
              {
                cols.push_back(n + c);
                units.push_back(u);
              }
          }
        CsvWriter table(work + "/impact_comparison.csv", cols, units,
                        {"impact_compare: FE impact (fe_stage study impact) against a single "
                         "impact of the journal's mass on the law " + law_path +
                           " (F = K delta^n, K = " + format_value(law.law.K) + " N/m^n, n = " +
                           format_value(law.law.n) + "), bearing rigid and massless",
                         "damping models with c_e = " + format_value(ce) + " (none: undamped); "
                         "impact velocity at the start of the impact as delta_dot^-",
                         "*_peak_force_error = MBD peak force / FE peak force - 1"});
        std::vector<std::string> fit_cols = {"v_in", "fe_restitution"}, fit_units = {"m/s", "1"};
        for (std::size_t k = 1; k < models.size(); ++k)
          {
            fit_cols.push_back("c_e_" + laws::to_string(models[k]));
            fit_units.push_back("1");
          }
        CsvWriter fits(work + "/restitution_fit.csv", fit_cols, fit_units,
                       {"impact_compare: per damping model the c_e whose single impact returns "
                        "the FE restitution; -1 where the model cannot reach it (its damping "
                        "factor is bounded)"});
        std::map<std::string, std::vector<double>> fitted;
        double max_delta = 0.0;
        for (const auto &r : fe)
          {
            std::vector<double> row = {r.v, r.mass, r.peak, r.delta_max, r.duration,
                                       r.restitution};
            std::vector<double> fit_row = {r.v, r.restitution};
            for (const auto m : models)
              {
                mbd::SingleImpact s{r.mass, r.v, law.law, m,
                                    m == laws::DampingModel::none ? 1.0 : ce};
                const auto res = mbd::simulate_single_impact(s);
                max_delta = std::max(max_delta, res.delta_max);
                row.insert(row.end(), {res.peak_force, res.delta_max, res.contact_duration,
                                       res.restitution, res.peak_force / r.peak - 1.0});
                if (m == laws::DampingModel::none)
                  continue;
                double c = -1.0;
                if (r.restitution > 0.0 && r.restitution <= 1.0)
                  try
                    {
                      c = mbd::fit_restitution_coefficient(s, r.restitution);
                      fitted[laws::to_string(m)].push_back(c);
                    }
                  catch (const InputError &e)
                    {
                      log::warning("impact_compare: v = " + format_value(r.v) + " m/s: " +
                                   e.what());
                    }
                fit_row.push_back(c);
              }
            table.write_row(row);
            fits.write_row(fit_row);
          }
        table.commit();
        fits.commit();
        Manifest manifest("impact_compare", work + "/manifest.json", argc, argv);
        manifest.add_input(law_path);
        manifest.add_input(sweep_path);
        manifest.add_output(work + "/impact_comparison.csv");
        manifest.add_output(work + "/restitution_fit.csv");
        nlohmann::json per_model = nlohmann::json::object();
        for (const auto &[name, cs] : fitted)
          {
            const auto [lo, hi] = std::minmax_element(cs.begin(), cs.end());
            double mean = 0.0;
            for (const double c : cs)
              mean += c / cs.size();
            per_model[name] = {{"c_e_mean", mean},
                               {"c_e_min", *lo},
                               {"c_e_max", *hi},
                               {"spread_over_v", *hi - *lo},
                               {"depends_on_v", *hi - *lo > 1e-3},
                               {"n_velocities", cs.size()}};
            log::info("impact_compare: " + name + ": c_e = " + format_value(mean) +
                      " reproduces the FE restitution (spread over v " +
                      format_value(*hi - *lo) + ")");
          }
        manifest.extra()["fitted_restitution_coefficient"] = per_model;
        manifest.extra()["comparison_restitution"] = ce;
        manifest.extra()["law"] = {{"K", law.law.K}, {"n", law.law.n},
                                   {"delta_max", law.delta_max}};
        if (max_delta > law.delta_max)
          log::warning("impact_compare: the single impacts reach delta = " +
                       format_value(max_delta) + " m, beyond the law's fitted range (" +
                       format_value(law.delta_max) + " m): the law is extrapolated");
        if (!no_plots && run_plot_script("impact_compare", {work + "/impact_compare.png", work}))
          manifest.add_output(work + "/impact_compare.png");
        manifest.write("complete");
      }
    catch (...)
      {
        std::error_code ec;
        fs::remove_all(work, ec);
        throw;
      }
    std::error_code ec;
    fs::remove_all(output, ec);
    fs::rename(work, output, ec);
    if (ec)
      throw NumericalError("cannot rename " + work + " to " + output + ": " + ec.message());
    log::info("impact_compare: " + output + ": impact_comparison.csv, restitution_fit.csv");
    return exit_success;
  });
}
