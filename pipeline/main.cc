// run_pipeline: runs the FE sweeps, the fits and law families, the MBD scenes and the report
// described by pipeline.yaml, re-running only what changed. See --help.
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "pipeline/pipeline_runner.h"
#include "pipeline/presets.h"
#include "pipeline/sweep_values.h"
#include "pipeline/task_runner.h"

#include <CLI/CLI.hpp>

#include <filesystem>

namespace fs = std::filesystem;

namespace
{
  using namespace clearjoint;

  /// run_pipeline --help: what it does, its outputs and its exit codes.
  const char *const help_text =
    "run_pipeline — the clearjoint pipeline: FE sweeps → fitted laws → MBD scenes → report.\n"
    "\n"
    "  run_pipeline [pipeline.yaml] [--preset fast|standard|accurate] [--force]\n"
    "               [--only fe|fit|mbd|report] [--no-plots] [--output-root DIR] [--check]\n"
    "               [--jobs N] [--executor local|slurm]\n"
    "\n"
    "Results go to <output_root>/<run>/ (default out/default/): fe/, fit/, mbd/, scenes/,\n"
    "pipeline_summary.json, manifest.json and report.html. A task whose inputs (input files,\n"
    "upstream results, stage executable) are unchanged is reused, not re-run; --force re-runs\n"
    "all. An interrupted task leaves only '<dir>.partial/' and is redone by the next run.\n"
    "Before the first task (and alone with --check) every generated FE and MBD scene is\n"
    "validated by its stage's own reader; nothing is written under the output root until the\n"
    "whole pipeline is valid.\n"
    "Tasks whose upstream tasks are done run at once: up to --jobs CPU slots on this machine\n"
    "(default: its cores; a task on R MPI ranks takes R), or with --executor slurm one Slurm\n"
    "job per task (up to --jobs queued at once, default 100); see docs/pipeline.md.\n"
    "\n"
    "Exit codes: 0 success, 1 input error (pipeline.yaml or a scene), 2 a stage failed (a\n"
    "failing rolling study does not stop the rest: the report is written, then exit 2),\n"
    "3 an output could not be written (a full disk, an I/O error: one line naming the task,\n"
    "the file and the reason; the next run redoes only what was lost),\n"
    "130/143 interrupted by SIGINT/SIGTERM (passed on to the running stage or report).";

  /// What the command line asks for.
  struct CommandLine
  {
    std::string pipeline_file = "pipeline.yaml", preset, only, build_dir, output_root, executor;
    long jobs = 0;
    bool check_only = false;
    pipeline::RunOptions options;
  };

  /// The options and flags of run_pipeline, read into `cl` by app.parse.
  void add_options(CLI::App &app, CommandLine &cl)
  {
    app.add_option("pipeline", cl.pipeline_file, "pipeline file (schema clearjoint.pipeline/1)");
    app.add_option("--preset", cl.preset, "speed/accuracy preset, overrides the file's 'preset'")
      ->check(CLI::IsMember({"fast", "standard", "accurate"}));
    app.add_flag("--force", cl.options.force, "re-run every task even if its inputs are unchanged");
    app.add_option("--only", cl.only, "run only this stage's tasks (upstream must be up to date)")
      ->check(CLI::IsMember({"fe", "fit", "mbd", "report"}));
    app.add_flag("--no-plots", [&cl](std::int64_t) { cl.options.plots = false; }, "no plots, no report");
    app.add_option("--build-dir", cl.build_dir, "where the stages were built (default: ours)");
    app.add_option("--jobs", cl.jobs,
                   "tasks at once: CPU slots here, or Slurm jobs queued at once; overrides "
                   "pipeline.yaml 'jobs' (1 to " + std::to_string(pipeline::max_jobs) + ")");
    app.add_option("--executor", cl.executor, "where tasks run; overrides pipeline.yaml executor.kind")
      ->check(CLI::IsMember({"local", "slurm"}));
    app.add_flag("--check", cl.check_only,
                 "validate the pipeline file and every scene it generates, then exit (0 valid, "
                 "1 input error); writes nothing under the output root");
    app.add_option("--output-root", cl.output_root, "overrides the file's output_root (results folder)");
  }

  /// The run options from the parsed command line (--jobs is checked later, as an input error).
  void resolve_run_options(CommandLine &cl)
  {
    // The stages live beside us in the build tree: <build>/pipeline/run_pipeline.
    cl.options.build_dir = cl.build_dir.empty()
                             ? fs::canonical("/proc/self/exe").parent_path().parent_path().string()
                             : cl.build_dir;
    if (!cl.only.empty())
      cl.options.only = cl.only;
    if (!cl.executor.empty())
      cl.options.executor = cl.executor;
  }

  /// pipeline.yaml with the command line's preset and output root, its value keywords resolved.
  pipeline::PipelineConfig read_config(const CommandLine &cl)
  {
    auto config = pipeline::read_pipeline_config(cl.pipeline_file);
    if (!cl.preset.empty())
      config.preset = cl.preset;
    if (!cl.output_root.empty())
      config.output_root = cl.output_root;
    // theta_max & co. depend on the scene geometry after the preset: resolve them now.
    pipeline::resolve_value_keywords(config);
    return config;
  }

  struct TaskCounts
  {
    int ran = 0, reused = 0;
  };

  TaskCounts count_tasks(const nlohmann::json &summary)
  {
    TaskCounts n;
    for (const auto &t : summary["tasks"])
      (t["outcome"] == "ran" ? n.ran : n.reused) += 1;
    return n;
  }

  /// report.html from the summary, when asked for; true if it was written.
  bool write_report(const pipeline::PipelineConfig &config, const pipeline::RunOptions &options,
                    const std::string &run_dir, Manifest &manifest)
  {
    if (!(config.report && options.plots && (!options.only || *options.only == "report")))
      return false;
    const std::string html = run_dir + "/report.html";
    bool plotted = false;
    try
    {
      plotted = run_plot_script("report", {run_dir + "/pipeline_summary.json", "--output", html});
    }
    catch (const WriteError &e)
    {
      throw pipeline::TaskWriteError(std::string("run_pipeline in the report: ") + e.what() +
                                     "; every task is complete, the next run makes the report");
    }
    if (!plotted)
      return false;
    manifest.add_output(html);
    log::info("report: " + html);
    return true;
  }

  /// The last log line: tasks ran and reused, the time and, when every task ran, the time
  /// beside the preset's measured pipeline_time (a reused task costs nothing).
  void log_run_time(const pipeline::PipelineConfig &config, const TaskCounts &n,
                    const Manifest &manifest)
  {
    std::string against;
    if (const auto m = config.preset_measured.find(config.preset);
        m != config.preset_measured.end() && m->second.pipeline_time && n.reused == 0)
      against = " (" +
                pipeline::describe_against_figure(config.preset, manifest.elapsed_seconds(),
                                                  *m->second.pipeline_time) +
                ")";
    log::info("run_pipeline: " + std::to_string(n.ran) + " tasks ran, " +
              std::to_string(n.reused) + " reused, in " +
              log::format_duration(manifest.elapsed_seconds()) + against + "; " +
              pipeline::describe_preset_errors(config, config.preset));
  }

  /// The run's manifest after a failure; on a full disk it may not be writable either, which
  /// must not hide the failure itself (already logged).
  void write_final_manifest(clearjoint::Manifest *manifest, const std::string &status,
                            const std::string &message)
  {
    if (!manifest)
      return;
    try
    {
      manifest->write(status, message);
    }
    catch (const std::exception &)
    {
      manifest->discard();
    }
  }

  /// Inside a catch block: logs the exception in flight, records it in the manifest (if one
  /// was started) and returns the exit code it means (see --help).
  int exit_code_of_current_exception(Manifest *manifest)
  {
    try
    {
      throw;
    }
    catch (const InputError &e)
    {
      log::error(e.what());
      write_final_manifest(manifest, "failed", e.what());
      return exit_input_error;
    }
    catch (const pipeline::TaskWriteError &e)
    {
      // A task's output could not be written (a full disk): one line naming the task, the file
      // and the reason. The tasks completed before are kept; the next run redoes the rest.
      log::error(e.what());
      write_final_manifest(manifest, "failed", e.what());
      return exit_write_error;
    }
    catch (const WriteError &e)
    {
      // run_pipeline's own file (its manifest, the summary, a generated scene).
      log::error(std::string("run_pipeline: ") + e.what() +
                 "; the tasks completed so far are kept, the next run redoes the rest");
      write_final_manifest(manifest, "failed", e.what());
      return exit_write_error;
    }
    catch (const std::exception &e)
    {
      log::error(e.what());
      write_final_manifest(manifest, pipeline::interrupt_requested() ? "incomplete" : "failed",
                           e.what());
      return pipeline::interrupt_requested() ? interrupt::exit_code() : exit_numerical_error;
    }
  }
} // namespace

int main(int argc, char **argv)
{
  using namespace clearjoint;
  CLI::App app{help_text};
  CommandLine cl;
  add_options(app, cl);
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError &e)
  {
    return app.exit(e) == 0 ? exit_success : exit_input_error;
  }
  resolve_run_options(cl);
  const pipeline::RunOptions &options = cl.options;
  pipeline::install_signal_handlers();

  std::unique_ptr<Manifest> manifest;
  try
  {
    if (app.count("--jobs") > 0)
      cl.options.jobs = pipeline::checked_jobs(cl.jobs, "", "--jobs");
    const pipeline::PipelineConfig config = read_config(cl);
    pipeline::PipelineRunner runner(config, options);
    runner.check();  // input errors end the run here, before anything is written
    if (cl.check_only)
      return exit_success;
    fs::create_directories(runner.run_dir());
    manifest = std::make_unique<Manifest>("run_pipeline", runner.run_dir() + "/manifest.json",
                                          argc, argv);
    manifest->add_input(cl.pipeline_file);
    log::info("run_pipeline: " + cl.pipeline_file + " → " + runner.run_dir() + " (preset " +
              config.preset + ")");
    log::info(pipeline::describe_preset_errors(config, config.preset));
    const auto summary = runner.run();
    manifest->add_output(runner.run_dir() + "/pipeline_summary.json");
    const TaskCounts n = count_tasks(summary);
    manifest->extra()["tasks_ran"] = n.ran;
    manifest->extra()["tasks_reused"] = n.reused;
    const bool report_written = write_report(config, options, runner.run_dir(), *manifest);
    interrupt::throw_if_requested("after the last task");
    // The rolling study's failure did not stop the run (PipelineRunner::run_rolling): the
    // rest is complete and the report shows the failure, but the run did not do all it was
    // asked to: exit 2.
    if (summary.contains("rolling") && summary["rolling"].value("status", "") == "failed")
    {
      const std::string message =
        "the FE rolling study failed (every other task is complete" +
        std::string(report_written ? ", report.html shows the failure" : "") +
        "): " + summary["rolling"].value("message", std::string());
      log::error("run_pipeline: " + message);
      manifest->write("failed", message);
      return exit_numerical_error;
    }
    manifest->write("complete");
    log_run_time(config, n, *manifest);
    return exit_success;
  }
  catch (...)
  {
    return exit_code_of_current_exception(manifest.get());
  }
}
