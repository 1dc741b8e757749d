// pipeline.yaml, schema clearjoint.pipeline/1: which FE sweeps to run (one scene key over
// values, each case fitted, a law family over them), which MBD scenes to run with which fitted
// laws, and the presets. See docs/pipeline.md for every key.
//
// "Study" is fe_stage's word for what a scene computes (its `study:` key: radial,
// misalignment, hertz, patch, impact, rolling); a *sweep* here runs one such scene over the
// values of one of its keys. Files written before the rename say `fe_studies:` and, in a law
// choice, `study:`; both are still read, with a warning naming the new key.
#pragma once

#include "common/key_path.h"
#include "pipeline/executor_config.h"

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace clearjoint::pipeline
{
  /// Scene key path → value, applied in order.
  using Overrides = std::vector<std::pair<std::string, nlohmann::json>>;

  /// A block's `presets.<p>`: preset name → scene settings set after the block's `overrides`
  /// when preset p runs. Empty: the global presets alone. Given, it names every preset (a
  /// preset left out would run the block on settings nobody measured for it); an entry given
  /// as null is empty.
  using PresetOverrides = std::map<std::string, Overrides>;

  /// What a block (an FE sweep, the rolling study) sets after the preset's `fe` map when
  /// `preset` runs, in order: its `overrides`, then its `presets.<preset>` (if any).
  Overrides overrides_for_preset(const Overrides &overrides,
                                 const PresetOverrides &preset_overrides,
                                 const std::string &preset);

  /// The keyword a sweep's `values` (and a law's `value`) may hold instead of a number:
  /// θ_max of the sweep's scene geometry (paper Eq. 3), see sweep_values.h.
  inline constexpr const char *theta_max_keyword = "theta_max";

  /// One entry of `fe_sweeps`: an FE scene run once per value of one of its keys; the cases'
  /// curves are fitted, one law per value and a law family over the values.
  struct FeSweep
  {
    std::string name;             ///< e.g. "thickness"; output folder name
    std::string scene;            ///< base FE scene file (clearjoint.fe/1)
    std::string parameter;        ///< law-family parameter name, e.g. "t_B"
    std::string unit;             ///< the unit of `values` and of the scene key, e.g. "m", "deg"
    std::string key;              ///< key path in the scene that the sweep sets
    /// In `unit`. Where the file gives a keyword (keywords[i] non-empty) the value is NaN until
    /// resolve_value_keywords() (sweep_values.h) replaces it with the number.
    std::vector<double> values;
    std::vector<std::string> keywords;  ///< parallel to values: "" or e.g. "theta_max"
    /// Set in every case's scene after the preset's overrides (e.g. geometry.mesh).
    Overrides overrides;
    /// `presets.<p>`: set in every case's scene after `overrides` when preset p runs (e.g. the
    /// adaptive cycles of a sweep whose scene does not converge on the presets' uniform
    /// levels); see PresetOverrides.
    PresetOverrides preset_overrides;
    /// Extra `gmsh -setnumber NAME VALUE` when the scene's geometry.mesh names a .geo file
    /// (the scene's geometry keys R_B, t_B, L_B, c_r, c_a are always passed) [SI].
    std::map<std::string, double> mesh_parameters;
  };

  /// Which law an MBD scene gets, and where in the scene it goes.
  struct LawChoice
  {
    std::string key;                    ///< key path in the MBD scene, e.g. "contact.law_file"
    std::optional<std::string> file;    ///< a law file given directly (no FE)
    std::optional<std::string> sweep;   ///< a fitted law: sweep name (key `sweep`) ...
    std::optional<double> value;        ///< ... and parameter value; without a value, the family
    std::string value_keyword;          ///< "" or the sweep's keyword (value set on resolution)
  };

  struct MbdRun
  {
    std::string name;
    std::string scene;                  ///< MBD scene file (clearjoint.mbd/1)
    std::vector<LawChoice> laws;        ///< zero or more law substitutions
    Overrides overrides;                ///< set after the preset, before the laws
    /// Also run the scene with the law's 95 % confidence-band variants (laws/confidence_band.h);
    /// needs exactly one law, a fitted one (sweep + value).
    bool band = false;
  };

  /// The impact study's second variant (issue 31 item 2): both bodies deformable, as the paper
  /// modelled them — an impact scene whose journal is meshed and free (loading.journal
  /// end_faces or axis_line: its mass the FE mass matrix's), run as its own fe_stage task
  /// (fe/impact_deformable) and compared with the same law (impact/compare_deformable).
  struct DeformableImpact
  {
    std::string scene;                  ///< FE scene file with study: impact, a deformable journal
    /// Set in the scene after the preset's `fe` overrides (e.g. mesh.global_refinements: 0 to
    /// keep the deformable impact on the coarse mesh whatever the preset).
    Overrides overrides;
  };

  /// The FE impact study (issue 12): one fe_stage run of an impact scene (its sweep.velocity
  /// lists the velocities), compared with the MBD contact law `law` (impact_compare); and,
  /// optionally, the same with the journal deformable (`deformable`).
  struct ImpactStudy
  {
    std::string scene;                  ///< FE scene file with study: impact
    /// Set in the rigid journal's scene after the preset's `fe` overrides (e.g. its own
    /// adaptive mesh keys, which the preset's `fe` map would set in every FE task).
    Overrides overrides;
    /// `presets.<p>`: set in that scene after `overrides` when preset p runs; see
    /// PresetOverrides.
    PresetOverrides preset_overrides;
    LawChoice law;                      ///< the law of the same geometry (key unused)
    std::optional<DeformableImpact> deformable;  ///< absent: the scene's journal only
  };

  /// The FE rolling study (issue 13, paper §3.4): one fe_stage run of a scene with
  /// study: rolling (the bearing turning, the journal pushed and spun by friction). Nothing
  /// downstream uses its results; the report has its own section.
  struct RollingStudy
  {
    std::string scene;                  ///< FE scene file with study: rolling
    /// Set in the scene after the preset's `fe` overrides (e.g. mesh.global_refinements: 0 to
    /// keep the rolling mesh coarse whatever the preset).
    Overrides overrides;
    /// `presets.<p>`: set in the scene after `overrides` when preset p runs (e.g. the mesh
    /// level and rolling.n_steps of a rolling case whose cost the presets' `fe` maps cannot
    /// set without changing every other FE task); see PresetOverrides.
    PresetOverrides preset_overrides;
  };

  /// A preset's measured estimated error of F(δ_max) for one FE sweep (or the impact or
  /// rolling study).
  struct PresetError
  {
    std::optional<double> percent;      ///< [%]; nullopt: not yet measured
    std::string where;                  ///< how and where it was measured
  };

  /// What a preset costs and how accurate it is, as measured (docs/benchmarks.md).
  struct PresetMeasured
  {
    std::string note;                        ///< where the numbers come from
    std::optional<double> fe_dofs;           ///< [1] DoFs of the reference FE case
    std::optional<double> fe_case_time;      ///< [s] one reference FE curve
    std::optional<double> impact_time;       ///< [s] the FE impact study (its one task)
    /// [s] the deformable-journal impact study (its one task, impact.deformable)
    std::optional<double> impact_deformable_time;
    std::optional<double> rolling_time;      ///< [s] the FE rolling study (its one task)
    std::optional<double> pipeline_time;     ///< [s] the whole default pipeline
    /// sweep name, impact, impact_deformable, rolling → error
    std::map<std::string, PresetError> error_F_max;
    /// FE sweep name → [s] one FE case of that sweep, where it differs from fe_case_time (which
    /// is the thickness sweep's reference case): e.g. the misalignment sweep's.
    std::map<std::string, double> case_times;
    /// FE sweep name, impact, impact_deformable, rolling → [1] DoFs of its reference case.
    std::map<std::string, double> dofs;
    std::string date;                        ///< when measured ("" not stated)
    std::string machine_cpu;                 ///< the CPU model it was measured on ("" not stated)
    std::optional<int> machine_cores;        ///< [1] that machine's cores
  };

  struct PipelineConfig
  {
    std::string source;                 ///< the pipeline file
    std::string run;                    ///< results go to <output_root>/<run>/
    std::string output_root;
    std::string preset;                 ///< fast | standard | accurate
    int mpi_ranks = 1;
    /// Tasks at once (executor_config.h); nullopt: the executor's default (local: the
    /// machine's cores; slurm: default_slurm_jobs). `run_pipeline --jobs` overrides.
    std::optional<int> jobs;
    ExecutorConfig executor;            ///< local (default) or slurm; `--executor` overrides kind
    /// preset → stage ("fe" | "mbd") → key path → value, applied to every generated scene.
    std::map<std::string, std::map<std::string, nlohmann::json>> presets;
    std::map<std::string, PresetMeasured> preset_measured;  ///< preset → measurements
    std::vector<FeSweep> fe_sweeps;
    /// The key the file gave them under: "fe_sweeps", or the deprecated "fe_studies" (messages
    /// name the key as written).
    std::string fe_sweeps_key = "fe_sweeps";
    std::string fit_weighting = "absolute";
    /// fit_stage --family-out-of-range: what a law family does for a parameter outside its values.
    std::string family_out_of_range = "error";
    std::vector<MbdRun> mbd_runs;
    std::optional<ImpactStudy> impact;  ///< absent: no impact study
    std::optional<RollingStudy> rolling;  ///< absent: no rolling study
    bool report = true;
  };

  inline const std::vector<std::string> &preset_names()
  {
    static const std::vector<std::string> names = {"fast", "standard", "accurate"};
    return names;
  }

  /// What a case of `sweep` sets after the preset's `fe` map, in order: the sweep's
  /// `overrides`, then its `presets.<preset>` (the swept key comes last, per case).
  Overrides sweep_overrides(const FeSweep &sweep, const std::string &preset);

  /// What the rolling study's scene sets after the preset's `fe` map, in order: the block's
  /// `overrides`, then its `presets.<preset>`.
  Overrides rolling_overrides(const RollingStudy &rolling, const std::string &preset);
  /// The rigid journal's impact scene's settings when `preset` runs: impact.overrides, then
  /// impact.presets.<preset>.
  Overrides impact_overrides(const ImpactStudy &impact, const std::string &preset);

  /// Strict reading: unknown keys, missing keys, a wrong schema, an MBD law naming a sweep that
  /// does not exist or a value not in that sweep → InputError naming the key and valid range.
  /// A deprecated key (`fe_studies`, a law's `study`) is read with one warning line (log.h)
  /// naming its new name; a file giving both the old and the new key is an InputError.
  /// Relative paths are taken relative to the directory run_pipeline runs in; override values
  /// that name an existing file from there are made absolute. Keywords in `values` are kept
  /// (NaN); resolve_value_keywords() (sweep_values.h) fills them in once the preset is known.
  PipelineConfig read_pipeline_config(const std::string &path);

  /// The shortest text that reads back as exactly `value` ("0.004", "1.5",
  /// "3.2842262350456..." for θ_max): names of output folders and law labels.
  std::string value_label(double value);
} // namespace clearjoint::pipeline
