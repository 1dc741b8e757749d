// impact_compare: the FE impact sweep (fe_stage study impact, impact_sweep.csv) against the MBD
// contact law, one single impact per case and damping model (mbd_stage/single_impact.h), and the
// c_e that makes each damping model return the FE's restitution (issue 12 item 4, issue 31
// item 4).
//
//   impact_compare --fe-sweep DIR/impact_sweep.csv --output OUT [--law LAW.json]
//                  [--fe-sweep-level OTHER/impact_sweep.csv ...] [--restitution 0.9]
//                  [--no-plots] [--check]
//
// The law, like for like: each FE case's folder holds the quasi-static curve of the same
// journal on the same mesh (force_penetration.csv); it is fitted here, F = K δ^n, with
// fit_stage's fitter (absolute weighting, the whole curve: it reaches 1.5× the impact's expected
// δ_max), and that case's single impacts use it. The case folders are the ones the sweep's
// manifest lists. A sweep without case folders (a table alone) needs --law, which is then used
// for every case; with case folders, --law is set beside (its undamped peak force per case).
//
// Error bars: each --fe-sweep-level is the same sweep (the same v and journal masses) run at
// another Δt or mesh level. A case's error bar on the FE restitution and on each model's fitted
// c_e is the largest difference between a level's value and the main sweep's — the spread over
// the Δt and mesh levels given, not a statistical interval; none without levels.
//
// Writes OUT/impact_comparison.csv (per case: FE and each model's peak force, δ_max, contact
// duration, restitution, the models' peak-force error against FE, the law used),
// OUT/restitution_fit.csv (per case: the FE restitution and each model's fitted c_e, with error
// bars), OUT/impact_compare.png and OUT/manifest.json (the laws, the fitted c_e per model, its
// spread over the cases and its error bar). Everything goes to OUT.tmp.<pid> first and
// replaces OUT when complete.
// Exit codes: 0 success, 1 input error, 2 numerical failure, 3 write error (a full disk),
// 130/143 interrupted.
#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/stage_main.h"
#include "fit_stage/power_law_fitter.h"
#include "laws/law_file.h"
#include "mbd_stage/single_impact.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include <unistd.h>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  const std::vector<laws::DampingModel> models = {
    laws::DampingModel::none, laws::DampingModel::lankarani_nikravesh,
    laws::DampingModel::hunt_crossley, laws::DampingModel::flores, laws::DampingModel::gonthier};

  /// The law a case's single impacts use: its own quasi-static curve fitted, or a given file.
  struct CaseLaw
  {
    laws::PowerLaw law;
    double delta_max = 0.0;  // [m] top of the range it was fitted on
    double r_squared = 0.0;  // [1] (own curve; the file's own for a given law)
    bool own = false;        // fitted on the case's own quasi-static curve
    std::string source;      // the curve or the law file
  };

  /// One row of impact_sweep.csv, with its case folder ("" for a table alone) and law.
  struct FeCase
  {
    double v = 0.0, mass = 0.0, peak = 0.0, delta_max = 0.0, duration = 0.0, restitution = 0.0;
    std::string folder;
    CaseLaw law;
  };

  /// An impact sweep: its rows and what sets its level (Δt and mesh).
  struct FeSweep
  {
    std::string path;
    std::vector<FeCase> cases;
    double steps_per_period = 0.0;  // [1] T_c / Δt of its first case
    double n_dofs = 0.0;            // [1] its first case's (0: unknown, a table alone)
  };

  /// The command line.
  struct Options
  {
    std::string law_path, sweep_path, output;
    std::vector<std::string> level_paths;
    double ce = 0.9;
    bool no_plots = false, check = false;
  };

  /// Per case: the comparison row and, per damping model, the fitted c_e (-1: unreachable).
  struct CaseResult
  {
    std::vector<double> row;
    std::map<laws::DampingModel, double> c_e;
  };

  // --- reading -----------------------------------------------------------------------------

  /// The sweep's case folders in row order, from the manifest beside the table (the cases'
  /// manifests, listed as outputs); empty if there is none (a table written by hand).
  std::vector<std::string> case_folders(const std::string &sweep_path)
  {
    const fs::path dir = fs::path(sweep_path).parent_path();
    const fs::path manifest = dir / "manifest.json";
    if (!fs::is_regular_file(manifest))
      return {};
    const nlohmann::json j = read_json_file(manifest.string());
    std::vector<std::string> folders;
    if (!j.contains("outputs") || !j["outputs"].is_array())
      return {};
    for (const auto &o : j["outputs"])
      {
        if (!o.contains("path") || !o["path"].is_string())
          continue;
        const fs::path p = o["path"].get<std::string>();
        // a case's manifest: <case folder>/manifest.json; the folder beside the table (the
        // sweep's folder may have been moved since: only the case folder's name is used)
        if (p.filename() == "manifest.json" && p.has_parent_path())
          folders.push_back((dir / p.parent_path().filename()).string());
      }
    return folders;
  }

  /// The case's own quasi-static curve (force_penetration.csv) fitted with fit_stage's fitter.
  CaseLaw fit_own_law(const std::string &folder)
  {
    const std::string path = folder + "/force_penetration.csv";
    const CsvTable t = read_csv(path);
    if (t.status.rfind("complete", 0) != 0)
      throw InputError(path, "status", t.status.empty() ? "(none)" : t.status, "complete",
                       "the case's quasi-static reference curve is incomplete");
    fit::FitOptions options;
    options.source = path;
    const fit::FitResult fit = fit::fit_power_law(t.column("delta"), t.column("force"), options);
    return {fit.law, fit.diagnostics.fit_delta_max, fit.diagnostics.r_squared, true, path};
  }

  /// The case's manifest says which v and journal mass it ran: they must be the row's.
  void check_case_matches(const std::string &folder, const FeCase &c, const std::string &sweep)
  {
    const nlohmann::json j = read_json_file(folder + "/manifest.json");
    const auto value = [&](const char *key) {
      const auto &q = j.at("extra").at("impact").at(key);
      return q.is_object() ? q.at("value").get<double>() : q.get<double>();
    };
    const double v = value("velocity_in"), m = value("journal_mass");
    if (std::abs(v - c.v) > 1e-9 * c.v || std::abs(m - c.mass) > 1e-9 * c.mass)
      throw InputError(sweep, "case folder", folder,
                       "the case of the row with v = " + format_value(c.v) + " m/s, m = " +
                         format_value(c.mass) + " kg",
                       "its manifest says v = " + format_value(v) + " m/s, m = " +
                         format_value(m) + " kg");
  }

  /// The table's rows; each case's own law where its folder exists, else the given law.
  FeSweep read_sweep(const std::string &path, const std::optional<laws::LawFile> &given,
                     const std::string &given_path)
  {
    const CsvTable t = read_csv(path);
    if (t.status.rfind("complete", 0) != 0 && !t.status.empty())
      throw InputError(path, "status", t.status, "complete", "the FE impact sweep is incomplete");
    FeSweep sweep;
    sweep.path = path;
    const auto v = t.column("v_in_m_per_s"), m = t.column("journal_mass_kg"),
               p = t.column("peak_force_N"), d = t.column("delta_max_m"),
               c = t.column("contact_duration_s"), e = t.column("restitution");
    if (t.has_column("time_step_s") && t.has_column("contact_period_s") && !v.empty() &&
        t.column("time_step_s")[0] > 0.0)
      sweep.steps_per_period = t.column("contact_period_s")[0] / t.column("time_step_s")[0];
    const std::vector<std::string> folders = case_folders(path);
    if (!folders.empty() && folders.size() != v.size())
      throw InputError(path, "rows", std::to_string(v.size()),
                       std::to_string(folders.size()) + " (the cases its manifest lists)");
    for (std::size_t i = 0; i < v.size(); ++i)
      {
        if (!(v[i] > 0.0 && m[i] > 0.0))
          throw InputError(path, "row " + std::to_string(i + 1), format_value(v[i]),
                           "v_in_m_per_s > 0 and journal_mass_kg > 0");
        FeCase fc{v[i], m[i], p[i], d[i], c[i], e[i], "", {}};
        if (!folders.empty())
          {
            fc.folder = folders[i];
            check_case_matches(fc.folder, fc, path);
            fc.law = fit_own_law(fc.folder);
          }
        else if (given)
          fc.law = {given->law, given->delta_max,
                    given->diagnostics ? given->diagnostics->r_squared : 0.0, false,
                    given_path};
        else
          throw InputError(path, "manifest.json", "(none beside it)",
                           "the sweep's case folders (each with its quasi-static curve), or "
                           "--law",
                           "without the cases' own curves the law must be given");
        sweep.cases.push_back(fc);
      }
    if (sweep.cases.empty())
      throw InputError(path, "rows", "(none)", "at least one impact");
    if (!folders.empty())
      {
        const nlohmann::json j = read_json_file(folders.front() + "/manifest.json");
        if (j.contains("extra") && j["extra"].contains("n_dofs"))
          sweep.n_dofs = j["extra"]["n_dofs"].get<double>();
      }
    return sweep;
  }

  /// The level's case with the same v and journal mass (InputError if it has none).
  const FeCase &matching_case(const FeSweep &level, const FeCase &c)
  {
    for (const auto &o : level.cases)
      if (std::abs(o.v - c.v) <= 1e-9 * c.v && std::abs(o.mass - c.mass) <= 1e-9 * c.mass)
        return o;
    throw InputError(level.path, "v_in_m_per_s, journal_mass_kg",
                     format_value(c.v) + " m/s, " + format_value(c.mass) + " kg",
                     "the cases of --fe-sweep (a level is the same sweep at another dt or mesh)");
  }

  // --- computing ---------------------------------------------------------------------------

  /// The c_e with which `model`'s single impact on the case's law returns the FE restitution;
  /// -1 where the model cannot reach it (warned).
  double fitted_coefficient(const FeCase &c, const laws::DampingModel model)
  {
    if (!(c.restitution > 0.0 && c.restitution <= 1.0))
      return -1.0;
    try
      {
        return mbd::fit_restitution_coefficient({c.mass, c.v, c.law.law, model, 1.0},
                                                c.restitution);
      }
    catch (const InputError &e)
      {
        log::warning("impact_compare: v = " + format_value(c.v) + " m/s, m = " +
                     format_value(c.mass) + " kg: " + e.what());
        return -1.0;
      }
  }

  /// The case's row of impact_comparison.csv and its fitted c_e; worst_overshoot: the largest
  /// δ_max of a single impact over the top of its law's range so far.
  CaseResult compare_case(const FeCase &c, const double ce,
                          const std::optional<laws::LawFile> &given, double &worst_overshoot)
  {
    CaseResult r;
    r.row = {c.v, c.mass, c.peak, c.delta_max, c.duration, c.restitution,
             c.law.law.K, c.law.law.n, c.law.own ? 1.0 : 0.0};
    for (const auto m : models)
      {
        const mbd::SingleImpact s{c.mass, c.v, c.law.law, m,
                                  m == laws::DampingModel::none ? 1.0 : ce};
        const auto res = mbd::simulate_single_impact(s);
        worst_overshoot = std::max(worst_overshoot, res.delta_max / c.law.delta_max);
        r.row.insert(r.row.end(), {res.peak_force, res.delta_max, res.contact_duration,
                                   res.restitution, res.peak_force / c.peak - 1.0});
        if (m != laws::DampingModel::none)
          r.c_e[m] = fitted_coefficient(c, m);
      }
    if (given && c.law.own)
      {
        // the given law (another study's, e.g. the thickness sweep's) for the same impact
        const auto res =
          mbd::simulate_single_impact({c.mass, c.v, given->law, laws::DampingModel::none, 1.0});
        r.row.insert(r.row.end(), {res.peak_force, res.peak_force / c.peak - 1.0});
      }
    return r;
  }

  /// The largest |x_level − x_main| over the levels (0 without levels; -1 where a level's
  /// value does not exist, e.g. a c_e a model cannot reach).
  double error_bar(const double main_value, const std::vector<double> &level_values)
  {
    double bar = 0.0;
    for (const double x : level_values)
      {
        if (x < 0.0 || main_value < 0.0)
          return -1.0;
        bar = std::max(bar, std::abs(x - main_value));
      }
    return bar;
  }

  // --- writing -----------------------------------------------------------------------------

  std::vector<std::string> comparison_comments(const FeSweep &sweep, const double ce,
                                               const std::optional<laws::LawFile> &given,
                                               const std::string &given_path)
  {
    const bool own = sweep.cases.front().law.own;
    std::vector<std::string> c = {
      "impact_compare: FE impact (fe_stage study impact) against a single impact of the "
      "journal's mass on an MBD law F = K delta^n (bearing rigid and massless)",
      own ? "law: each case's own quasi-static curve (force_penetration.csv of its folder: the "
            "same journal and mesh as the impact) fitted with fit_stage's fitter, absolute "
            "weighting; law_own = 1" :
            "law: " + given_path + " for every case (no case folders beside the sweep); law_own "
                                   "= 0",
      "damping models with c_e = " + format_value(ce) +
        " (none: undamped); impact velocity at the start of the impact as delta_dot^-",
      "*_peak_force_error = MBD peak force / FE peak force - 1"};
    if (given && own)
      c.push_back("given_law_*: the undamped single impact on " + given_path + " (K = " +
                  format_value(given->law.K) + " N/m^n, n = " + format_value(given->law.n) +
                  "), set beside the case's own law");
    return c;
  }

  std::pair<std::vector<std::string>, std::vector<std::string>>
  comparison_columns(const bool with_given)
  {
    std::vector<std::string> cols = {"v_in", "journal_mass", "fe_peak_force", "fe_delta_max",
                                     "fe_contact_duration", "fe_restitution", "law_K", "law_n",
                                     "law_own"},
                             units = {"m/s", "kg", "N", "m", "s", "1", "N/m^n", "1", "1"};
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
    if (with_given)
      {
        cols.insert(cols.end(), {"given_law_peak_force", "given_law_peak_force_error"});
        units.insert(units.end(), {"N", "1"});
      }
    return {cols, units};
  }

  std::pair<std::vector<std::string>, std::vector<std::string>> fit_columns()
  {
    std::vector<std::string> cols = {"v_in", "journal_mass", "fe_restitution",
                                     "fe_restitution_error_bar"},
                             units = {"m/s", "kg", "1", "1"};
    for (std::size_t k = 1; k < models.size(); ++k)
      for (const char *suffix : {"", "_error_bar"})
        {
          cols.push_back("c_e_" + laws::to_string(models[k]) + suffix);
          units.push_back("1");
        }
    return {cols, units};
  }

  /// What the error bars are made of, for the manifest and the tables.
  nlohmann::json levels_json(const FeSweep &main, const std::vector<FeSweep> &levels)
  {
    const auto level = [](const FeSweep &s) {
      return nlohmann::json{{"sweep", s.path},
                            {"steps_per_period", s.steps_per_period},
                            {"n_dofs", s.n_dofs}};
    };
    nlohmann::json j = {{"main", level(main)}, {"levels", nlohmann::json::array()}};
    for (const auto &l : levels)
      j["levels"].push_back(level(l));
    j["error_bar"] = levels.empty() ?
                       "none: only one dt and mesh level was given (--fe-sweep-level)" :
                       "per case, the largest |value at a level - value of the main sweep| over "
                       "the levels listed: the spread over dt and mesh levels, not a "
                       "statistical interval";
    return j;
  }

  /// Per damping model: the fitted c_e's mean, range over the cases and largest error bar.
  nlohmann::json fitted_summary(const std::map<laws::DampingModel, std::vector<double>> &fitted,
                                const std::map<laws::DampingModel, std::vector<double>> &bars)
  {
    nlohmann::json per_model = nlohmann::json::object();
    for (const auto &[model, cs] : fitted)
      {
        std::vector<double> ok;
        for (const double c : cs)
          if (c > 0.0)
            ok.push_back(c);
        if (ok.empty())
          continue;
        const auto [lo, hi] = std::minmax_element(ok.begin(), ok.end());
        double mean = 0.0, bar = 0.0;
        bool bar_known = true;
        for (const double c : ok)
          mean += c / ok.size();
        for (const double b : bars.at(model))
          {
            bar_known = bar_known && b >= 0.0;
            bar = std::max(bar, b);
          }
        const std::string name = laws::to_string(model);
        per_model[name] = {{"c_e_mean", mean},
                           {"c_e_min", *lo},
                           {"c_e_max", *hi},
                           {"spread_over_v", *hi - *lo},
                           {"spread_over_cases", *hi - *lo},
                           {"depends_on_v", *hi - *lo > 1e-3},
                           {"error_bar", bar_known ? nlohmann::json(bar) : nlohmann::json()},
                           {"n_velocities", ok.size()},
                           {"n_cases", ok.size()}};
        log::info("impact_compare: " + name + ": c_e = " + format_value(mean) +
                  " reproduces the FE restitution (spread over the cases " +
                  format_value(*hi - *lo) + ", error bar from dt and mesh " +
                  (bar_known ? format_value(bar) : std::string("unknown")) + ")");
      }
    return per_model;
  }

  // --- the steps of a run ------------------------------------------------------------------

  /// The options read; an exit code when the command line ends the run here (--help, an
  /// error).
  std::optional<int> parse_command_line(CLI::App &app, Options &o, int argc, char **argv)
  {
    app.add_option("--law", o.law_path,
                   "law file (clearjoint.law/1): used for every case when the sweep has no case "
                   "folders; otherwise set beside each case's own law");
    app.add_option("--fe-sweep", o.sweep_path,
                   "fe_stage's impact_sweep.csv (v_in_m_per_s, journal_mass_kg, peak_force_N, "
                   "delta_max_m, contact_duration_s, restitution), its case folders beside it")
      ->required();
    app.add_option("--fe-sweep-level", o.level_paths,
                   "the same sweep at another dt or mesh level (repeatable): the error bars");
    app.add_option("--output,-o", o.output, "output directory");
    app.add_option("--restitution", o.ce,
                   "[1] the damping models' c_e in the comparison (0, 1], default 0.9");
    app.add_flag("--no-plots", o.no_plots, "do not draw impact_compare.png");
    app.add_flag("--check", o.check, "read and validate the inputs and exit; writes nothing");
    try
      {
        app.parse(argc, argv);
      }
    catch (const CLI::ParseError &e)
      {
        return app.exit(e) == 0 ? exit_success : exit_input_error;
      }
    return std::nullopt;
  }

  /// Every case compared; the two tables written into `work`; the manifest's figures.
  void write_comparison(const Options &o, const FeSweep &sweep, const std::vector<FeSweep> &levels,
                        const std::optional<laws::LawFile> &given, const std::string &work,
                        Manifest &manifest)
  {
    const bool with_given = given && sweep.cases.front().law.own;
    const auto [cols, units] = comparison_columns(with_given);
    CsvWriter table(work + "/impact_comparison.csv", cols, units,
                    comparison_comments(sweep, o.ce, given, o.law_path));
    const auto [fcols, funits] = fit_columns();
    CsvWriter fits(work + "/restitution_fit.csv", fcols, funits,
                   {"impact_compare: per damping model the c_e whose single impact on the case's "
                    "law returns the FE restitution; -1 where the model cannot reach it (its "
                    "damping factor is bounded)",
                    "*_error_bar: " + levels_json(sweep, levels)["error_bar"].get<std::string>() +
                      "; -1 where a level's value does not exist"});
    std::map<laws::DampingModel, std::vector<double>> fitted, bars;
    double worst_overshoot = 0.0, ignored = 0.0;
    nlohmann::json case_laws = nlohmann::json::array();
    for (const auto &c : sweep.cases)
      {
        const CaseResult r = compare_case(c, o.ce, given, worst_overshoot);
        table.write_row(r.row);
        // the same case at the other dt and mesh levels, each on its own law
        std::vector<double> e_levels;
        std::vector<CaseResult> at_levels;
        for (const auto &l : levels)
          {
            const FeCase &lc = matching_case(l, c);
            e_levels.push_back(lc.restitution);
            at_levels.push_back(compare_case(lc, o.ce, std::nullopt, ignored));
          }
        std::vector<double> fit_row = {c.v, c.mass, c.restitution,
                                       error_bar(c.restitution, e_levels)};
        for (const auto &[model, ce] : r.c_e)
          {
            std::vector<double> ce_levels;
            for (const auto &lr : at_levels)
              ce_levels.push_back(lr.c_e.at(model));
            const double bar = error_bar(ce, ce_levels);
            fit_row.insert(fit_row.end(), {ce, bar});
            fitted[model].push_back(ce);
            bars[model].push_back(bar);
          }
        fits.write_row(fit_row);
        case_laws.push_back({{"v_in", c.v},
                             {"journal_mass", c.mass},
                             {"K", c.law.law.K},
                             {"n", c.law.law.n},
                             {"delta_max", c.law.delta_max},
                             {"r_squared", c.law.r_squared},
                             {"own", c.law.own},
                             {"source", c.law.source}});
      }
    table.commit();
    fits.commit();
    manifest.add_output(work + "/impact_comparison.csv");
    manifest.add_output(work + "/restitution_fit.csv");
    manifest.extra()["fitted_restitution_coefficient"] = fitted_summary(fitted, bars);
    manifest.extra()["comparison_restitution"] = o.ce;
    manifest.extra()["laws"] = case_laws;
    manifest.extra()["law_source"] = sweep.cases.front().law.own ? "own_quasi_static_curve" :
                                                                   "given_file";
    manifest.extra()["error_bar_from"] = levels_json(sweep, levels);
    if (given)
      manifest.extra()["law"] = {{"K", given->law.K},
                                 {"n", given->law.n},
                                 {"delta_max", given->delta_max},
                                 {"file", o.law_path}};
    if (worst_overshoot > 1.0)
      log::warning("impact_compare: a single impact reaches " + format_value(worst_overshoot) +
                   " times the top of its law's fitted range: the law is extrapolated");
  }

  /// After the command line: the inputs read, the comparison written to OUT.tmp.<pid> and
  /// renamed to OUT.
  int run(const Options &o, int argc, char **argv)
  {
    if (!(o.ce > 0.0 && o.ce <= 1.0))
      throw InputError("", "--restitution", format_value(o.ce), "(0, 1]");
    std::optional<laws::LawFile> given;
    if (!o.law_path.empty())
      given = laws::read_law_file(o.law_path);
    const FeSweep sweep = read_sweep(o.sweep_path, given, o.law_path);
    std::vector<FeSweep> levels;
    for (const auto &p : o.level_paths)
      {
        levels.push_back(read_sweep(p, given, o.law_path));
        for (const auto &c : sweep.cases)
          matching_case(levels.back(), c);  // every case is there (InputError if not)
      }
    if (o.check)
      {
        log::info("impact_compare: the law and the FE sweep are valid");
        return exit_success;
      }
    if (o.output.empty())
      throw InputError("", "--output", "(none)", "a directory");
    check_output_replaceable(o.output, "impact_compare");
    const std::string work = o.output + ".tmp." + std::to_string(::getpid());
    create_work_folder(work, o.output);
    try
      {
        Manifest manifest("impact_compare", work + "/manifest.json", argc, argv);
        if (given)
          manifest.add_input(o.law_path);
        manifest.add_input(o.sweep_path);
        for (const auto &c : sweep.cases)
          if (c.law.own)
            manifest.add_input(c.law.source);
        for (const auto &p : o.level_paths)
          manifest.add_input(p);
        write_comparison(o, sweep, levels, given, work, manifest);
        if (!o.no_plots && run_plot_script("impact_compare", {work + "/impact_compare.png", work}))
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
    fs::remove_all(o.output, ec);
    fs::rename(work, o.output, ec);
    if (ec)
      throw NumericalError("cannot rename " + work + " to " + o.output + ": " + ec.message());
    log::info("impact_compare: " + o.output + ": impact_comparison.csv, restitution_fit.csv");
    return exit_success;
  }
} // namespace

int main(int argc, char **argv)
{
  CLI::App app{"impact_compare: the FE impact sweep against the MBD contact law of the same "
               "journal and mesh (each case's own quasi-static curve, fitted), per damping "
               "model, and the c_e that reproduces the FE restitution (clearjoint).\n"
               "Exit codes: 0 success, 1 input error, 2 numerical failure, 3 an output could not be "
               "written (a full disk), 130/143 interrupted."};
  Options options;
  if (const auto code = parse_command_line(app, options, argc, argv))
    return *code;
  interrupt::install();
  interrupt::arm_hard_stop("impact_compare", 1.0);  // a signal inside a long step: stopped within 1 s
  return run_stage_main("impact_compare", [&]() -> int { return run(options, argc, argv); });
}
