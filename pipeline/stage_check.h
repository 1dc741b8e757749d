// The stages' --check runs of the inputs the pipeline generated (scenes, fit commands), and
// how a failure is reported: an input error of the stage becomes an input error naming the
// pipeline key that produced the rejected value (a sweep value, an override, a preset key, a
// law), so the user is sent to the line of pipeline.yaml to change.
#pragma once

#include <nlohmann/json.hpp>

#include <sys/types.h>

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

  /// The stages' --check runs of the inputs a pipeline generates, a few at once: each is mostly
  /// its stage's start-up (fe_stage ~0.7 s, the relocation of deal.II's and Trilinos's shared
  /// libraries), and run_pipeline checks every scene before its first task. A failure is
  /// reported when finish() has waited for them all: the first in the order they were added,
  /// as an input error of the pipeline key of the last of its `origins` that set the failing
  /// scene key (or a key above or below it), else of its base_key; any other failure, or an
  /// interrupt, as a NumericalError. `what` names the input in the messages ("FE case
  /// thickness t_B=0.004 (scene ...)").
  class StageChecks
  {
  public:
    explicit StageChecks(int at_once);
    /// Ends and reaps the checks still running (when an error ends the check early).
    ~StageChecks();
    StageChecks(const StageChecks &) = delete;
    StageChecks &operator=(const StageChecks &) = delete;

    /// Starts STAGE ARGS... --check -q (its log to log_path), once fewer than `at_once` run.
    void add(const StageCheck &check, std::vector<std::string> args, const std::string &log_path,
             const std::vector<Origin> &origins, const std::string &base_key,
             const std::string &what);
    /// Waits for every check added; returns if all accepted, else throws (above).
    void finish();

  private:
    struct Pending
    {
      StageCheck check;
      std::string log_path;
      std::vector<Origin> origins;
      std::string base_key, what;
      pid_t pid = 0;
      bool running = false;
      int status = 0;  ///< the wait status, once reaped
    };
    void wait_for(Pending &p);

    std::size_t at_once_;
    std::vector<Pending> checks_;
    std::size_t oldest_running_ = 0;  ///< checks_ before it are reaped
  };
} // namespace clearjoint::pipeline
