#include "pipeline/pipeline_config.h"

#include "common/error.h"
#include "common/log.h"
#include "common/strict_reader.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <tuple>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  Overrides overrides_for_preset(const Overrides &overrides,
                                 const PresetOverrides &preset_overrides, const std::string &preset)
  {
    Overrides out = overrides;
    const auto p = preset_overrides.find(preset);
    if (p != preset_overrides.end())
      out.insert(out.end(), p->second.begin(), p->second.end());
    return out;
  }

  Overrides sweep_overrides(const FeSweep &sweep, const std::string &preset)
  {
    return overrides_for_preset(sweep.overrides, sweep.preset_overrides, preset);
  }

  Overrides rolling_overrides(const RollingStudy &rolling, const std::string &preset)
  {
    return overrides_for_preset(rolling.overrides, rolling.preset_overrides, preset);
  }

  Overrides impact_overrides(const ImpactStudy &impact, const std::string &preset)
  {
    return overrides_for_preset(impact.overrides, impact.preset_overrides, preset);
  }

  std::string value_label(const double value)
  {
    // Shortest "%.{p}g" that reads back as the same double: 0.004 stays "0.004", a computed
    // θ_max keeps all its digits (so two different values never share a folder).
    char buf[40];
    for (int precision = 6; precision <= 17; ++precision)
    {
      std::snprintf(buf, sizeof(buf), "%.*g", precision, value);
      if (std::strtod(buf, nullptr) == value)
        break;
    }
    return buf;
  }

  namespace
  {
    /// `key: {a.b: value, ...}` → overrides; a string naming an existing file relative to the
    /// directory run_pipeline runs in becomes absolute (the generated scenes live elsewhere).
    Overrides read_overrides(StrictObject &o, const std::string &key)
    {
      Overrides out;
      if (!o.has(key))
      {
        o.allow(key);
        return out;
      }
      const auto &map = o.raw(key);
      if (!map.is_object())
        o.fail(key, map.dump(), "a mapping of scene key paths to values");
      for (auto it = map.begin(); it != map.end(); ++it)
      {
        nlohmann::json value = it.value();
        if (value.is_string())
        {
          std::error_code ec;
          const std::string s = value.get<std::string>();
          if (!s.empty() && s[0] != '/' && fs::is_regular_file(s, ec))
            value = fs::canonical(s).string();
        }
        out.emplace_back(it.key(), value);
      }
      return out;
    }

    /// A block's `presets` (an FE sweep's, the rolling study's; see PresetOverrides): absent or
    /// null → empty; else a mapping that names every preset, each null or a mapping of scene
    /// key paths to values (read_overrides), and no other name. `block` names the block in the
    /// message of a missing preset ("sweep", "rolling study").
    PresetOverrides read_preset_overrides(StrictObject &o, const std::string &block)
    {
      PresetOverrides out;
      if (!o.has("presets"))
        {
          o.allow("presets");
          return out;
        }
      const auto &given = o.raw("presets");
      if (!given.is_object())
        o.fail("presets", json_excerpt(given, 60),
               "a mapping of preset names (fast, standard, accurate) to scene settings");
      StrictObject presets = o.object("presets");
      for (const auto &preset : preset_names())
        {
          if (!given.contains(preset))
            presets.fail(preset, "missing",
                         "settings (or null) for every preset: fast, standard, accurate",
                         "a " + block +
                           "'s presets name every preset, so that no preset runs this " + block +
                           " on settings nobody measured for it");
          out[preset] = read_overrides(presets, preset);
        }
      presets.finish();  // an unknown preset name: the message lists the valid ones
      return out;
    }

    std::optional<double> optional_number(StrictObject &o, const std::string &key,
                                          const Range &range)
    {
      if (!o.has(key))
      {
        o.allow(key);
        return std::nullopt;
      }
      return o.number(key, range);
    }

    PresetMeasured read_measured(StrictObject m)
    {
      PresetMeasured r;
      r.note = m.string("note");
      r.fe_dofs = optional_number(m, "fe_dofs", Range::positive("1"));
      r.fe_case_time = optional_number(m, "fe_case_time", Range::positive("s"));
      r.pipeline_time = optional_number(m, "pipeline_time", Range::positive("s"));
      r.impact_time = optional_number(m, "impact_time", Range::positive("s"));
      r.impact_deformable_time = optional_number(m, "impact_deformable_time", Range::positive("s"));
      r.rolling_time = optional_number(m, "rolling_time", Range::positive("s"));
      const auto &map = m.raw("error_F_max");
      if (!map.is_object())
        m.fail("error_F_max", map.dump(),
               "a mapping of FE sweep names (and impact, impact_deformable, rolling) to "
               "{percent, where}");
      auto errors = m.object("error_F_max");
      for (auto it = map.begin(); it != map.end(); ++it)
      {
        auto e = errors.object(it.key());
        PresetError pe;
        if (!e.has("percent"))
          e.raw("percent");  // required: a number, or null for "not yet measured"
        else
          pe.percent = e.number("percent", Range::open(0.0, 100.0, "%"));
        pe.where = e.string("where");
        e.finish();
        r.error_F_max[it.key()] = pe;
      }
      errors.finish();
      // Per-sweep (and impact, rolling) figures (bench/measure_presets.py writes them):
      // {name: number}.
      for (const auto &[key, target, range] :
           {std::tuple{"case_times", &r.case_times, Range::positive("s")},
            std::tuple{"dofs", &r.dofs, Range::positive("1")}})
      {
        if (!m.has(key))
        {
          m.allow(key);
          continue;
        }
        const auto &raw = m.raw(key);
        if (!raw.is_object())
          m.fail(key, raw.dump(), "a mapping of FE sweep names (and impact, impact_deformable, rolling) "
                         "to numbers");
        auto per_name = m.object(key);
        for (auto it = raw.begin(); it != raw.end(); ++it)
          (*target)[it.key()] = per_name.number(it.key(), range);
        per_name.finish();
      }
      if (m.has("date"))
        r.date = m.string("date");
      else
        m.allow("date");
      if (m.has("machine"))
      {
        auto machine = m.object("machine");
        r.machine_cpu = machine.string("cpu");
        r.machine_cores = int(machine.integer("cores", 1, 1000000));
        machine.finish();
      }
      else
        m.allow("machine");
      m.finish();
      return r;
    }

    /// One element of a sweep's `values` or a law's `value`: a number or a keyword.
    void read_value(const nlohmann::json &v, StrictObject &o, const std::string &key,
                    const std::string &unit, double &number, std::string &keyword)
    {
      if (v.is_number())
      {
        number = v.get<double>();
        if (!std::isfinite(number))
          o.fail(key, v.dump(), "a finite number in " + unit);
        keyword.clear();
      }
      else if (v.is_string() && v.get<std::string>() == theta_max_keyword)
      {
        number = std::numeric_limits<double>::quiet_NaN();
        keyword = theta_max_keyword;
      }
      else
        o.fail(key, v.dump(), std::string("a number in ") + unit + " or the keyword " +
                                theta_max_keyword + " (paper Eq. 3 for the sweep's geometry)");
    }

    FeSweep read_sweep(StrictObject &s, const std::vector<FeSweep> &others)
    {
      FeSweep f;
      f.name = s.string("name");
      if (f.name.empty() || f.name.find('/') != std::string::npos || f.name[0] == '.')
        s.fail("name", f.name, "a folder name without '/' that does not start with '.'");
      f.scene = s.string("scene");
      auto p = s.object("parameter");
      f.parameter = p.string("name");
      f.unit = p.string("unit");
      f.key = p.string("key");
      p.finish();
      const auto &values = s.raw("values");
      if (!values.is_array() || values.empty())
        s.fail("values", values.dump(), "a list of at least 1 value: numbers in " + f.unit +
                                          " or the keyword theta_max");
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        double v;
        std::string keyword;
        read_value(values[i], s, "values[" + std::to_string(i) + "]", f.unit, v, keyword);
        for (std::size_t j = 0; j < f.keywords.size(); ++j)
          if (!keyword.empty() && f.keywords[j] == keyword)
            s.fail("values[" + std::to_string(i) + "]", keyword, "each keyword at most once");
        f.values.push_back(v);
        f.keywords.push_back(keyword);
      }
      // The numbers must increase; keywords are checked once resolved (sweep_values.h).
      double previous = -std::numeric_limits<double>::infinity();
      for (const double v : f.values)
        if (!std::isnan(v))
        {
          if (!(v > previous))
            s.fail("values", value_label(v), "strictly increasing values");
          previous = v;
        }
      for (const auto &other : others)
        if (other.name == f.name)
          s.fail("name", f.name, "a name not used by another sweep");
      f.overrides = read_overrides(s, "overrides");
      for (const auto &[key, value] : f.overrides)
        if (key == f.key)
          s.fail("overrides", key, "keys other than the swept parameter's key '" + f.key + "'");
      f.preset_overrides = read_preset_overrides(s, "sweep");
      if (!f.preset_overrides.empty())  // given, it names every preset
        for (const auto &preset : preset_names())
          for (const auto &[key, value] : f.preset_overrides.at(preset))
            if (key == f.key)
              s.fail("presets." + preset, key,
                     "keys other than the swept parameter's key '" + f.key + "'");
      if (s.has("mesh_parameters"))
      {
        const auto &mp = s.raw("mesh_parameters");
        if (!mp.is_object())
          s.fail("mesh_parameters", mp.dump(), "a mapping of Gmsh DefineConstant names to numbers");
        for (auto it = mp.begin(); it != mp.end(); ++it)
        {
          if (!it.value().is_number() || it.key().empty() ||
              it.key().find_first_of(" \t\"'") != std::string::npos)
            s.fail("mesh_parameters." + it.key(), it.value().dump(),
                   "a number (SI) for a Gmsh DefineConstant name without spaces or quotes");
          f.mesh_parameters[it.key()] = it.value().get<double>();
        }
      }
      else
        s.allow("mesh_parameters");
      s.finish();
      return f;
    }

    /// Reads the key `key`, or the deprecated `old_key` that it replaced, whichever the object
    /// gives: both → InputError naming both; the old one → its path is added to `deprecated`.
    /// Returns the key given ("" when neither).
    std::string renamed_key(StrictObject &o, const std::string &key, const std::string &old_key,
                            std::vector<std::string> &deprecated)
    {
      const bool has_new = o.has(key), has_old = o.has(old_key);
      if (has_new && has_old)
        o.fail(old_key, json_excerpt(o.raw(old_key), 60),
               "only '" + key + "' (the new name of '" + old_key + "')",
               "'" + o.path_of(key) + "' and '" + o.path_of(old_key) +
                 "' are both given, the new and the old name of one key: keep only '" + key +
                 "'");
      o.allow(old_key);
      if (has_old)
      {
        deprecated.push_back(o.path_of(old_key));
        return old_key;
      }
      o.allow(key);
      return has_new ? key : "";
    }

    /// One warning line for the places that use `old_key` (renamed to `key`).
    void warn_deprecated(const std::string &file, const std::string &old_key,
                         const std::string &key, const std::vector<std::string> &paths)
    {
      if (paths.empty())
        return;
      std::string where;
      for (std::size_t i = 0; i < paths.size() && i < 3; ++i)
        where += (i ? ", " : "") + paths[i];
      if (paths.size() > 3)
        where += " and " + std::to_string(paths.size() - 3) + " more";
      log::warning(file + ": '" + old_key + "' is deprecated, rename it to '" + key + "' (" +
                   where + ")");
    }

    /// `with_key`: the law goes into a scene at `key` (MBD runs); the impact comparison takes
    /// the law file itself. A fitted law names its sweep with `sweep` (formerly `study`).
    LawChoice read_law_choice(StrictObject &l, const PipelineConfig &c,
                              std::vector<std::string> &deprecated, const bool with_key = true)
    {
      LawChoice choice;
      if (with_key)
        choice.key = l.string("key");
      if (l.has("file"))
        choice.file = l.string("file");
      const std::string sweep_key = renamed_key(l, "sweep", "study", deprecated);
      if (!sweep_key.empty())
      {
        choice.sweep = l.string(sweep_key);
        const FeSweep *sweep = nullptr;
        std::string names;
        for (const auto &f : c.fe_sweeps)
        {
          names += (names.empty() ? "" : "|") + f.name;
          if (f.name == *choice.sweep)
            sweep = &f;
        }
        if (!sweep)
          l.fail(sweep_key, *choice.sweep, "one of the " + c.fe_sweeps_key + ": " + names);
        if (l.has("value"))
        {
          double v;
          read_value(l.raw("value"), l, "value", sweep->unit, v, choice.value_keyword);
          bool found = false;
          std::string values;
          for (std::size_t i = 0; i < sweep->values.size(); ++i)
          {
            const double s = sweep->values[i];
            if (choice.value_keyword.empty())
              found = found || std::abs(s - v) <= 1e-12 * std::abs(s);
            else
              found = found || sweep->keywords[i] == choice.value_keyword;
            values += (values.empty() ? "" : ", ") +
                      (sweep->keywords[i].empty() ? value_label(s) : sweep->keywords[i]);
          }
          if (!found)
            l.fail("value", choice.value_keyword.empty() ? value_label(v) : choice.value_keyword,
                   "one of the values of sweep '" + sweep->name + "': " + values);
          if (choice.value_keyword.empty())
            choice.value = v;
        }
        else if (sweep->values.size() < 2)
          l.fail(sweep_key, sweep->name, "a sweep with >= 2 values for a law family",
                 "or give 'value' to use one law");
      }
      else if (l.has("value"))
        l.fail("value", l.raw("value").dump(), "only together with 'sweep'");
      if (choice.file.has_value() == choice.sweep.has_value())
        l.fail("file", choice.file.value_or("(none)"),
               "exactly one of 'file' (a law file) or 'sweep' (a fitted law)");
      l.finish();
      return choice;
    }

    /// The run's own keys: run (a folder name), output_root, preset, mpi_ranks, report, jobs,
    /// executor.
    void read_run_settings(StrictObject &top, PipelineConfig &c)
    {
      c.run = top.string("run");
      if (c.run.empty() || c.run.find('/') != std::string::npos || c.run[0] == '.')
        top.fail("run", c.run, "a folder name without '/' that does not start with '.'");
      c.output_root = top.string_or("output_root", "out");
      c.preset = top.string("preset", preset_names());
      c.mpi_ranks = static_cast<int>(top.integer_or("mpi_ranks", 1, 1, 64));
      c.report = top.boolean_or("report", true);
      if (top.has("jobs"))
        c.jobs = static_cast<int>(top.integer("jobs", 1, max_jobs));
      else
        top.allow("jobs");
      if (top.has("executor"))
        c.executor = read_executor_config(top.object("executor"));
      else
        top.allow("executor");
    }

    /// `presets`: per preset, the fe and mbd scene overrides and what was measured.
    void read_presets(StrictObject &top, PipelineConfig &c)
    {
      auto presets = top.object("presets");
      for (const std::string &p : preset_names())
      {
        auto stages = presets.object(p);
        for (const std::string s : {"fe", "mbd"})
        {
          const auto &overrides = stages.raw(s);
          if (!overrides.is_null() && !overrides.is_object())
            stages.fail(s, overrides.dump(), "a mapping of scene key paths to values");
          if (overrides.is_object())
            for (auto it = overrides.begin(); it != overrides.end(); ++it)
              c.presets[p][s + ":" + it.key()] = it.value();
        }
        if (stages.has("measured"))
          c.preset_measured[p] = read_measured(stages.object("measured"));
        else
          stages.allow("measured");
        stages.finish();
      }
      presets.finish();
    }

    /// `fe_sweeps` (or the deprecated `fe_studies`, whose places join old_sweeps_key).
    void read_fe_sweeps(StrictObject &top, PipelineConfig &c,
                        std::vector<std::string> &old_sweeps_key)
    {
      c.fe_sweeps_key = renamed_key(top, "fe_sweeps", "fe_studies", old_sweeps_key);
      if (c.fe_sweeps_key.empty())
        c.fe_sweeps_key = "fe_sweeps";  // absent: object_array reports the missing key
      for (auto &s : top.object_array(c.fe_sweeps_key))
        c.fe_sweeps.push_back(read_sweep(s, c.fe_sweeps));
    }

    /// `fit`: the weighting and what a law family does outside its values.
    void read_fit_settings(StrictObject &top, PipelineConfig &c)
    {
      auto fit = top.object("fit");
      c.fit_weighting = fit.string_or("weighting", "absolute", {"absolute", "relative"});
      c.family_out_of_range =
        fit.string_or("family_out_of_range", "error", {"error", "clamp", "extend"});
      fit.finish();
    }

    /// One entry of `mbd_runs`; its laws name sweeps already read into c.
    MbdRun read_mbd_run(StrictObject &m, const PipelineConfig &c,
                        std::vector<std::string> &old_law_key)
    {
      MbdRun r;
      r.name = m.string("name");
      if (r.name.empty() || r.name.find('/') != std::string::npos || r.name[0] == '.')
        m.fail("name", r.name, "a folder name without '/' that does not start with '.'");
      r.scene = m.string("scene");
      if (m.has("laws"))
        for (auto &l : m.object_array("laws"))
          r.laws.push_back(read_law_choice(l, c, old_law_key));
      else
        m.allow("laws");
      r.overrides = read_overrides(m, "overrides");
      r.band = m.boolean_or("band", false);
      if (r.band && !(r.laws.size() == 1 && r.laws[0].sweep &&
                      (r.laws[0].value || !r.laws[0].value_keyword.empty())))
        m.fail("band", "true", "false, or exactly one law given by 'sweep' and 'value'",
               "a confidence band varies one fitted law");
      m.finish();
      return r;
    }

    /// `impact.deformable`: the deformable-journal variant's scene and its overrides (the scene's
    /// journal is checked with the scenes, before the run).
    DeformableImpact read_deformable_impact(StrictObject m)
    {
      DeformableImpact d;
      d.scene = m.string("scene");
      if (d.scene.empty())
        m.fail("scene", "",
               "an FE scene file (clearjoint.fe/1) with study: impact and a deformable journal "
               "(loading.journal: end_faces or axis_line)");
      d.overrides = read_overrides(m, "overrides");
      m.finish();
      return d;
    }

    /// `impact`: the FE impact study's scene, its overrides and its settings per preset, the
    /// one law it is compared with, and the optional deformable-journal variant.
    ImpactStudy read_impact(StrictObject m, const PipelineConfig &c,
                            std::vector<std::string> &old_law_key)
    {
      ImpactStudy impact;
      impact.scene = m.string("scene");
      impact.overrides = read_overrides(m, "overrides");
      impact.preset_overrides = read_preset_overrides(m, "impact study");
      if (m.has("deformable"))
        impact.deformable = read_deformable_impact(m.object("deformable"));
      else
        m.allow("deformable");
      auto law = m.object("law");
      impact.law = read_law_choice(law, c, old_law_key, false);
      if (impact.law.sweep && !impact.law.value && impact.law.value_keyword.empty())
        law.fail(law.has("study") ? "study" : "sweep", *impact.law.sweep,
                 "one law: give 'value' too",
                 "the impact comparison uses the law of one geometry");
      m.finish();
      return impact;
    }

    /// `rolling`: the FE rolling study's scene, its overrides and its settings per preset.
    RollingStudy read_rolling(StrictObject m)
    {
      RollingStudy rolling;
      rolling.scene = m.string("scene");
      if (rolling.scene.empty())
        m.fail("scene", "", "an FE scene file (clearjoint.fe/1) with study: rolling");
      rolling.overrides = read_overrides(m, "overrides");
      rolling.preset_overrides = read_preset_overrides(m, "rolling study");
      m.finish();
      return rolling;
    }

    /// The names a preset's measurements are given for: "a|b|…" of the FE sweeps (and impact,
    /// rolling when present and not fe_only), and whether `name` is one of them.
    std::pair<bool, std::string> measured_name_choice(const PipelineConfig &c,
                                                      const std::string &name,
                                                      const bool fe_only)
    {
      std::string names;
      const bool deformable = c.impact && c.impact->deformable;
      bool found = !fe_only && ((name == "impact" && c.impact.has_value()) ||
                                (name == "impact_deformable" && deformable) ||
                                (name == "rolling" && c.rolling.has_value()));
      for (const auto &f : c.fe_sweeps)
      {
        names += (names.empty() ? "" : "|") + f.name;
        found = found || f.name == name;
      }
      if (c.impact && !fe_only)
        names += "|impact";
      if (deformable && !fe_only)
        names += "|impact_deformable";
      if (c.rolling && !fe_only)
        names += "|rolling";
      return {found, names};
    }

    /// A preset's case times, DoFs and errors are per FE sweep: each name must be one of them
    /// (or `impact`, the impact study's peak force, when there is one; or `rolling`, when
    /// there is one; case times: FE sweeps only).
    void check_measured_names(const std::string &path, const PipelineConfig &c)
    {
      const auto check = [&](const std::string &key, const std::string &name, const bool fe_only) {
        const auto [found, names] = measured_name_choice(c, name, fe_only);
        if (!found)
          throw InputError(path, key, name,
                           (fe_only ? "one of the quasi-static " + c.fe_sweeps_key + ": "
                                    : "one of the " + c.fe_sweeps_key + ", impact or rolling: ") +
                             names);
      };
      for (const auto &[preset, measured] : c.preset_measured)
      {
        for (const auto &[name, seconds] : measured.case_times)
          check("presets." + preset + ".measured.case_times." + name, name, true);
        for (const auto &[name, n] : measured.dofs)
          check("presets." + preset + ".measured.dofs." + name, name, false);
      }
      // the deformable impact's task time only where that task exists
      for (const auto &[preset, measured] : c.preset_measured)
        if (measured.impact_deformable_time && !(c.impact && c.impact->deformable))
          throw InputError(path, "presets." + preset + ".measured.impact_deformable_time",
                           format_value(*measured.impact_deformable_time),
                           "absent without an impact.deformable section",
                           "it is the time of the deformable-journal impact task");
      for (const auto &[preset, measured] : c.preset_measured)
        for (const auto &[name, error] : measured.error_F_max)
          if (const auto [found, names] = measured_name_choice(c, name, false); !found)
            throw InputError(path, "presets." + preset + ".measured.error_F_max." + name, name,
                             "one of the " + c.fe_sweeps_key + ": " + names);
    }
  } // namespace

  PipelineConfig read_pipeline_config(const std::string &path)
  {
    const auto j = read_yaml_file(path);
    StrictObject top(j, path);
    top.expect_schema("clearjoint.pipeline/1");
    PipelineConfig c;
    c.source = path;
    read_run_settings(top, c);
    read_presets(top, c);
    std::vector<std::string> old_sweeps_key, old_law_key;  // deprecated keys, where given
    read_fe_sweeps(top, c, old_sweeps_key);
    read_fit_settings(top, c);
    for (auto &m : top.object_array("mbd_runs"))
      c.mbd_runs.push_back(read_mbd_run(m, c, old_law_key));
    if (top.has("impact"))
      c.impact = read_impact(top.object("impact"), c, old_law_key);
    if (top.has("rolling"))
      c.rolling = read_rolling(top.object("rolling"));
    check_measured_names(path, c);
    top.finish();
    // Only once the file is read: a file with an error says that, not what to rename.
    warn_deprecated(path, "fe_studies", "fe_sweeps", old_sweeps_key);
    warn_deprecated(path, "study", "sweep", old_law_key);
    return c;
  }
} // namespace clearjoint::pipeline
