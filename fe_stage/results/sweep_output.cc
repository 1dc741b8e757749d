#include "fe_stage/results/sweep_output.h"

#include "common/plot_script.h"
#include "common/units.h"
#include "fe_stage/results/impact_output.h"

#include <filesystem>
#include <sstream>

namespace clearjoint::fe
{
  SweepKind sweep_kind(const FeScene &scene)
  {
    if (!scene.sweep_velocity.empty() || !scene.sweep_journal_mass.empty())
      return SweepKind::impact;
    return scene.sweep_theta_deg.empty() ? SweepKind::thickness : SweepKind::theta;
  }

  std::string short_number(const double v)
  {
    std::ostringstream o;
    o << v;
    return o.str();
  }

  Columns<SweepCase> sweep_columns(const SweepKind kind)
  {
    Columns<SweepCase> columns;
    if (kind == SweepKind::impact)
      {
        for (auto &c : impact_sweep_columns())
          columns.push_back(
            {c.name, c.unit, [value = c.value](const SweepCase &s) { return value(s.impact); }});
        return columns;
      }
    const bool by_theta = kind == SweepKind::theta;
    return {{by_theta ? "theta" : "t_B", by_theta ? "deg" : "m",
             [](const SweepCase &s) { return s.value; }},
            {"force_at_delta_max", "N", [](const SweepCase &s) { return s.force_at_delta_max; }}};
  }

  SweepOutput::SweepOutput(const std::string &dir, const SweepKind kind,
                           const std::string &scene_path, const int argc, char **argv)
    : dir_(dir)
    , table_path_(dir + (kind == SweepKind::impact ? "/impact_sweep.csv" : "/sweep.csv"))
    , kind_(kind)
  {
    std::filesystem::create_directories(dir);
    manifest_ = std::make_unique<Manifest>("fe_stage", dir + "/manifest.json", argc, argv);
    manifest_->add_input(scene_path);
    const std::vector<std::string> comments =
      kind == SweepKind::impact ?
        impact_sweep_comments() :
        std::vector<std::string>{std::string("fe_stage ") +
                                 (kind == SweepKind::theta ? "misalignment" : "thickness") +
                                 " sweep; one folder per case"};
    table_ = std::make_unique<RecordCsv<SweepCase>>(table_path_, sweep_columns(kind), comments);
  }

  SweepOutput::~SweepOutput() = default;

  void SweepOutput::add_case(const SweepCase &c)
  {
    table_->write(c);
    manifest_->add_output(c.folder + "/manifest.json");
    cases_.push_back(c);
  }

  void SweepOutput::finish(const bool complete, const bool plots)
  {
    table_->commit(complete, "a case failed; see its manifest");
    manifest_->add_output(table_path_);
    if (kind_ == SweepKind::impact)
      {
        // the sweep's quantities, and beside them the paper's Fig. 5a and 5b
        if (plots &&
            run_plot_script("fe_impact", {dir_ + "/impact_sweep.png", "--sweep", table_path_}))
          for (const char *png : {"/impact_sweep.png", "/fig5a.png", "/fig5b.png"})
            if (std::filesystem::exists(dir_ + png))
              manifest_->add_output(dir_ + png);
      }
    else
      {
        // every case's curve in one figure, labelled by its value
        std::vector<std::string> plot_args = {dir_ + "/sweep.png"};
        for (const auto &c : cases_)
          if (std::filesystem::exists(c.folder + "/force_penetration.csv"))
            plot_args.push_back(c.folder + "=" +
                                (kind_ == SweepKind::theta ?
                                   "theta " + short_number(c.value) + " deg" :
                                   "t_B " + short_number(units::to_mm(c.value)) + " mm"));
        if (plots && run_plot_script("fe", plot_args))
          manifest_->add_output(dir_ + "/sweep.png");
      }
    manifest_->write(complete ? "complete" : "incomplete");
  }
}  // namespace clearjoint::fe
