// What the impact study writes (no deal.II): the time history's and the sweep table's columns
// (results/record_table.h), and the manifest's summary of one impact. results/case_output.cc
// and results/sweep_output.cc stream them.
#pragma once

#include "fe_stage/fe_model.h"
#include "fe_stage/results/record_table.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// impact_history.csv: one row per converged time step (and the row at t = 0).
  Columns<DynamicStepRecord> impact_history_columns();
  std::vector<std::string> impact_history_comments(const FeScene &scene);

  /// impact_sweep.csv: one row per impact velocity (the sweep table of issue 12).
  Columns<ImpactSummary> impact_sweep_columns();
  std::vector<std::string> impact_sweep_comments();

  /// The manifest's "impact" object: every number with its unit.
  nlohmann::json impact_summary_json(const ImpactSummary &s);
}  // namespace clearjoint::fe
