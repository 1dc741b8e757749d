// What a sweep writes into its top folder (no deal.II): sweep.csv (force at delta_max per
// t_B or theta) or impact_sweep.csv (per impact case: velocity × journal mass), its plots and
// the top manifest, which lists every case's manifest. Each case's own folder is a CaseOutput's.
#pragma once

#include "common/manifest.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/results/record_table.h"

#include <memory>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// The swept parameter: sweep.t_B, sweep.theta_deg, or sweep.velocity and/or
  /// sweep.journal_mass (the impact study's).
  enum class SweepKind
  {
    thickness,
    theta,
    impact
  };
  SweepKind sweep_kind(const FeScene &scene);

  /// A number as `std::ostream <<` writes it (6 significant digits): folder names and labels.
  std::string short_number(double v);

  /// One case of a sweep once run: its folder, the swept value (t_B [m], theta [deg] or v
  /// [m/s]; an impact case's journal mass is in `impact`) and what the table records.
  struct SweepCase
  {
    std::string folder;
    double value = 0.0;
    double force_at_delta_max = 0.0;  // [N]
    ImpactSummary impact;             // study impact
  };

  /// sweep.csv's or impact_sweep.csv's columns.
  Columns<SweepCase> sweep_columns(SweepKind kind);

  class SweepOutput
  {
  public:
    SweepOutput(const std::string &dir, SweepKind kind, const std::string &scene_path, int argc,
                char **argv);
    ~SweepOutput();
    /// A finished case (complete or not): its row and its manifest.
    void add_case(const SweepCase &c);
    /// Commits the table (incomplete if a case failed), draws the plot and writes the manifest.
    void finish(bool complete, bool plots);

  private:
    std::string dir_, table_path_;
    SweepKind kind_;
    std::unique_ptr<Manifest> manifest_;
    std::unique_ptr<RecordCsv<SweepCase>> table_;
    std::vector<SweepCase> cases_;
  };
}  // namespace clearjoint::fe
