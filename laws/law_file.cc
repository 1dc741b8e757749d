#include "laws/law_file.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/strict_reader.h"
#include "common/units.h"

#include <cmath>

namespace clearjoint::laws
{
  namespace
  {
    nlohmann::json optional_string(const std::optional<std::string> &s)
    {
      return s ? nlohmann::json(*s) : nlohmann::json(nullptr);
    }

    std::optional<std::string> read_optional_string(StrictObject &o, const std::string &key)
    {
      if (!o.has(key))
      {
        o.raw(key);  // must be present (null allowed): marks it read, throws if missing
        return std::nullopt;
      }
      return o.string(key);
    }

    FitDiagnostics diagnostics_from_json(StrictObject d)
    {
      FitDiagnostics f;
      const Range any = Range::any();
      f.n_points = static_cast<std::size_t>(d.integer("n_points", 0, 1000000000));
      f.weighting = d.string("weighting", {"absolute", "relative"});
      auto range = d.object("fit_range");
      f.fit_delta_min = range.number("delta_min", Range::non_negative("m"));
      f.fit_delta_max = range.number("delta_max", Range::positive("m"));
      range.finish();
      f.r_squared = d.number("r_squared", any);
      f.residual_std = d.number("residual_std", Range::non_negative());
      f.sum_squared_residuals = d.number("sum_squared_residuals", Range::non_negative());
      f.K_std_error = d.number("K_std_error", Range::non_negative("N/m^n"));
      f.n_std_error = d.number("n_std_error", Range::non_negative());
      const auto K_ci = d.number_array("K_ci95", any, 2);
      const auto n_ci = d.number_array("n_ci95", any, 2);
      f.K_ci95_low = K_ci[0], f.K_ci95_high = K_ci[1];
      f.n_ci95_low = n_ci[0], f.n_ci95_high = n_ci[1];
      f.correlation_K_n = d.number("correlation_K_n", Range::closed(-1.0 - 1e-9, 1.0 + 1e-9));
      f.condition_number = d.number("condition_number", Range::non_negative());
      f.max_relative_residual = d.number("max_relative_residual", Range::non_negative());
      f.solver_summary = d.string("solver_summary");
      f.delta = d.number_array("delta", Range::non_negative("m"));
      f.force = d.number_array("force", Range::non_negative("N"));
      f.residual = d.number_array("residual", any);
      if (f.delta.size() != f.force.size() || f.delta.size() != f.residual.size())
        d.fail("delta", std::to_string(f.delta.size()) + " values",
               "as many values as force and residual");
      d.finish();
      return f;
    }
  } // namespace

  nlohmann::json to_json(const FitDiagnostics &d)
  {
    return {
      {"n_points", d.n_points},
      {"weighting", d.weighting},
      {"fit_range", {{"delta_min", d.fit_delta_min}, {"delta_max", d.fit_delta_max}}},
      {"r_squared", d.r_squared},
      {"residual_std", d.residual_std},
      {"sum_squared_residuals", d.sum_squared_residuals},
      {"K_std_error", d.K_std_error},
      {"n_std_error", d.n_std_error},
      {"K_ci95", {d.K_ci95_low, d.K_ci95_high}},
      {"n_ci95", {d.n_ci95_low, d.n_ci95_high}},
      {"correlation_K_n", d.correlation_K_n},
      {"condition_number", d.condition_number},
      {"max_relative_residual", d.max_relative_residual},
      {"solver_summary", d.solver_summary},
      {"delta", d.delta},
      {"force", d.force},
      {"residual", d.residual},
    };
  }

  nlohmann::json to_json(const LawFile &l)
  {
    nlohmann::json j;
    j["schema"] = law_schema;
    j["law"] = {{"form", "F = K*delta^n"}, {"K", l.law.K}, {"n", l.law.n}};
    j["units"] = {{"delta", "m"}, {"force", "N"}, {"K", "N/m^n"}, {"n", "1"}};
    j["valid_range"] = {{"delta_min", l.delta_min}, {"delta_max", l.delta_max}};
    j["reference"] = {{"delta_ref", l.delta_ref}, {"F_ref", l.F_ref()}};
    j["mm_N"] = {{"K", units::power_law_K_SI_to_mm(l.law.K, l.law.n)},
                 {"n", l.law.n},
                 {"note", "the same law with delta in mm and F in N, for comparison with papers"}};
    j["source"] = {{"kind", l.source_kind},
                   {"description", l.source_description},
                   {"data_file", optional_string(l.data_file)},
                   {"data_sha256", optional_string(l.data_sha256)}};
    j["scene"] = l.scene.is_null() ? nlohmann::json(nullptr) : l.scene;
    j["diagnostics"] = l.diagnostics ? to_json(*l.diagnostics) : nlohmann::json(nullptr);
    j["discretisation_error"] =
      l.discretisation_error ?
        nlohmann::json{{"F_relative", l.discretisation_error->F_relative},
                       {"unit", "1"},
                       {"description", l.discretisation_error->description}} :
        nlohmann::json(nullptr);
    return j;
  }

  LawFile law_from_json(const nlohmann::json &j, const std::string &source,
                        const std::string &key_prefix)
  {
    StrictObject top(j, source, key_prefix);
    top.expect_schema(law_schema);
    LawFile l;

    auto units_obj = top.object("units");
    units_obj.string("delta", {"m"});
    units_obj.string("force", {"N"});
    units_obj.string("K", {"N/m^n"});
    units_obj.string("n", {"1"});
    units_obj.finish();

    auto law = top.object("law");
    law.string("form", {"F = K*delta^n"});
    l.law.K = law.number("K", Range::positive("N/m^n"));
    l.law.n = law.number("n", Range::open(0.0, 10.0));
    law.finish();

    auto range = top.object("valid_range");
    l.delta_min = range.number("delta_min", Range::non_negative("m"));
    l.delta_max = range.number("delta_max", Range::positive("m"));
    if (!(l.delta_max > l.delta_min))
      range.fail("delta_max", format_value(l.delta_max),
                 "> delta_min = " + format_value(l.delta_min) + " m");
    range.finish();

    auto ref = top.object("reference");
    l.delta_ref = ref.number("delta_ref", Range::positive("m"));
    const double F_ref = ref.number("F_ref", Range::positive("N"));
    if (std::abs(F_ref - l.F_ref()) > 1e-6 * l.F_ref())
      ref.fail("F_ref", format_value(F_ref),
               "K*delta_ref^n = " + format_value(l.F_ref()) + " N (within 1e-6 relative)",
               "F_ref disagrees with K and n: the file was edited inconsistently");
    ref.finish();

    // mm_N is a display copy; it is checked, not trusted.
    auto mm = top.object("mm_N");
    const double K_mm = mm.number("K", Range::positive("N/mm^n"));
    mm.number("n", Range::positive());
    mm.string_or("note", "");
    const double K_mm_expected = units::power_law_K_SI_to_mm(l.law.K, l.law.n);
    if (std::abs(K_mm - K_mm_expected) > 1e-6 * K_mm_expected)
      mm.fail("K", format_value(K_mm),
              format_value(K_mm_expected) + " N/mm^n (K converted from SI)",
              "the mm/N copy disagrees with the SI law");
    mm.finish();

    auto src = top.object("source");
    l.source_kind = src.string("kind", {"paper", "fit", "confidence_band"});
    l.source_description = src.string("description");
    l.data_file = read_optional_string(src, "data_file");
    l.data_sha256 = read_optional_string(src, "data_sha256");
    src.finish();

    l.scene = top.raw("scene");
    if (!l.scene.is_null() && !l.scene.is_object())
      top.fail("scene", json_excerpt(l.scene), "null or a mapping of scene parameters");
    if (top.has("diagnostics"))
      l.diagnostics = diagnostics_from_json(top.object("diagnostics"));
    else
      top.raw("diagnostics");
    // Optional: law files written before the key existed have no such key.
    if (top.has("discretisation_error"))
    {
      auto e = top.object("discretisation_error");
      DiscretisationError de;
      de.F_relative = e.number("F_relative", Range{.lo = 0.0, .hi = 1.0, .hi_open = true, .unit = "1"});
      e.string("unit", {"1"});
      de.description = e.string("description");
      e.finish();
      l.discretisation_error = de;
    }
    else
      top.allow("discretisation_error");  // null: not known
    top.finish();
    return l;
  }

  LawFile read_law_file(const std::string &path)
  {
    return law_from_json(read_json_file(path), path);
  }

  void write_law_file(const std::string &path, const LawFile &law)
  {
    write_file_atomically(path, json_text(to_json(law)) + "\n");
  }
} // namespace clearjoint::laws
