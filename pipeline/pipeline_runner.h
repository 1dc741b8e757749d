// Turns a PipelineConfig into tasks (meshes → FE cases → fits → law families → MBD scenes →
// report) and runs them, reusing every task whose inputs are unchanged.
#pragma once

#include "pipeline/pipeline_config.h"
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

    /// The scene of one FE case (base + preset + sweep overrides + the swept value), with a
    /// .geo in geometry.mesh replaced by the mesh its task writes (dry_run: checked only).
    nlohmann::json fe_case_scene(const FeSweep &sweep, double value, bool dry_run,
                                 std::vector<int> &after);
    /// One fe_stage run of a composed scene (written to `scene`) into <run>/<name>; the files
    /// the scene names join its inputs when it starts (add).
    Task fe_stage_task(const std::string &scene, const std::string &name,
                       const std::string &stage) const;
    /// The FE impact sweep and its comparison with the MBD law (config_.impact).
    void run_impact(const std::map<std::string, std::map<std::string, Done>> &laws);
    /// The FE rolling study (config_.rolling): one fe_stage task, fe/rolling. It is a first
    /// step (docs/fe.md): a failure of it is recorded in the summary (status, message, where
    /// its partial output is) and the run goes on; run_pipeline then exits 2 after the report.
    void run_rolling();
    /// The rolling study's scene: base scene, the preset's `fe` overrides, rolling.overrides.
    nlohmann::json rolling_scene() const;
    /// Writes a composed scene to <run>/scenes/<name>.yaml.
    std::string write_scene(const nlohmann::json &scene, const std::string &base,
                            const std::string &name);
    /// Adds a task to the graph (run later by the scheduler); returns its id. `scene`: the
    /// composed scene the task runs, whose named files join its inputs when it starts.
    int add(const Task &task, const std::string &stage_group, std::vector<int> after,
            int ranks = 1, const nlohmann::json &scene = nullptr);
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
    /// The chosen preset's measured fe_case_time, pipeline_time, impact_time or rolling_time
    /// [s], if measured.
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
    std::unique_ptr<RunEta> eta_;
  };
} // namespace clearjoint::pipeline
