#include "pipeline/pipeline_config.h"

#include "common/error.h"
#include "common/strict_reader.h"

#include <cmath>
#include <cstdio>

namespace clearjoint::pipeline
{
  std::string value_label(const double value)
  {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.6g", value);
    return buf;
  }

  void set_key_path(nlohmann::json &root, const std::string &key_path, const nlohmann::json &value,
                    const std::string &source)
  {
    nlohmann::json *node = &root;
    std::size_t start = 0;
    while (true)
    {
      const std::size_t dot = key_path.find('.', start);
      const std::string key = key_path.substr(start, dot == std::string::npos ? dot : dot - start);
      const bool last = dot == std::string::npos;
      if (node->is_array())
      {
        // A numeric component indexes a list: "clearance_joints.0.normal.law_file".
        const bool numeric = !key.empty() && key.find_first_not_of("0123456789") == std::string::npos;
        if (!numeric || std::stoul(key) >= node->size())
          throw InputError(source, key_path, key,
                           "an index in [0, " + std::to_string(node->size()) + ") of the list");
        node = &(*node)[std::stoul(key)];
      }
      else if (node->is_object())
      {
        if (last)
        {
          (*node)[key] = value;
          return;
        }
        if (!node->contains(key))
          (*node)[key] = nlohmann::json::object();
        node = &(*node)[key];
      }
      else
        throw InputError(source, key_path, node->dump(), "a key path through mappings and lists",
                         "'" + key + "' cannot be set inside a scalar");
      if (last)
      {
        *node = value;
        return;
      }
      start = dot + 1;
    }
  }

  PipelineConfig read_pipeline_config(const std::string &path)
  {
    const auto j = read_yaml_file(path);
    StrictObject top(j, path);
    top.expect_schema("clearjoint.pipeline/1");
    PipelineConfig c;
    c.source = path;
    c.run = top.string("run");
    if (c.run.empty() || c.run.find('/') != std::string::npos || c.run[0] == '.')
      top.fail("run", c.run, "a folder name without '/' that does not start with '.'");
    c.output_root = top.string_or("output_root", "out");
    c.preset = top.string("preset", {"fast", "standard", "accurate"});
    c.mpi_ranks = static_cast<int>(top.integer_or("mpi_ranks", 1, 1, 64));
    c.report = top.boolean_or("report", true);

    auto presets = top.object("presets");
    for (const std::string p : {"fast", "standard", "accurate"})
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
      stages.finish();
    }
    presets.finish();

    for (auto &s : top.object_array("fe_studies"))
    {
      FeStudy f;
      f.name = s.string("name");
      f.scene = s.string("scene");
      auto p = s.object("parameter");
      f.parameter = p.string("name");
      f.unit = p.string("unit");
      f.key = p.string("key");
      p.finish();
      f.values = s.number_array("values", Range::any(f.unit), 1);
      for (std::size_t i = 1; i < f.values.size(); ++i)
        if (!(f.values[i] > f.values[i - 1]))
          s.fail("values", value_label(f.values[i]), "strictly increasing values");
      for (const auto &other : c.fe_studies)
        if (other.name == f.name)
          s.fail("name", f.name, "a name not used by another study");
      s.finish();
      c.fe_studies.push_back(f);
    }

    auto fit = top.object("fit");
    c.fit_weighting = fit.string_or("weighting", "absolute", {"absolute", "relative"});
    fit.finish();

    for (auto &m : top.object_array("mbd_runs"))
    {
      MbdRun r;
      r.name = m.string("name");
      r.scene = m.string("scene");
      if (m.has("laws"))
        for (auto &l : m.object_array("laws"))
        {
          LawChoice choice;
          choice.key = l.string("key");
          if (l.has("file"))
            choice.file = l.string("file");
          if (l.has("study"))
          {
            choice.study = l.string("study");
            const FeStudy *study = nullptr;
            std::string names;
            for (const auto &f : c.fe_studies)
            {
              names += (names.empty() ? "" : "|") + f.name;
              if (f.name == *choice.study)
                study = &f;
            }
            if (!study)
              l.fail("study", *choice.study, "one of the fe_studies: " + names);
            if (l.has("value"))
            {
              choice.value = l.number("value", Range::any(study->unit));
              bool found = false;
              std::string values;
              for (double v : study->values)
              {
                found = found || std::abs(v - *choice.value) <= 1e-12 * std::abs(v);
                values += (values.empty() ? "" : ", ") + value_label(v);
              }
              if (!found)
                l.fail("value", value_label(*choice.value),
                       "one of the values of study '" + study->name + "': " + values);
            }
            else if (study->values.size() < 2)
              l.fail("study", study->name, "a study with >= 2 values for a law family",
                     "or give 'value' to use one law");
          }
          else if (l.has("value"))
            l.fail("value", l.raw("value").dump(), "only together with 'study'");
          if (choice.file.has_value() == choice.study.has_value())
            l.fail("file", choice.file.value_or("(none)"),
                   "exactly one of 'file' (a law file) or 'study' (a fitted law)");
          l.finish();
          r.laws.push_back(choice);
        }
      else
        m.allow("laws");
      r.band = m.boolean_or("band", false);
      if (r.band && !(r.laws.size() == 1 && r.laws[0].value))
        m.fail("band", "true", "false, or exactly one law given by 'study' and 'value'",
               "a confidence band varies one fitted law");
      m.finish();
      c.mbd_runs.push_back(r);
    }
    top.finish();
    return c;
  }
} // namespace clearjoint::pipeline
