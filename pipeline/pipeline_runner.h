// Turns a PipelineConfig into tasks (FE cases → fits → law families → MBD scenes → report)
// and runs them, reusing every task whose inputs are unchanged.
#pragma once

#include "pipeline/pipeline_config.h"
#include "pipeline/task_runner.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace clearjoint::pipeline
{
  struct RunOptions
  {
    std::string build_dir;              ///< where fe_stage/, fit_stage/, mbd_stage/ were built
    bool force = false;                 ///< re-run every task
    std::optional<std::string> only;    ///< fe | fit | mbd | report
    bool plots = true;
  };

  class PipelineRunner
  {
  public:
    PipelineRunner(PipelineConfig config, RunOptions options);
    /// Runs everything; returns the summary written to <run dir>/pipeline_summary.json.
    nlohmann::json run();
    std::string run_dir() const;

  private:
    /// Base scene + preset overrides (+ extra overrides) written to <run>/scenes/<name>.yaml.
    std::string make_scene(const std::string &base, const std::string &stage,
                           const std::vector<std::pair<std::string, nlohmann::json>> &overrides,
                           const std::string &name);
    TaskResult execute(const Task &task, const std::string &stage_group);
    std::string stage_executable(const std::string &stage) const;

    PipelineConfig config_;
    RunOptions options_;
    nlohmann::json summary_;
  };
} // namespace clearjoint::pipeline
