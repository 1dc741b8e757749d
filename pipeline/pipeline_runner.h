// Turns a PipelineConfig into tasks (meshes → FE cases → fits → law families → MBD scenes →
// report) and runs them, reusing every task whose inputs are unchanged.
#pragma once

#include "pipeline/pipeline_config.h"
#include "pipeline/presets.h"
#include "pipeline/run_eta.h"
#include "pipeline/scheduler.h"
#include "pipeline/task_graph.h"
#include "pipeline/task_runner.h"

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

namespace clearjoint::pipeline
{
  struct RunOptions
  {
    std::string build_dir;              ///< where fe_stage/, fit_stage/, mbd_stage/ were built
    bool force = false;                 ///< re-run every task
    std::optional<std::string> only;    ///< fe | fit | mbd | report
    bool plots = true;
    std::optional<int> jobs;            ///< --jobs: overrides pipeline.yaml `jobs`
    std::optional<std::string> executor;  ///< --executor local|slurm: overrides executor.kind
  };

  class PipelineRunner
  {
  public:
    /// The config's value keywords must be resolved (resolve_value_keywords, sweep_values.h).
    PipelineRunner(PipelineConfig config, RunOptions options);
    /// Runs everything; returns the summary written to <run dir>/pipeline_summary.json.
    nlohmann::json run();
    std::string run_dir() const;
    /// Validates the whole run before anything is written (pipeline_check.cc): names and the
    /// output root usable, and every generated FE and MBD scene accepted by its stage's own
    /// reader (STAGE --check). Throws InputError naming the pipeline key; writes nothing
    /// under the output root.
    void check();

  private:
    struct Done
    {
      std::string path;  ///< the result file
      int node;          ///< the task behind it (graph_)
    };
    /// Sweep name → value label → fitted law; sweep name → law family.
    using LawsBySweep = std::map<std::string, std::map<std::string, Done>>;
    struct FittedLaws
    {
      LawsBySweep laws;
      std::map<std::string, Done> families;
    };
    /// One FE case as the sweep's family and summary need it.
    struct FeCase
    {
      int fe_node;           ///< its fe_stage task
      std::string csv;       ///< the force–penetration curve it writes
      /// its manifest, whose own error estimate becomes its laws' discretisation error where the
      /// preset has no measured figure for the sweep (adaptive meshes only; else empty)
      std::string own_estimate_manifest;
      nlohmann::json summary;  ///< its entry in the summary's sweep
    };

    // The steps of run(), in order.
    /// The summary's header: run, preset, presets, pipeline file, empty lists.
    void start_summary();
    /// Composes (dry run) every FE case's scene, so a bad one stops the run before any work.
    void check_fe_case_scenes();
    /// One FE sweep: a case and its fit per value, and a law family over >= 2 values.
    void add_fe_sweep(const FeSweep &sweep, FittedLaws &fitted);
    /// Value `i` of the sweep: its scene, fe_stage task and the fit of its curve.
    FeCase add_fe_case(const FeSweep &sweep, std::size_t i,
                       const std::vector<std::string> &mesh_error_args, FittedLaws &fitted);
    /// fit_stage --family over the sweep's curves; returns the family file and its task.
    Done add_family_fit(const FeSweep &sweep, const std::string &family_unit,
                        const std::vector<std::string> &family_args,
                        const std::vector<std::string> &mesh_error_args,
                        const std::vector<std::string> &family_inputs,
                        const std::vector<int> &family_deps);
    /// One MBD run: its scene with the chosen laws, its task, and its band tasks once the
    /// fitted law exists (m.band).
    void add_mbd_run(const MbdRun &m, const FittedLaws &fitted);
    /// Runs the graph on the executor asked for, then records the tasks in the summary.
    void execute_tasks();

    /// The scene of one FE case (base + preset + sweep overrides + the swept value), with a
    /// .geo in geometry.mesh replaced by the mesh its task writes (dry_run: checked only).
    nlohmann::json fe_case_scene(const FeSweep &sweep, double value, bool dry_run,
                                 std::vector<int> &after);
    /// One fe_stage run of a composed scene (written to `scene`) into <run>/<name>; the files
    /// the scene names join its inputs when it starts (add).
    Task fe_stage_task(const std::string &scene, const std::string &name,
                       const std::string &stage) const;
    /// The FE impact study and its comparison with the MBD law (config_.impact), and its
    /// deformable-journal variant (impact.deformable) if given.
    void run_impact(const LawsBySweep &laws);
    /// One impact variant: the fe_stage task of `scene_json` (written as
    /// scenes/fe_impact<suffix>.yaml) into fe/impact<suffix>, its impact_compare against `law`
    /// (after the task `law_node` that fits it, if any) into impact/compare<suffix>, and the
    /// summary's entry impact<suffix>. Stage fe_impact<suffix> (its own measured time).
    void add_impact_variant(const nlohmann::json &scene_json, const std::string &base,
                            const std::string &suffix, const std::string &law,
                            std::optional<int> law_node);
    /// The rigid journal's impact scene: base scene, the preset's `fe` overrides,
    /// impact.overrides, impact.presets.<preset>.
    nlohmann::json impact_scene() const;
    /// The deformable impact's scene: base scene, the preset's `fe` overrides,
    /// impact.deformable.overrides.
    nlohmann::json impact_deformable_scene() const;
    /// The FE rolling study (config_.rolling): one fe_stage task, fe/rolling. It is a first
    /// step (docs/fe.md): a failure of it is recorded in the summary (status, message, where
    /// its partial output is) and the run goes on; run_pipeline then exits 2 after the report.
    void run_rolling();
    /// The rolling study's scene: base scene, the preset's `fe` overrides, rolling.overrides,
    /// rolling.presets.<preset>.
    nlohmann::json rolling_scene() const;
    /// Writes a composed scene to <run>/scenes/<name>.yaml.
    std::string write_scene(const nlohmann::json &scene, const std::string &base,
                            const std::string &name);
    /// Adds a task to the graph (run later by the scheduler); returns its id. `scene`: the
    /// composed scene the task runs, whose named files join its inputs when it starts.
    int add(const Task &task, const std::string &stage_group, std::vector<int> after,
            int ranks = 1, const nlohmann::json &scene = nullptr);
    /// When FE case `node` (value `label` of `sweep`) ends: logs fe_stage's own estimate of
    /// the error of F(delta_max) if the case ran adaptive cycles, and keeps it for the sweep's
    /// line at the end of the run and the summary (log_own_estimates).
    void watch_own_estimate(int node, const std::string &sweep, const std::string &label,
                            const std::string &fe_dir);
    /// After the tasks: one line per sweep with the run's own estimates beside the preset's
    /// measured figure, and each case's estimate in the summary (own_error_F_max).
    void log_own_estimates();
    /// Sets the chosen preset's measured time of task `node` (of FE sweep `sweep`, if any):
    /// printed beside its time when it ends and written into the summary (presets.h).
    void attach_figure(int node, const std::string &sweep = "");
    /// The band variants of MBD run `m` (entry `index` of the summary's mbd_runs), once the
    /// fitted law at `law_path` exists: one MBD task each, after the fit `fit_node`.
    void add_band_tasks(const MbdRun &m, std::size_t index, const Task &mbd,
                        const std::string &law_path, int fit_node);
    /// The executor pipeline.yaml and the command line ask for (`executor`, `jobs`).
    std::unique_ptr<Executor> make_executor() const;
    /// The summary's task list, in the order the tasks were added.
    void record_tasks(const Scheduler &scheduler);
    /// fit_stage's --discretisation-error arguments from the chosen preset's measured error
    /// of F for this sweep; none when it is not measured.
    std::vector<std::string> discretisation_error_args(const std::string &sweep) const;
    /// Tasks per stage this run will execute or reuse (for "task k of N").
    std::map<std::string, int> planned_tasks() const;
    /// The chosen preset's measured fe_case_time, pipeline_time, impact_time,
    /// impact_deformable_time or rolling_time [s], if measured.
    std::optional<double> preset_time(const std::string &which) const;
    void check_output_root() const;
    class Checker;  ///< the steps of check() after the names (pipeline_check.cc)
    std::string stage_executable(const std::string &stage) const;

    PipelineConfig config_;
    RunOptions options_;
    nlohmann::json summary_;
    TaskGraph graph_;
    std::map<std::string, Done> meshes_;  ///< mesh task output folder → its .msh
    std::set<std::string> planned_meshes_;  ///< mesh task folders found by the dry run
    /// sweeps whose cases run adaptive meshes (the dry run): their laws carry the cases' own
    /// error estimate where the preset has no figure
    std::set<std::string> adaptive_sweeps_;
    std::unique_ptr<RunEta> eta_;
    /// Sweep name → value label → fe_stage's own estimate of the error of F(delta_max), from
    /// each adaptive case's manifest as its task ends (watch_own_estimate).
    std::map<std::string, std::map<std::string, OwnErrorEstimate>> own_estimates_;
  };
} // namespace clearjoint::pipeline
