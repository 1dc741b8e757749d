// pipeline.yaml, schema clearjoint.pipeline/1: which FE studies to sweep, which MBD scenes to
// run with which fitted laws, and the presets. See the committed pipeline.yaml for every key.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct FeStudy
  {
    std::string name;             ///< e.g. "thickness"; output folder name
    std::string scene;            ///< base FE scene file (clearjoint.fe/1)
    std::string parameter;        ///< law-family parameter name, e.g. "t_B"
    std::string unit;             ///< its SI unit, e.g. "m"
    std::string key;              ///< key path in the scene that the sweep sets
    std::vector<double> values;   ///< SI
  };

  /// Which law an MBD scene gets, and where in the scene it goes.
  struct LawChoice
  {
    std::string key;                    ///< key path in the MBD scene, e.g. "contact.law_file"
    std::optional<std::string> file;    ///< a law file given directly (no FE)
    std::optional<std::string> study;   ///< a fitted law: study name ...
    std::optional<double> value;        ///< ... and parameter value; without a value, the family
  };

  struct MbdRun
  {
    std::string name;
    std::string scene;                  ///< MBD scene file (clearjoint.mbd/1)
    std::vector<LawChoice> laws;        ///< zero or more law substitutions
    /// Also run the scene with the law's 95 % confidence-band variants (laws/confidence_band.h);
    /// needs exactly one law, a fitted one (study + value).
    bool band = false;
  };

  struct PipelineConfig
  {
    std::string source;                 ///< the pipeline file
    std::string run;                    ///< results go to <output_root>/<run>/
    std::string output_root;
    std::string preset;                 ///< fast | standard | accurate
    int mpi_ranks = 1;
    /// preset → stage ("fe" | "mbd") → key path → value, applied to every generated scene.
    std::map<std::string, std::map<std::string, nlohmann::json>> presets;
    std::vector<FeStudy> fe_studies;
    std::string fit_weighting = "absolute";
    std::vector<MbdRun> mbd_runs;
    bool report = true;
  };

  /// Strict reading: unknown keys, missing keys, a wrong schema, an MBD law naming a study that
  /// does not exist or a value not in that study → InputError naming the key and valid range.
  /// Relative paths are taken relative to base_dir (the directory run_pipeline runs in).
  PipelineConfig read_pipeline_config(const std::string &path);

  /// Sets "a.b.c" in a JSON object, creating intermediate objects; throws InputError if a
  /// non-object is in the way.
  void set_key_path(nlohmann::json &root, const std::string &key_path, const nlohmann::json &value,
                    const std::string &source);

  /// "0.004" for 0.004, "%.6g" (names of output folders).
  std::string value_label(double value);
} // namespace clearjoint::pipeline
