#include "mbd_stage/output.h"

#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/document_reader.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/manifest.h"
#include "common/plot_script.h"
#include "common/strict_reader.h"
#include "mbd_stage/run_summary.h"

#include <Eigen/Core>
#include <sundials/sundials_config.h>

#include <cstdlib>
#include <filesystem>
#include <unistd.h>

#ifndef CLEARJOINT_SOURCE_DIR
#define CLEARJOINT_SOURCE_DIR "."
#endif

namespace fs = std::filesystem;

namespace clearjoint::mbd
{
  OutputWriter::OutputWriter(std::string output_dir, const int argc, const char *const *argv)
    : dir_(std::move(output_dir))
    , argc_(argc)
    , argv_(argv)
  {
    while (dir_.size() > 1 && dir_.back() == '/')
      dir_.pop_back();
    tmp_ = dir_ + ".tmp." + std::to_string(::getpid());
    check_output_replaceable(dir_, "mbd_stage");
    create_work_folder(tmp_, dir_);
    temporary_.set(tmp_);
  }

  OutputWriter::~OutputWriter()
  {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
  }

  int OutputWriter::write(const Scene &scene, const SimulationResult &r, const bool make_plots)
  {
    {
      CsvWriter csv(tmp_ + "/timeseries.csv", r.columns, r.units,
                    {"clearjoint mbd_stage time series of scene '" + scene.name + "'",
                     "energies: potential zero at z = 0; W_* are work done on the system "
                     "(negative: dissipated)",
                     "<joint>_F*: force the joint exerts on its body_j (ground frame)"});
      for (const auto &row : r.rows)
        csv.write_row(row);
      if (r.complete)
        csv.commit();
      else
        csv.commit_incomplete(r.failure);
    }
    write_file_atomically(tmp_ + "/summary.json", json_text(r.summary) + "\n");
    // Plots are drawn in the temporary folder too, so that an interrupt while plot.py runs
    // (it is stopped, common/plot_script.h) leaves DIR as it was.
    if (make_plots)
      run_plot_script("mbd", {tmp_});  // warns on failure: the data files are complete
    interrupt::throw_if_requested("before " + dir_ + " was replaced");

    // From here on the outputs are complete: an interrupt is noted but the manifest is written.
    std::error_code ec;
    fs::remove_all(dir_, ec);
    fs::rename(tmp_, dir_, ec);
    if (ec)
      throw NumericalError("cannot rename " + tmp_ + " to " + dir_ + ": " + ec.message());
    temporary_.set(dir_);  // until the manifest is written: DIR without one is not an output
    write_manifest(scene, r, make_plots);
    temporary_.release();
    // The end-of-run summary (issue 14, item 5).
    const RunSummaryLines lines =
      make_run_summary(r.summary, dir_, make_plots && fs::exists(dir_ + "/plots"));
    for (const auto &l : lines.info)
      log::info(l);
    for (const auto &l : lines.warnings)
      log::warning(l);
    if (r.complete)
      return exit_success;
    log::error("mbd_stage: simulation failed: " + r.failure + " (partial outputs in " + dir_ + ")");
    return exit_numerical_error;
  }

  /// DIR/manifest.json, written last. DIR is removed if it cannot be written (a full disk):
  /// outputs without their manifest would look like an earlier run's.
  void OutputWriter::write_manifest(const Scene &scene, const SimulationResult &r,
                                    const bool make_plots)
  {
    try
    {
      write_manifest_file(scene, r, make_plots);
    }
    catch (const WriteError &)
    {
      std::error_code ec;
      fs::remove_all(dir_, ec);
      throw;
    }
  }

  void OutputWriter::write_manifest_file(const Scene &scene, const SimulationResult &r,
                                         const bool make_plots)
  {
    Manifest manifest("mbd_stage", dir_ + "/manifest.json", argc_, argv_);
    manifest.add_input(scene.file);
    for (const auto &f : scene.input_files)
      manifest.add_input(f);
    manifest.set_library_version("sundials", SUNDIALS_VERSION);
    manifest.set_library_version("eigen", std::to_string(EIGEN_WORLD_VERSION) + "." +
                                            std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                            std::to_string(EIGEN_MINOR_VERSION));
    manifest.add_output(dir_ + "/timeseries.csv");
    manifest.add_output(dir_ + "/summary.json");

    if (make_plots)
    {
      if (fs::exists(dir_ + "/plots"))
        for (const auto &p : fs::directory_iterator(dir_ + "/plots"))
          manifest.add_output(p.path().string());
    }
    manifest.extra()["summary"] = {{"status", r.summary["status"]},
                                   {"energy", r.summary["energy"]},
                                   {"peaks", r.summary["peaks"]}};
    manifest.write(r.complete ? "complete" : "failed", r.complete ? "" : r.failure);
  }
} // namespace clearjoint::mbd
