// What the rolling study writes (no deal.II): the time history's columns and rows, the strain
// profile's, and the manifest's summary. fe_stage's main() streams them.
#pragma once

#include "fe_stage/fe_model.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// rolling_history.csv: one row per converged time step (and the row at t = 0).
  struct Table
  {
    std::vector<std::string> columns, units;
  };
  Table rolling_history_table();
  std::vector<std::string> rolling_history_comments(const FeScene &scene);
  std::vector<double> rolling_history_row(const RollingStepRecord &r);
  std::vector<double> rolling_history_start();

  /// rolling_strain_profile.csv: the bore's (body 0) and a deformable journal's (body 1) strains
  /// across the contact zone at the end.
  Table strain_profile_table();
  std::vector<double> strain_profile_row(const StrainProfilePoint &p);

  /// The manifest's "rolling" object, every number with its unit.
  nlohmann::json rolling_summary_json(const RollingSummary &s, const RollingStepRecord *last);
} // namespace clearjoint::fe
