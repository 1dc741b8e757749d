// Runs one stage invocation ("task") of the pipeline, unless an identical one already ran.
//
// A task's identity is the sha256 of: the stage executable (the code version), its arguments,
// the contents of its input files, and the identities of the tasks it depends on. The task
// writes into "<dir>.partial/"; only when the stage exits 0 is that renamed to "<dir>/" and a
// stamp "<dir>/.task.json" (with the identity) written atomically. So:
//   - a second run with nothing changed finds every stamp and runs nothing;
//   - changing one input re-runs exactly the tasks whose identity it enters;
//   - an interrupted or failed task leaves only "<dir>.partial/" (with "<dir>.log" and
//     "<dir>.command.txt" beside it), which never looks complete, and is redone next time.
// A finished task's folder holds stage.log and command.txt (the exact command line).
#pragma once

#include <nlohmann/json.hpp>

#include <atomic>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  struct Task
  {
    std::string name;                  ///< e.g. "fe/thickness/t_B=0.004"
    std::string stage;                 ///< fe_stage | fit_stage | mbd_stage (for messages)
    std::vector<std::string> launcher; ///< e.g. {"mpirun", "-np", "2"}; not part of identity
    std::string executable;            ///< absolute path of the stage executable
    /// Arguments; the token "{out}" is replaced by the task's working output directory.
    std::vector<std::string> args;
    std::vector<std::string> input_files;  ///< hashed into the identity
    std::vector<std::string> depends_on;   ///< identities of upstream tasks
    std::string output_dir;                ///< final output directory
  };

  enum class TaskOutcome { ran, reused };

  struct TaskResult
  {
    TaskOutcome outcome;
    std::string identity;  ///< sha256 hex
    double wall_time_s;    ///< [s] of the run that produced the result (also when reused)
  };

  /// Set by SIGINT/SIGTERM; the scheduler stops every running task and throws.
  std::atomic<bool> &interrupt_requested();
  /// Installs SIGINT/SIGTERM handlers that set interrupt_requested() and forward the signal
  /// to every running stage's process group (process_groups.h).
  void install_signal_handlers();

  /// Runs argv (words) in its own process group with stdout and stderr appended to log_path
  /// and waits for it; an interrupt is passed on to it. Returns the wait status.
  int run_process(const std::vector<std::string> &words, const std::string &log_path);

  std::string compute_identity(const Task &task);

  /// The task's earlier result if its folder holds a stamp with `identity` (outcome reused,
  /// wall time of the run that made it); nullopt otherwise.
  std::optional<TaskResult> find_completed(const Task &task, const std::string &identity);
  std::optional<TaskResult> find_completed(const Task &task);

  /// A task about to run: its "<dir>.partial/" emptied, "<dir>.command.txt" written.
  struct PreparedRun
  {
    std::string identity;
    std::string partial;                 ///< <dir>.partial
    std::string log_path;                ///< <dir>.log: the stage's stdout and stderr
    std::string command_path;            ///< <dir>.command.txt
    std::vector<std::string> words;      ///< launcher, executable, args with {out} replaced
  };
  PreparedRun prepare_run(const Task &task, const std::string &identity);

  /// After the stage exited 0: "<dir>.partial" becomes "<dir>" (an earlier "<dir>" replaced),
  /// the log and command line move in as stage.log and command.txt, the manifests' paths are
  /// repointed, and the stamp "<dir>/.task.json" is written last (with `executor`, e.g. the
  /// Slurm job id, when not null).
  TaskResult complete_run(const Task &task, const PreparedRun &run, double wall_time_s,
                          const nlohmann::json &executor);

  /// "<stage> failed in task <name> (<what>); its log <log> ends with:\n<last 2000 bytes>".
  std::string failure_message(const Task &task, const std::string &log_path,
                              const std::string &what);

  /// One line for a task ended from outside (a signal; Slurm's time limit, scancel, a node
  /// failure): "<stage> in task <name>: <what>; its log: <log>" — its log tells nothing more.
  std::string ended_message(const Task &task, const std::string &log_path,
                            const std::string &what);

  /// One line for a stage that could not write its output (exit 3): "<stage> in task <name>:
  /// cannot write '<file>': <reason>; its log: <log>" (the file and the reason are the
  /// stage's own last line).
  std::string write_failure_message(const Task &task, const std::string &log_path);

  /// A task's output could not be written (by its stage or by run_pipeline): run_pipeline
  /// exits 3. The message is one line and names the task.
  class TaskWriteError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace clearjoint::pipeline
