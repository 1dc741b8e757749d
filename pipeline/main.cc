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
} // namespace

int main(int argc, char **argv)
{
  using namespace clearjoint;
  CLI::App app{
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
    "130/143 interrupted by SIGINT/SIGTERM (passed on to the running stage or report)."};
  std::string pipeline_file = "pipeline.yaml", preset, only, build_dir;
  pipeline::RunOptions options;
  app.add_option("pipeline", pipeline_file, "pipeline file (schema clearjoint.pipeline/1)");
  app.add_option("--preset", preset, "speed/accuracy preset, overrides the file's 'preset'")
    ->check(CLI::IsMember({"fast", "standard", "accurate"}));
  app.add_flag("--force", options.force, "re-run every task even if its inputs are unchanged");
  app.add_option("--only", only, "run only this stage's tasks (upstream must be up to date)")
    ->check(CLI::IsMember({"fe", "fit", "mbd", "report"}));
  app.add_flag("--no-plots", [&](std::int64_t) { options.plots = false; }, "no plots, no report");
  app.add_option("--build-dir", build_dir, "where the stages were built (default: ours)");
  std::string output_root;
  long jobs = 0;
  std::string executor;
  app.add_option("--jobs", jobs,
                 "tasks at once: CPU slots here, or Slurm jobs queued at once; overrides "
                 "pipeline.yaml 'jobs' (1 to " + std::to_string(pipeline::max_jobs) + ")");
  app.add_option("--executor", executor, "where tasks run; overrides pipeline.yaml executor.kind")
    ->check(CLI::IsMember({"local", "slurm"}));
  bool check_only = false;
  app.add_flag("--check", check_only,
               "validate the pipeline file and every scene it generates, then exit (0 valid, "
               "1 input error); writes nothing under the output root");
  app.add_option("--output-root", output_root, "overrides the file's output_root (results folder)");
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError &e)
  {
    return app.exit(e) == 0 ? exit_success : exit_input_error;
  }

  // The stages live beside us in the build tree: <build>/pipeline/run_pipeline.
  options.build_dir = build_dir.empty()
                        ? fs::canonical("/proc/self/exe").parent_path().parent_path().string()
                        : build_dir;
  if (!only.empty())
    options.only = only;
  if (!executor.empty())
    options.executor = executor;
  pipeline::install_signal_handlers();

  std::unique_ptr<Manifest> manifest;
  try
  {
    if (app.count("--jobs") > 0)
      options.jobs = pipeline::checked_jobs(jobs, "", "--jobs");
    auto config = pipeline::read_pipeline_config(pipeline_file);
    if (!preset.empty())
      config.preset = preset;
    if (!output_root.empty())
      config.output_root = output_root;
    // theta_max & co. depend on the scene geometry after the preset: resolve them now.
    pipeline::resolve_value_keywords(config);
    pipeline::PipelineRunner runner(config, options);
    runner.check();  // input errors end the run here, before anything is written
    if (check_only)
      return exit_success;
    fs::create_directories(runner.run_dir());
    manifest = std::make_unique<Manifest>("run_pipeline", runner.run_dir() + "/manifest.json",
                                          argc, argv);
    manifest->add_input(pipeline_file);
    log::info("run_pipeline: " + pipeline_file + " → " + runner.run_dir() + " (preset " +
              config.preset + ")");
    log::info(pipeline::describe_preset_errors(config, config.preset));
    const auto summary = runner.run();
    manifest->add_output(runner.run_dir() + "/pipeline_summary.json");
    int n_ran = 0, n_reused = 0;
    for (const auto &t : summary["tasks"])
      (t["outcome"] == "ran" ? n_ran : n_reused) += 1;
    manifest->extra()["tasks_ran"] = n_ran;
    manifest->extra()["tasks_reused"] = n_reused;
    bool report_written = false;
    if (config.report && options.plots && (!options.only || *options.only == "report"))
    {
      const std::string html = runner.run_dir() + "/report.html";
      bool plotted = false;
      try
      {
        plotted = run_plot_script("report",
                                  {runner.run_dir() + "/pipeline_summary.json", "--output", html});
      }
      catch (const WriteError &e)
      {
        throw pipeline::TaskWriteError(std::string("run_pipeline in the report: ") + e.what() +
                                       "; every task is complete, the next run makes the report");
      }
      if (plotted)
      {
        manifest->add_output(html);
        log::info("report: " + html);
        report_written = true;
      }
    }
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
    // The whole run beside the preset's measured pipeline_time: only comparable when every
    // task ran (a reused task costs nothing).
    std::string against;
    if (const auto m = config.preset_measured.find(config.preset);
        m != config.preset_measured.end() && m->second.pipeline_time && n_reused == 0)
      against = " (" +
                pipeline::describe_against_figure(config.preset, manifest->elapsed_seconds(),
                                                  *m->second.pipeline_time) +
                ")";
    log::info("run_pipeline: " + std::to_string(n_ran) + " tasks ran, " +
              std::to_string(n_reused) + " reused, in " +
              log::format_duration(manifest->elapsed_seconds()) + against + "; " +
              pipeline::describe_preset_errors(config, config.preset));
    return exit_success;
  }
  catch (const InputError &e)
  {
    log::error(e.what());
    write_final_manifest(manifest.get(), "failed", e.what());
    return exit_input_error;
  }
  catch (const pipeline::TaskWriteError &e)
  {
    // A task's output could not be written (a full disk): one line naming the task, the file
    // and the reason. The tasks completed before are kept; the next run redoes the rest.
    log::error(e.what());
    write_final_manifest(manifest.get(), "failed", e.what());
    return exit_write_error;
  }
  catch (const WriteError &e)
  {
    // run_pipeline's own file (its manifest, the summary, a generated scene).
    log::error(std::string("run_pipeline: ") + e.what() +
               "; the tasks completed so far are kept, the next run redoes the rest");
    write_final_manifest(manifest.get(), "failed", e.what());
    return exit_write_error;
  }
  catch (const std::exception &e)
  {
    log::error(e.what());
    write_final_manifest(manifest.get(),
                         pipeline::interrupt_requested() ? "incomplete" : "failed", e.what());
    return pipeline::interrupt_requested() ? interrupt::exit_code() : exit_numerical_error;
  }
}
