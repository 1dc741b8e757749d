// Fitted laws do not exist before a run, yet run_pipeline --check hands every MBD scene to
// mbd_stage --check first: the scenes get stand-ins (the paper's law for t_B = 4 mm, and a
// two-member family of it over a sweep's parameter), which validate every other key; the
// fitted law itself is checked when mbd_stage runs.
#pragma once

#include "pipeline/pipeline_config.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace clearjoint::pipeline
{
  class StandInLaws
  {
  public:
    /// The stand-ins are written into `folder`, each once, when first asked for.
    StandInLaws(std::filesystem::path folder, const std::vector<FeSweep> &sweeps);

    /// The law file an MBD scene gets for `choice`: a given file as it is (absolute), else a
    /// stand-in — the paper's law for a law at one value, a family for a law over a sweep.
    std::string for_choice(const LawChoice &choice);

  private:
    const std::string &paper_law();
    /// The paper's law at both ends of the sweep's values (clamped outside them).
    const std::string &family(const std::string &sweep_name);

    std::filesystem::path folder_;
    const std::vector<FeSweep> &sweeps_;
    std::string paper_law_;
    std::map<std::string, std::string> families_;  ///< sweep name → its family's file
  };
} // namespace clearjoint::pipeline
