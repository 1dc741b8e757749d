// The short summary mbd_stage prints at the end of every run (issue 14, item 5): status and
// time reached, impacts per contact kind, peak contact force, energy drift, the law-range and
// impact-velocity-floor counters when non-zero, and where the outputs are. Built from the
// summary JSON alone, so a failed run reports the same way.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  struct RunSummaryLines
  {
    std::vector<std::string> info;      ///< always printed (log level info)
    std::vector<std::string> warnings;  ///< non-zero range counters (log level warning)
  };

  /// `summary`: the clearjoint.mbd_summary/1 document; `output_dir`: where the files are;
  /// `plots`: whether plots/ was made.
  RunSummaryLines make_run_summary(const nlohmann::json &summary, const std::string &output_dir,
                                   bool plots);
} // namespace clearjoint::mbd
