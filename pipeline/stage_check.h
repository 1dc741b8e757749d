// One stage's --check run of an input the pipeline generated (a scene, or a fit command), and
// how its failure is reported: an input error of the stage becomes an input error naming the
// pipeline key that produced the rejected value (a sweep value, an override, a preset key, a
// law), so the user is sent to the line of pipeline.yaml to change.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  /// Where a scene key got its value: the pipeline key (and its value, for the message).
  struct Origin
  {
    std::string scene_key, pipeline_key;
    nlohmann::json value;
  };

  struct StageCheck
  {
    std::string stage;       ///< fe_stage, fit_stage or mbd_stage
    std::string executable;  ///< its path
    std::string source;      ///< the pipeline file, for the error messages
  };

  /// Runs STAGE ARGS... --check -q (its log to log_path). Returns when the stage accepts. An
  /// input error of the stage throws an InputError of the pipeline key of the last of
  /// `origins` that set the failing scene key (or a key above or below it), else of base_key;
  /// any other failure, or an interrupt, throws a NumericalError. `what` names the input in
  /// the messages ("FE case thickness t_B=0.004 (scene ...)").
  void run_stage_check(const StageCheck &check, std::vector<std::string> args,
                       const std::string &log_path, const std::vector<Origin> &origins,
                       const std::string &base_key, const std::string &what);
} // namespace clearjoint::pipeline
