// "task k of N" and the time left for a pipeline run, from the chosen preset's measured times
// (pipeline.yaml presets.<name>.measured) corrected by what this run has measured so far.
//
// Before a task of a stage has finished, a task of that stage is expected to take:
//   fe_stage  — the preset's fe_case_time (one reference FE curve);
//   fe_impact, fe_impact_deformable, fe_rolling — the preset's impact_time,
//               impact_deformable_time, rolling_time (one task each, a study of its own;
//               unknown when not measured, and then left out of the estimate);
//   the rest  — (pipeline_time − n_fe·fe_case_time) / n_other, the measured whole pipeline
//               minus its FE share, spread over the other tasks (fits, MBD runs, meshes).
// Once tasks of a stage have finished, their mean wall time replaces that guess, and the
// fraction of them that were reused (cost ~0) scales the stage's remaining tasks: a second run
// with nothing changed shows a few seconds, not the first run's minutes.
//
// Tasks at once (run_pipeline --jobs, issue 33): the remaining work, each task weighted by the
// slots it takes (an FE case on R ranks takes R), is shared by the slots, but a run cannot end
// before its longest remaining task: left = max(work / slots, longest task). Dependencies may
// keep slots idle (the fits wait for their FE cases), so this is a lower estimate when tasks
// run at once; running tasks count in full until they end.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace clearjoint::pipeline
{
  class RunEta
  {
  public:
    /// planned: number of tasks per stage ("fe_stage", "fit_stage", "mbd_stage", "mesh").
    /// fe_case_time, pipeline_time: the preset's measured times [s], when measured.
    /// impact_time: the FE impact study's measured time [s] (stage "fe_impact"), if measured;
    /// rolling_time: the FE rolling study's [s] (stage "fe_rolling"), if measured;
    /// impact_deformable_time: the deformable-journal impact's [s] (stage
    /// "fe_impact_deformable"), if measured.
    RunEta(std::map<std::string, int> planned, std::optional<double> fe_case_time,
           std::optional<double> pipeline_time, std::optional<double> impact_time = std::nullopt,
           std::optional<double> rolling_time = std::nullopt,
           std::optional<double> impact_deformable_time = std::nullopt);

    /// Tasks at once: `slots` (run_pipeline --jobs) and the slots one task of a stage takes
    /// (default 1; an FE case on R MPI ranks takes R). Without a call: one at a time.
    void set_concurrency(int slots, std::map<std::string, int> slots_per_task = {});

    /// The expected time of one task of `stage` before any has run [s]: the preset's
    /// measured time (above); nullopt when not measured.
    std::optional<double> expected_seconds(const std::string &stage) const
    {
      return prior_seconds(stage);
    }

    /// Records a finished task; `ran` false for a reused one (its wall_time is then ignored).
    void finished(const std::string &stage, bool ran, double wall_time_s);

    int n_done() const { return n_done_; }
    /// The planned total, raised if more tasks finished than planned.
    int n_total() const;
    struct Left
    {
      double seconds = 0.0;      ///< [s] expected time of the tasks not yet finished
      bool lower_bound = false;  ///< some remaining stage's cost is not known yet (not counted)
    };
    /// nullopt when nothing is known (no measured preset times and no task run yet).
    std::optional<Left> time_left() const;
    /// "task 3 of 35" and, when known, ", about 2 min 10 s left" (or "at least ..."); with
    /// tasks running, "task 5 of 35 (2 running), ...": the next task's number counts them.
    std::string describe_next(int n_running = 0) const;

  private:
    struct Stage
    {
      int planned = 0, ran = 0, reused = 0;
      double ran_seconds = 0.0;
    };
    std::optional<double> prior_seconds(const std::string &stage) const;

    std::map<std::string, Stage> stages_;
    std::optional<double> fe_case_time_, pipeline_time_;
    /// Stages of one task with a measured time of their own: fe_impact, fe_rolling.
    std::map<std::string, std::optional<double>> own_times_;
    int n_done_ = 0;
    int slots_ = 1;
    std::map<std::string, int> slots_per_task_;
  };
} // namespace clearjoint::pipeline
