// Writes a run's outputs atomically: everything goes into "<DIR>.tmp.<pid>", which is renamed
// to DIR when complete (an existing DIR is replaced); the plots are made from the renamed
// outputs; manifest.json is written last and carries the status. A run that dies leaves at
// most a *.tmp.* directory, never a DIR that looks finished.
#pragma once

#include "common/interrupt.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <string>

namespace clearjoint::mbd
{
  class OutputWriter
  {
  public:
    OutputWriter(std::string output_dir, int argc, const char *const *argv);
    ~OutputWriter();

    /// Writes timeseries.csv, summary.json, plots (if asked) and manifest.json; returns the
    /// exit code (0 complete, 2 the simulation failed numerically).
    int write(const Scene &scene, const SimulationResult &result, bool make_plots);

  private:
    void write_manifest(const Scene &scene, const SimulationResult &r, bool make_plots);
    void write_manifest_file(const Scene &scene, const SimulationResult &r, bool make_plots);

    std::string dir_, tmp_;
    interrupt::Temporary temporary_;  ///< tmp_, removed by a hard stop
    int argc_;
    const char *const *argv_;
  };
} // namespace clearjoint::mbd
