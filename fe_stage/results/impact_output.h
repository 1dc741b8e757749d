// What the impact study writes (no deal.II): the time-history CSV's columns and rows, the sweep
// table's, and the manifest's summary of one impact. fe_stage's main() streams them.
#pragma once

#include "fe_stage/fe_model.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// impact_history.csv: one row per converged time step (and the row at t = 0).
  std::vector<std::string> impact_history_columns();
  std::vector<std::string> impact_history_units();
  std::vector<std::string> impact_history_comments(const FeScene &scene);
  std::vector<double> impact_history_row(const DynamicStepRecord &r);
  /// The state at t = 0: first touch, the journal at v_in, everything else at rest.
  std::vector<double> impact_history_start(const FeScene &scene);

  /// impact_sweep.csv: one row per impact velocity (the sweep table of issue 12).
  std::vector<std::string> impact_sweep_columns();
  std::vector<std::string> impact_sweep_units();
  std::vector<double> impact_sweep_row(const ImpactSummary &s);

  /// The manifest's "impact" object: every number with its unit.
  nlohmann::json impact_summary_json(const ImpactSummary &s);
} // namespace clearjoint::fe
