// What one case writes into its folder (no deal.II): force_penetration.csv, the impact and
// rolling studies' histories and strain profile, adaptive_cycles.csv, the plots and
// manifest.json. fe_stage's main() makes one on rank 0, streams the run's records to it and
// finishes it with the run's result.
#pragma once

#include "common/manifest.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/presets.h"
#include "fe_stage/results/record_table.h"

#include <memory>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// How the scene was made: the preset of pipeline.yaml applied to it, if any.
  struct PresetUse
  {
    std::string name, file;
    PresetOverrides overrides;
  };

  /// force_penetration.csv: one row per converged increment (and the row at δ = 0, all zero).
  Columns<IncrementRecord> force_penetration_columns();
  std::vector<std::string> force_penetration_comments(const FeScene &scene);

  /// adaptive_cycles.csv: one row per adaptive mesh (the last is the recorded curve's).
  struct AdaptiveCycleRow
  {
    std::size_t cycle = 0;
    AdaptiveCycle mesh;
  };
  Columns<AdaptiveCycleRow> adaptive_cycles_columns();
  std::vector<std::string> adaptive_cycles_comments(const FeScene &scene, const RunResult &result);

  /// The manifest's yield check: per body its volume, the volume above the yield stress and
  /// the largest von Mises stress with its place (SI, units stated).
  nlohmann::json yield_check_json(const YieldCheck &y);

  /// One case's outputs in `dir`: the tables are opened (with their first row) when it is
  /// made, rows stream in while the run goes, finish() commits them and writes the rest.
  class CaseOutput
  {
  public:
    CaseOutput(const FeScene &scene, const std::string &dir, int argc, char **argv,
               const PresetUse &preset);
    ~CaseOutput();

    void write_increment(const IncrementRecord &r);
    void write_dynamic_step(const DynamicStepRecord &r);
    void write_rolling_step(const RollingStepRecord &r);

    /// Commits the tables (incomplete if the run is), writes the strain profile, the adaptive
    /// cycles, the plots (if `plots`) and the manifest, and logs the result; `shown_dir` is
    /// the folder as messages name it.
    void finish(const RunResult &result, bool plots, const std::string &shown_dir);

  private:
    void finish_impact(const RunResult &result, bool plots);
    void finish_rolling(const RunResult &result, bool plots);
    void write_adaptive_cycles(const RunResult &result);
    void record_run(const RunResult &result);
    void log_result(const RunResult &result, const std::string &shown_dir) const;

    FeScene scene_;
    std::string dir_;
    std::unique_ptr<Manifest> manifest_;
    std::unique_ptr<RecordCsv<IncrementRecord>> curve_;
    std::unique_ptr<RecordCsv<DynamicStepRecord>> impact_history_;
    std::unique_ptr<RecordCsv<RollingStepRecord>> rolling_history_;
  };
}  // namespace clearjoint::fe
