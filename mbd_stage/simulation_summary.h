// summary.json of an MBD run (schema clearjoint.mbd_summary/1): status, the integrator and its
// step statistics, the energy balance, constraint drift, peaks, each clearance joint's model,
// impacts, law-range and depth-guard counters, and the first 500 contact events. Read by the
// report (scripts/plotting/_report_mbd.py) and run_summary.cc.
#pragma once

#include "mbd_stage/run_peaks.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <nlohmann/json.hpp>

namespace clearjoint::mbd
{
  nlohmann::json make_summary(const Scene &scene, const SimulationResult &res,
                              const RunPeaks &peaks);
} // namespace clearjoint::mbd
