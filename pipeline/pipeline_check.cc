// run_pipeline --check, also the first step of every run (issue 16 item 2): every scene the
// run would generate is composed and handed to its stage's own reader (STAGE SCENE --check),
// in a scratch folder outside the output root, so that a bad value stops the run before
// anything exists under the output root — reported as an input error naming the pipeline key
// that produced it (a sweep value, an override, a preset key, a law) rather than as a stage
// failure half-way through the run. The stages' checks run a few at once (StageChecks); a
// failure among them is reported after the checks of the pipeline file's own keys.
#include "pipeline/executor_config.h"
#include "pipeline/pipeline_runner.h"
#include "pipeline/slurm_executor.h"

#include "common/atomic_file.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/log.h"
#include "laws/law_file.h"
#include "pipeline/scene_builder.h"
#include "pipeline/stage_check.h"
#include "pipeline/stand_in_laws.h"
#include "pipeline/sweep_values.h"

#include <unistd.h>

#include <climits>
#include <filesystem>
#include <set>

namespace clearjoint::pipeline
{
  namespace fs = std::filesystem;

  namespace
  {
    /// A scratch folder outside the output root, removed when the check ends.
    class Scratch
    {
    public:
      Scratch()
        : path_(fs::temp_directory_path() /
                ("clearjoint-check-" + std::to_string(::getpid())))
      {
        fs::remove_all(path_);
        fs::create_directories(path_);
      }
      ~Scratch()
      {
        std::error_code ec;
        fs::remove_all(path_, ec);
      }
      std::string file(const std::string &name) const { return (path_ / name).string(); }
      const fs::path &path() const { return path_; }

    private:
      fs::path path_;
    };

    /// Output folder and file names must fit the file system: NAME_MAX per component, with
    /// room for the suffixes the stages and the task runner append (".partial",
    /// ".command.txt", ".tmp.<pid>", "_band").
    constexpr std::size_t name_suffix_room = 32;

    void check_name(const std::string &source, const std::string &key, const std::string &name)
    {
      if (name.size() + name_suffix_room > NAME_MAX)
        throw InputError(source, key, name.substr(0, 40) + "... (" +
                                        std::to_string(name.size()) + " bytes)",
                         "at most " + std::to_string(NAME_MAX - name_suffix_room) + " bytes",
                         "a file or folder name made from it would be too long for the file "
                         "system");
      if (first_invalid_utf8(name) != std::string::npos)
        throw InputError(source, key, "(bytes that are not UTF-8)", "UTF-8 text",
                         "names are written into JSON manifests and summaries");
    }

    /// Every FE case gets its own folder: names the file system accepts, and no two values of
    /// one sweep with the same label.
    void check_fe_sweep_names(const PipelineConfig &config)
    {
      const std::string &src = config.source;
      for (std::size_t i = 0; i < config.fe_sweeps.size(); ++i)
      {
        const FeSweep &s = config.fe_sweeps[i];
        const std::string key = config.fe_sweeps_key + "[" + std::to_string(i) + "]";
        check_name(src, key + ".name", s.name);
        std::set<std::string> labels;
        for (std::size_t v = 0; v < s.values.size(); ++v)
        {
          const std::string label = s.parameter + "=" + value_label(s.values[v]);
          check_name(src, key + ".values[" + std::to_string(v) + "]", "fe_" + s.name + "_" + label);
          if (!labels.insert(label).second)
            throw InputError(src, key + ".values[" + std::to_string(v) + "]",
                             value_label(s.values[v]), "values that differ from each other",
                             "two cases of sweep '" + s.name + "' would share the folder " +
                               label);
        }
      }
    }

    /// Every MBD run gets its own folders under mbd/: NAME, and NAME_band for a run with a
    /// confidence band.
    void check_mbd_run_names(const std::string &src, const std::vector<MbdRun> &runs)
    {
      std::set<std::string> names;
      for (std::size_t i = 0; i < runs.size(); ++i)
      {
        const MbdRun &m = runs[i];
        const std::string key = "mbd_runs[" + std::to_string(i) + "]";
        check_name(src, key + ".name", "mbd_" + m.name + "_band");
        for (const std::string &folder :
             m.band ? std::vector<std::string>{m.name, m.name + "_band"}
                    : std::vector<std::string>{m.name})
          if (!names.insert(folder).second)
            throw InputError(src, key + ".name", m.name, "a name not used by another MBD run",
                             "two runs would write into the same folder mbd/" + folder);
      }
    }
  } // namespace

  void PipelineRunner::check_output_root() const
  {
    const std::string &src = config_.source;
    const std::string root = config_.output_root.empty() ? "." : config_.output_root;
    if (first_invalid_utf8(root) != std::string::npos)
      throw InputError(src, "output_root", "(a path with bytes that are not UTF-8)",
                       "a UTF-8 path", "paths are written into JSON manifests and summaries");
    check_name(src, "run", config_.run);
    // The nearest existing ancestor must be a writable directory; an existing root or run
    // folder must be a directory.
    std::error_code ec;
    fs::path p = fs::absolute(root, ec);
    for (const fs::path &must_be_dir : {p, p / config_.run})
      if (fs::exists(must_be_dir, ec) && !fs::is_directory(must_be_dir, ec))
        throw InputError(src, must_be_dir == p ? "output_root" : "run", must_be_dir.string(),
                         "a directory (or a path that can be created)",
                         "it exists and is not a directory");
    while (!p.empty() && !fs::exists(p, ec))
      p = p.parent_path();
    if (p.empty() || !fs::is_directory(p, ec) || ::access(p.c_str(), W_OK | X_OK) != 0)
      throw InputError(src, "output_root", root, "a directory this user can write",
                       "cannot create folders in " + p.string());
    // The longest path the run writes must fit PATH_MAX (with room for the suffixes above).
    std::size_t longest = 0;
    for (const auto &s : config_.fe_sweeps)
      for (const double v : s.values)
        longest = std::max(longest, std::string("/scenes/fe_" + s.name + "_" + s.parameter +
                                                "=" + value_label(v) + ".yaml")
                                      .size());
    for (const auto &m : config_.mbd_runs)
      longest = std::max(longest, ("/mbd/" + m.name + "_band/n_high/").size() + 64);
    const std::size_t total = run_dir().size() + longest + name_suffix_room;
    if (total > PATH_MAX)
      throw InputError(src, "output_root", root,
                       "a path short enough that the run's files fit in " +
                         std::to_string(PATH_MAX) + " bytes",
                       "the longest path of this run would be about " + std::to_string(total) +
                         " bytes");
  }

  /// The steps of check() after the names: each generated scene (and fit command) handed to
  /// its stage's own --check in a scratch folder, a failure traced back to the pipeline key
  /// that produced the value.
  class PipelineRunner::Checker
  {
  public:
    explicit Checker(PipelineRunner &runner)
      : runner_(runner)
      , config_(runner.config_)
      , src_(runner.config_.source)
      , stand_ins_(scratch_.path(), runner.config_.fe_sweeps)
    {
    }

    /// Each FE case's scene: base + preset + overrides + its value.
    void fe_cases()
    {
      for (std::size_t i = 0; i < config_.fe_sweeps.size(); ++i)
      {
        const FeSweep &sweep = config_.fe_sweeps[i];
        const std::string key = config_.fe_sweeps_key + "[" + std::to_string(i) + "]";
        for (std::size_t v = 0; v < sweep.values.size(); ++v)
        {
          std::vector<int> unused;
          nlohmann::json scene = runner_.fe_case_scene(sweep, sweep.values[v], true, unused);
          // A mesh a mesh task will make does not exist yet: check the rest of the scene (the
          // mesh is checked against the scene when the FE case runs).
          const nlohmann::json *mesh = find_key_path(scene, "geometry.mesh");
          if (mesh && mesh->is_string() && !fs::exists(mesh->get<std::string>()))
            scene["geometry"].erase("mesh");
          const std::string label = sweep.parameter + "=" + value_label(sweep.values[v]);
          const std::string file = write_scene("fe_" + sweep.name + "_" + label + ".yaml", scene);
          std::vector<Origin> origins = fe_origins(key, sweep.overrides, sweep.preset_overrides);
          origins.push_back({sweep.key, key + ".values[" + std::to_string(v) + "]",
                             sweep.keywords[v].empty() ? nlohmann::json(sweep.values[v])
                                                       : nlohmann::json(sweep.keywords[v])});
          add_scene_check("fe_stage", file, origins, key + ".scene",
                          "FE case " + sweep.name + " " + label + " (scene " + sweep.scene + ")");
        }
      }
    }

    /// The fit commands the run will give (fit_stage --check): the data files do not exist
    /// yet, so this checks the options the pipeline and its preset put on the command line
    /// (the weighting, the range policy, the preset's measured discretisation error, the
    /// family's parameter and values).
    void fit_commands()
    {
      for (std::size_t i = 0; i < config_.fe_sweeps.size(); ++i)
      {
        const FeSweep &sweep = config_.fe_sweeps[i];
        const std::string key = config_.fe_sweeps_key + "[" + std::to_string(i) + "]";
        const std::vector<std::string> mesh_error = runner_.discretisation_error_args(sweep.name);
        const std::vector<Origin> origins = fit_origins(sweep, key, mesh_error);
        std::vector<std::string> fit_args = {scratch_.file("fe_" + sweep.name + ".csv"),
                                             "--output", scratch_.file("law.json"), "--weighting",
                                             config_.fit_weighting, "--no-plots"};
        fit_args.insert(fit_args.end(), mesh_error.begin(), mesh_error.end());
        add_stage_check("fit_stage", fit_args, scratch_.file("fit_" + sweep.name + ".log"), origins,
                        key, "the fit of sweep " + sweep.name);
        if (sweep.values.size() < 2)
          continue;
        std::vector<std::string> family_args = {"--family", sweep.parameter};
        for (std::size_t v = 0; v < sweep.values.size(); ++v)
          family_args.push_back(
            scratch_.file("fe_" + sweep.name + "_" + std::to_string(v) + ".csv") + "=" +
            value_label(to_si(sweep.values[v], sweep.unit).value));
        for (const auto &a : std::vector<std::string>{
               "--parameter-unit", to_si(1.0, sweep.unit).unit, "--family-out-of-range",
               config_.family_out_of_range, "--output", scratch_.file("family.json"),
               "--weighting", config_.fit_weighting, "--no-plots"})
          family_args.push_back(a);
        family_args.insert(family_args.end(), mesh_error.begin(), mesh_error.end());
        add_stage_check("fit_stage", family_args, scratch_.file("family_" + sweep.name + ".log"),
                        origins, key, "the law family of sweep " + sweep.name);
      }
    }

    /// The FE impact study's scene, that it is one (study: impact), and a law given as a file
    /// (a fitted one is checked when impact_compare runs).
    void impact()
    {
      const nlohmann::json scene = runner_.impact_scene();
      const std::string file = write_scene("fe_impact.yaml", scene);
      add_scene_check("fe_stage", file,
                      fe_origins("impact", config_.impact->overrides,
                                 config_.impact->preset_overrides),
                      "impact.scene", "FE impact study (scene " + config_.impact->scene + ")");
      const nlohmann::json *study = find_key_path(scene, "study");
      if (!study || !study->is_string() || study->get<std::string>() != "impact")
        throw InputError(src_, "impact.scene", config_.impact->scene,
                         "a scene with study: impact");
      if (config_.impact->deformable)
        impact_deformable();
      if (config_.impact->law.file)
        try
        {
          laws::read_law_file(*config_.impact->law.file);
        }
        catch (const InputError &e)
        {
          throw InputError(src_, "impact.law.file", *config_.impact->law.file,
                           "a readable law file (clearjoint.law/1)", e.what());
        }
    }

    /// The deformable-journal impact's scene (impact.deformable): it exists, is readable, is an
    /// impact scene whose journal is deformable (else it would repeat the rigid variant), and
    /// fe_stage accepts it with the preset's and the block's overrides (a journal-mass key with
    /// the deformable journal is fe_stage's input error, named there).
    void impact_deformable()
    {
      const DeformableImpact &d = *config_.impact->deformable;
      std::error_code ec;
      if (!fs::is_regular_file(d.scene, ec))
        throw InputError(src_, "impact.deformable.scene", d.scene,
                         "an existing FE scene file (clearjoint.fe/1) with study: impact",
                         "no such file (relative paths are taken from the folder run_pipeline "
                         "runs in)");
      nlohmann::json scene;
      try
      {
        scene = runner_.impact_deformable_scene();
      }
      catch (const InputError &e)
      {
        throw InputError(src_, "impact.deformable.scene", d.scene,
                         "a readable FE scene (clearjoint.fe/1)", e.what());
      }
      const nlohmann::json *study = find_key_path(scene, "study");
      if (!study || !study->is_string() || study->get<std::string>() != "impact")
        throw InputError(src_, "impact.deformable.scene", d.scene, "a scene with study: impact",
                         "its study is " + (study ? json_excerpt(*study) : "radial (not stated)"));
      const nlohmann::json *journal = find_key_path(scene, "loading.journal");
      if (!journal || !journal->is_string() || journal->get<std::string>() == "rigid")
        throw InputError(src_, "impact.deformable.scene", d.scene,
                         "a scene with a deformable journal (loading.journal: end_faces or "
                         "axis_line)",
                         "its journal is " +
                           (journal ? json_excerpt(*journal) : "rigid (not stated: the default)") +
                           "; the rigid journal is impact.scene's");
      const std::string file = write_scene("fe_impact_deformable.yaml", scene);
      std::vector<Origin> origins = preset_origins("fe");
      for (const auto &[k, val] : d.overrides)
        origins.push_back({k, "impact.deformable.overrides." + k, val});
      add_scene_check("fe_stage", file, origins, "impact.deformable.scene",
                      "FE impact study, deformable journal (scene " + d.scene + ")");
    }

    /// The FE rolling study's scene: it exists, is readable, is a rolling scene, and fe_stage
    /// accepts it with the preset's `fe` map, rolling.overrides and rolling.presets.<preset>.
    void rolling()
    {
      const std::string &base = config_.rolling->scene;
      std::error_code ec;
      if (!fs::is_regular_file(base, ec))
        throw InputError(src_, "rolling.scene", base,
                         "an existing FE scene file (clearjoint.fe/1) with study: rolling",
                         "no such file (relative paths are taken from the folder run_pipeline "
                         "runs in)");
      nlohmann::json scene;
      try
      {
        scene = runner_.rolling_scene();
      }
      catch (const InputError &e)
      {
        throw InputError(src_, "rolling.scene", base, "a readable FE scene (clearjoint.fe/1)",
                         e.what());
      }
      // Before fe_stage's check: a scene of another study (or none, which is radial) would
      // pass it and then run the wrong study.
      const nlohmann::json *study = find_key_path(scene, "study");
      if (!study || !study->is_string() || study->get<std::string>() != "rolling")
        throw InputError(src_, "rolling.scene", base, "a scene with study: rolling",
                         "its study is " + (study ? json_excerpt(*study) : "radial (not stated)"));
      const std::string file = write_scene("fe_rolling.yaml", scene);
      const std::vector<Origin> origins =
        fe_origins("rolling", config_.rolling->overrides, config_.rolling->preset_overrides);
      add_scene_check("fe_stage", file, origins, "rolling.scene",
                      "FE rolling study (scene " + base + ")");
    }

    /// Each MBD run's scene with its laws (stand-ins for the fitted ones).
    void mbd_runs()
    {
      for (std::size_t i = 0; i < config_.mbd_runs.size(); ++i)
      {
        const MbdRun &m = config_.mbd_runs[i];
        const std::string key = "mbd_runs[" + std::to_string(i) + "]";
        std::vector<Origin> origins = preset_origins("mbd");
        Overrides overrides = m.overrides;
        for (const auto &[k, val] : m.overrides)
          origins.push_back({k, key + ".overrides." + k, val});
        for (std::size_t l = 0; l < m.laws.size(); ++l)
        {
          const std::string law = stand_ins_.for_choice(m.laws[l]);
          overrides.emplace_back(m.laws[l].key, law);
          origins.push_back({m.laws[l].key, key + ".laws[" + std::to_string(l) + "]",
                             m.laws[l].file ? nlohmann::json(*m.laws[l].file)
                                            : nlohmann::json("sweep " + *m.laws[l].sweep)});
        }
        const nlohmann::json scene = compose_scene(config_, m.scene, "mbd", overrides);
        const std::string file = write_scene("mbd_" + m.name + ".yaml", scene);
        add_scene_check("mbd_stage", file, origins, key + ".scene",
                        "MBD run " + m.name + " (scene " + m.scene + ")");
      }
    }

    /// Waits for the stages' checks; the first failure among them, in the order above, is
    /// thrown (StageChecks). The checks of the pipeline file's own keys throw at once.
    void finish() { checks_.finish(); }

  private:
    /// Writes a generated scene into the scratch folder; returns its path.
    std::string write_scene(const std::string &name, const nlohmann::json &scene) const
    {
      const std::string file = scratch_.file(name);
      write_file_atomically(file, json_text(scene) + "\n");
      return file;
    }

    /// The chosen preset's keys for `stage` ("fe" or "mbd"), as origins of scene keys.
    std::vector<Origin> preset_origins(const std::string &stage) const
    {
      std::vector<Origin> origins;
      const auto preset = config_.presets.find(config_.preset);
      if (preset != config_.presets.end())
        for (const auto &[key, value] : preset->second)
          if (key.rfind(stage + ":", 0) == 0)
            origins.push_back({key.substr(stage.size() + 1),
                               "presets." + config_.preset + "." + stage + "." +
                                 key.substr(stage.size() + 1),
                               value});
      return origins;
    }

    /// The pipeline keys behind an FE scene built as overrides_for_preset() builds it, in the
    /// order they are set: the chosen preset's `fe` map, then the block's (`key`: a sweep's,
    /// the impact or the rolling study's) `overrides` and its `presets.<chosen preset>`.
    std::vector<Origin> fe_origins(const std::string &key, const Overrides &overrides,
                                   const PresetOverrides &preset_overrides) const
    {
      std::vector<Origin> origins = preset_origins("fe");
      for (const auto &[k, val] : overrides)
        origins.push_back({k, key + ".overrides." + k, val});
      const auto own = preset_overrides.find(config_.preset);
      if (own != preset_overrides.end())
        for (const auto &[k, val] : own->second)
          origins.push_back({k, key + ".presets." + config_.preset + "." + k, val});
      return origins;
    }

    /// The pipeline keys behind the options of a sweep's fit commands.
    std::vector<Origin> fit_origins(const FeSweep &sweep, const std::string &key,
                                    const std::vector<std::string> &mesh_error) const
    {
      return {{"--weighting", "fit.weighting", config_.fit_weighting},
              {"--family-out-of-range", "fit.family_out_of_range", config_.family_out_of_range},
              {"--discretisation-error",
               "presets." + config_.preset + ".measured.error_F_max." + sweep.name + ".percent",
               mesh_error.size() > 1 ? nlohmann::json(std::stod(mesh_error[1]))
                                     : nlohmann::json()},
              {"--family", key + ".parameter.name", sweep.parameter},
              {"--parameter-unit", key + ".parameter.unit", sweep.unit}};
    }

    void add_scene_check(const std::string &stage, const std::string &scene_file,
                         const std::vector<Origin> &origins, const std::string &base_key,
                         const std::string &what)
    {
      add_stage_check(stage, {scene_file}, scene_file + ".log", origins, base_key, what);
    }

    void add_stage_check(const std::string &stage, std::vector<std::string> args,
                         const std::string &log_path, const std::vector<Origin> &origins,
                         const std::string &base_key, const std::string &what)
    {
      checks_.add({stage, runner_.stage_executable(stage), src_}, std::move(args), log_path,
                  origins, base_key, what);
    }

    PipelineRunner &runner_;
    const PipelineConfig &config_;
    const std::string &src_;
    const Scratch scratch_;
    StandInLaws stand_ins_;
    StageChecks checks_{machine_cores()};  ///< after scratch_: ended before it is removed
  };

  void PipelineRunner::check()
  {
    check_output_root();
    // The Slurm commands and a controller that answers, before anything is written.
    if (options_.executor.value_or(config_.executor.kind) == "slurm")
      SlurmExecutor::check_available(config_.executor.slurm, config_.source);
    check_fe_sweep_names(config_);
    check_mbd_run_names(config_.source, config_.mbd_runs);
    Checker checker(*this);
    checker.fe_cases();
    checker.fit_commands();
    if (config_.impact)
      checker.impact();
    if (config_.rolling)
      checker.rolling();
    checker.mbd_runs();
    checker.finish();
    log::info("run_pipeline: checked " + config_.source + ": every generated scene is valid");
  }
} // namespace clearjoint::pipeline
