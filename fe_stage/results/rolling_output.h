// What the rolling study writes (no deal.II): the time history's and the strain profile's
// columns (results/record_table.h), and the manifest's summary. results/case_output.cc streams
// them.
#pragma once

#include "fe_stage/fe_model.h"
#include "fe_stage/results/record_table.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// rolling_history.csv: one row per converged time step (and the row at t = 0, all zero).
  Columns<RollingStepRecord> rolling_history_columns();
  std::vector<std::string> rolling_history_comments(const FeScene &scene);

  /// rolling_strain_profile.csv: the bore's (body 0) and a deformable journal's (body 1) strains
  /// across the contact zone at the end.
  Columns<StrainProfilePoint> strain_profile_columns();
  std::vector<std::string> strain_profile_comments();

  /// The manifest's "rolling" object, every number with its unit.
  nlohmann::json rolling_summary_json(const RollingSummary &s, const RollingStepRecord *last);
}  // namespace clearjoint::fe
