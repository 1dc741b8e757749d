#include "fit_stage/fit_command.h"

#include "common/csv.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/sha256.h"
#include "common/strict_reader.h"
#include "common/units.h"
#include "laws/law_family.h"
#include "laws/own_error_estimate.h"

#include <ceres/version.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>

#include <unistd.h>

namespace clearjoint::fit
{
  namespace fs = std::filesystem;

  void parse_range(const std::string &text, FitOptions &options)
  {
    const auto colon = text.find(':');
    char *end = nullptr;
    bool ok = colon != std::string::npos;
    double a = 0, b = 0;
    if (ok)
    {
      const std::string sa = text.substr(0, colon), sb = text.substr(colon + 1);
      a = std::strtod(sa.c_str(), &end);
      ok = !sa.empty() && end == sa.c_str() + sa.size();
      b = std::strtod(sb.c_str(), &end);
      ok = ok && !sb.empty() && end == sb.c_str() + sb.size();
    }
    if (!ok || !(a >= 0) || !(b > a) || !std::isfinite(b))
      throw InputError("", "--range", text, "A:B in metres with 0 <= A < B, e.g. 0:5e-5");
    options.range_min = a;
    options.range_max = b;
  }

  std::optional<laws::DiscretisationError> own_estimate_error(
    const std::vector<std::string> &manifests, const bool skip_missing)
  {
    std::optional<laws::OwnErrorEstimate> largest;
    std::string largest_path;
    std::size_t n_read = 0;
    for (const auto &path : manifests)
    {
      if (skip_missing && !std::filesystem::exists(path))
        continue;
      const auto e = laws::read_own_error_estimate(read_json_file(path));
      if (!e)
        throw InputError(path, "extra.adaptive.estimated_error_F_max", "(missing)",
                         "the manifest of an fe_stage run on adaptive meshes "
                         "(mesh.adaptive_cycles >= 1)",
                         "given with --discretisation-error-from");
      if (!(e->relative >= 0.0 && e->relative < 1.0))
        throw InputError(path, "extra.adaptive.estimated_error_F_max.value",
                         format_value(e->relative), "[0, 1)");
      ++n_read;
      if (!largest || e->relative > largest->relative)
        largest = e, largest_path = path;
    }
    if (!largest)
      return std::nullopt;
    std::string source = "the FE run's own estimate, " + laws::describe_own_estimate(*largest) +
                         " (fe_stage: " + largest->method + "), " + largest_path;
    if (n_read > 1)
      source += ", the largest of " + std::to_string(n_read) + " cases' estimates";
    return laws::DiscretisationError{largest->relative, source};
  }

  std::pair<double, double> parse_start(const std::string &text)
  {
    double K = 0, n = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf%c", &K, &n, &tail) != 2 || !(K > 0) ||
        !std::isfinite(K) || !std::isfinite(n))
      throw InputError("", "--start", text, "K,n with K > 0 N/m^n and n finite, e.g. 3.6e8,1.0");
    return {K, n};
  }

  namespace
  {
    /// The FE stage records its scene under manifest.json "extra": {"scene": ...} beside the
    /// CSV; embed it in the law when present so the law says where it came from.
    nlohmann::json scene_beside(const std::string &csv_path)
    {
      const fs::path manifest = fs::path(csv_path).parent_path() / "manifest.json";
      if (!fs::is_regular_file(manifest))
        return nullptr;
      try
      {
        const auto j = read_json_file(manifest.string());
        if (j.contains("extra") && j["extra"].contains("scene") && j["extra"]["scene"].is_object())
          return j["extra"]["scene"];
      }
      catch (const InputError &)
      {
        log::warning("ignoring unreadable " + manifest.string());
      }
      return nullptr;
    }

    void print_law(const std::string &name, const laws::LawFile &l)
    {
      const auto &d = *l.diagnostics;
      const double K_mm = units::power_law_K_SI_to_mm(l.law.K, l.law.n);
      char buf[1024];
      std::snprintf(buf, sizeof(buf),
                    "%s: F = K*delta^n fitted to %zu points (%s weighting)\n"
                    "  K = %.6g N/m^n  (95%% CI %.6g .. %.6g)   [= %.6g N/mm^n with delta in mm]\n"
                    "  n = %.6g        (95%% CI %.6g .. %.6g)\n"
                    "  F_ref = %.6g N at delta_ref = %.6g m (%.4g mm)\n"
                    "  R^2 = %.8f   residual std = %.4g %s   max |rel. residual| = %.3g %%\n"
                    "  corr(K, n) = %.6f   condition number = %.4g",
                    name.c_str(), d.n_points, d.weighting.c_str(), l.law.K, d.K_ci95_low,
                    d.K_ci95_high, K_mm, l.law.n, d.n_ci95_low, d.n_ci95_high, l.F_ref(),
                    l.delta_ref, units::to_mm(l.delta_ref), d.r_squared, d.residual_std,
                    d.weighting == "relative" ? "(relative)" : "N",
                    100.0 * d.max_relative_residual, d.correlation_K_n, d.condition_number);
      log::info(buf);
      if (l.discretisation_error)
      {
        // Side by side: the fit's own 95 % half-width of F_ref against the mesh's error.
        std::snprintf(buf, sizeof(buf),
                      "  discretisation error of F (mesh, measured): %.3g %% (%s)",
                      100.0 * l.discretisation_error->F_relative,
                      l.discretisation_error->description.c_str());
        log::info(buf);
      }
      if (d.r_squared < 0.999)
        log::warning(name + ": R^2 = " + format_value(d.r_squared) +
                     " < 0.999: the data do not follow a single power law well over this range "
                     "(see the residual plot; consider --range)");
    }

    double parse_member_value(const std::string &text, const std::string &arg)
    {
      char *end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
        throw InputError("", "family member '" + arg + "'", text,
                         "FILE.csv=VALUE with a finite number VALUE in SI units");
      return v;
    }
  } // namespace

  laws::LawFile fit_csv_file(const std::string &csv_path, const FitOptions &base_options,
                             const nlohmann::json &scene, const std::optional<double> delta_ref)
  {
    const CsvTable table = read_csv(csv_path);
    for (const auto &[column, unit] : {std::pair{"delta", "m"}, std::pair{"force", "N"}})
    {
      table.column_index(column);  // throws naming the file and the columns present
      if (!table.units.empty() && table.unit_of(column) != unit)
        throw InputError(csv_path, std::string("column '") + column + "' unit",
                         table.unit_of(column), unit, "the fit stage reads SI data only");
    }
    if (!table.status.empty() && table.status != "complete")
      log::warning(csv_path + " is marked '" + table.status + "': fitting the part that exists");
    FitOptions options = base_options;
    options.source = csv_path;
    const FitResult r = fit_power_law(table.column("delta"), table.column("force"), options);

    laws::LawFile law;
    law.law = r.law;
    const auto &d = r.diagnostics;
    // Valid from the origin when the data contain it (F(0) = 0 is then measured, not assumed).
    law.delta_min = r.n_origin_rows_skipped > 0 && options.range_min == 0.0 ? 0.0
                                                                             : d.fit_delta_min;
    law.delta_max = d.fit_delta_max;
    law.delta_ref = delta_ref.value_or(law.delta_max);
    law.source_kind = "fit";
    law.source_description = "fit_stage: Ceres nonlinear least squares of F = K*delta^n to " +
                             fs::path(csv_path).filename().string() + " (" + d.weighting +
                             " weighting, started from " +
                             (base_options.start ? "--start" : "the log-log linear fit") + ")";
    law.data_file = fs::absolute(csv_path).lexically_normal().string();
    law.data_sha256 = sha256_file(csv_path);
    law.scene = scene.is_null() ? scene_beside(csv_path) : scene;
    law.diagnostics = d;
    return law;
  }

  void check_fit_command(const FitCommand &c)
  {
    if (c.scene_file)
      read_structured_file(*c.scene_file);
    if (!c.family_parameter && c.inputs.size() != 1)
      throw InputError("", "DATA.csv", std::to_string(c.inputs.size()) + " files",
                       "exactly one CSV file (or --family PARAM FILE=VALUE ...)");
    if (c.family_parameter && c.inputs.size() < 2)
      throw InputError("", "--family", std::to_string(c.inputs.size()) + " members",
                       "at least 2 FILE.csv=VALUE arguments");
    for (const auto &arg : c.inputs)
    {
      std::string file = arg;
      if (c.family_parameter)
      {
        const auto eq = arg.rfind('=');
        if (eq == std::string::npos)
          throw InputError("", "family member", arg, "FILE.csv=VALUE");
        file = arg.substr(0, eq);
        const std::string value = arg.substr(eq + 1);
        char *end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !std::isfinite(v))
          throw InputError("", "family member " + file, value, "a finite number");
      }
      if (!fs::exists(file))
        continue;
      const CsvTable t = read_csv(file);
      t.column_index("delta");
      t.column_index("force");
    }
  }

  namespace
  {
    /// The outputs of one fit_stage run (OUT, STEM.png, STEM.manifest.json) are written under
    /// temporary names (STEM.tmp.<pid>.json, STEM.tmp.<pid>.png) and renamed into place only
    /// when the whole output is complete. Whatever was not committed is removed when the run
    /// ends — by an input error, a numerical failure or an interrupt — together with the
    /// folder of --output if this run created it and left it empty. An earlier run's outputs
    /// stay as they were until the new ones replace them.
    class FitOutputs
    {
    public:
      explicit FitOutputs(const std::string &output)
        : output_(output)
      {
        const fs::path out(output);
        dir_ = out.parent_path();
        stem_ = (dir_ / out.stem()).string();
        const std::string tag = ".tmp." + std::to_string(::getpid());
        tmp_law_ = stem_ + tag + ".json";
        tmp_png_ = stem_ + tag + ".png";
        temporary_law_.set(tmp_law_);  // removed by a hard stop too (common/interrupt.h)
        temporary_png_.set(tmp_png_);
      }
      ~FitOutputs()
      {
        std::error_code ec;
        fs::remove(tmp_law_, ec);
        fs::remove(tmp_png_, ec);
        if (created_dir_)  // from the folder of --output up to the top-most one created
          for (fs::path d = dir_; !d.empty(); d = d.parent_path())
          {
            if (!fs::is_empty(d, ec) || ec || !fs::remove(d, ec))
              break;
            if (d == created_top_)
              break;
          }
      }

      /// Creates the folder of --output if needed; InputError naming --output if it cannot be.
      void make_folder()
      {
        if (dir_.empty() || fs::is_directory(dir_))
          return;
        std::error_code ec;
        fs::path missing = dir_;  // the top-most folder this run creates (removed if empty)
        while (!missing.parent_path().empty() && !fs::exists(missing.parent_path(), ec))
          missing = missing.parent_path();
        fs::create_directories(dir_, ec);
        if (ec)
          throw InputError("", "--output", output_, "a file in a folder that can be created",
                           "cannot create " + dir_.string() + ": " + ec.message());
        created_dir_ = true;
        created_top_ = missing;
      }

      const std::string &tmp_law() const { return tmp_law_; }
      const std::string &tmp_png() const { return tmp_png_; }
      std::string png() const { return stem_ + ".png"; }
      std::string manifest() const { return stem_ + ".manifest.json"; }

      /// Moves the temporaries into place: the plot (or, if none was made, an earlier run's
      /// plot is removed, so it cannot be mistaken for this law's), then the law.
      void commit(const bool plotted)
      {
        std::error_code ec;
        if (plotted)
          fs::rename(tmp_png_, png(), ec);
        else
          fs::remove(png(), ec);
        if (ec)
          throw NumericalError("cannot put " + png() + " in place: " + ec.message());
        fs::rename(tmp_law_, output_, ec);
        if (ec)
          throw NumericalError("cannot rename " + tmp_law_ + " to " + output_ + ": " +
                               ec.message());
        created_dir_ = false;
      }

    private:
      std::string output_, stem_, tmp_law_, tmp_png_;
      interrupt::Temporary temporary_law_, temporary_png_;
      fs::path dir_, created_top_;
      bool created_dir_ = false;
    };
  } // namespace

  int run_fit_command(const FitCommand &c, const int argc, const char *const *argv)
  {
    FitOutputs files(c.output);
    Manifest manifest("fit_stage", files.manifest(), argc, argv);
    manifest.set_library_version("ceres", CERES_VERSION_STRING);
    try
    {
      // Everything is read and fitted before anything is written: an input error leaves
      // nothing behind.
      nlohmann::json scene = nullptr;
      if (c.scene_file)
      {
        manifest.add_input(*c.scene_file);
        scene = read_structured_file(*c.scene_file);
      }
      std::optional<laws::LawFile> single;
      std::optional<laws::LawFamily> family;
      if (!c.family_parameter)
      {
        if (c.inputs.size() != 1)
          throw InputError("", "DATA.csv", std::to_string(c.inputs.size()) + " files",
                           "exactly one CSV file (or --family PARAM FILE=VALUE ...)");
        manifest.add_input(c.inputs[0]);
        laws::LawFile law = fit_csv_file(c.inputs[0], c.options, scene, c.delta_ref);
        law.discretisation_error = c.discretisation_error;
        print_law(c.inputs[0], law);
        manifest.extra()["K"] = {{"value", law.law.K}, {"unit", "N/m^n"}};
        manifest.extra()["n"] = law.law.n;
        manifest.extra()["r_squared"] = law.diagnostics->r_squared;
        if (law.discretisation_error)
          manifest.extra()["discretisation_error_F_relative"] =
            law.discretisation_error->F_relative;
        single = std::move(law);
      }
      else
      {
        if (c.inputs.size() < 2)
          throw InputError("", "--family", std::to_string(c.inputs.size()) + " members",
                           "at least 2 FILE.csv=VALUE arguments");
        std::vector<laws::LawFamilyMember> members;
        double delta_ref = std::numeric_limits<double>::infinity();
        for (const auto &arg : c.inputs)
        {
          const auto eq = arg.rfind('=');
          if (eq == std::string::npos)
            throw InputError("", "family member", arg, "FILE.csv=VALUE");
          const std::string file = arg.substr(0, eq);
          const double value = parse_member_value(arg.substr(eq + 1), arg);
          manifest.add_input(file);
          laws::LawFile law = fit_csv_file(file, c.options, scene, c.delta_ref);
          law.discretisation_error = c.discretisation_error;
          print_law(file + " (" + *c.family_parameter + " = " + format_value(value) + " " +
                      c.family_unit + ")",
                    law);
          delta_ref = std::min(delta_ref, law.delta_max);
          members.push_back({value, std::move(law)});
        }
        std::sort(members.begin(), members.end(),
                  [](const auto &a, const auto &b) { return a.value < b.value; });
        // One reference penetration inside every member's range: F_ref is compared there.
        const double ref = c.delta_ref.value_or(delta_ref);
        for (auto &m : members)
          m.law.delta_ref = ref;
        family.emplace(*c.family_parameter, c.family_unit, ref, std::move(members),
                       laws::parse_range_policy(c.family_policy));
      }

      files.make_folder();
      if (single)
        laws::write_law_file(files.tmp_law(), *single);
      else
        laws::write_law_family(files.tmp_law(), *family);
      bool plotted = false;
      if (c.plots)
        plotted = run_plot_script(c.family_parameter ? "law_family" : "fit",
                                  {files.tmp_law(), "--output", files.tmp_png()}) &&
                  fs::is_regular_file(files.tmp_png());
      interrupt::throw_if_requested("before its outputs were put in place");
      files.commit(plotted);
      manifest.add_output(c.output);
      if (plotted)
        manifest.add_output(files.png());
      try
      {
        manifest.write("complete");
      }
      catch (const WriteError &)
      {
        // A law without its manifest is not this run's output (a full disk): remove it.
        std::error_code ec;
        fs::remove(c.output, ec);
        fs::remove(files.png(), ec);
        throw;
      }
      log::info("wrote " + c.output);
      return exit_success;
    }
    catch (const NumericalError &e)
    {
      // A fit that did not converge: no law, a manifest that says why (exit 2).
      try
      {
        files.make_folder();
        manifest.write("failed", e.what());
      }
      catch (...)
      {
        manifest.discard();
      }
      throw;
    }
    catch (...)
    {
      // Input errors and interrupts leave nothing new behind (an earlier run's outputs stay).
      manifest.discard();
      throw;
    }
  }
} // namespace clearjoint::fit
