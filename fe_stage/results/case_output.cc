#include "fe_stage/results/case_output.h"

#include "common/error.h"
#include "common/log.h"
#include "common/plot_script.h"
#include "fe_stage/results/impact_output.h"
#include "fe_stage/results/rolling_output.h"

namespace clearjoint::fe
{
  Columns<IncrementRecord> force_penetration_columns()
  {
    using R = IncrementRecord;
    return {{"delta", "m", [](const R &r) { return r.delta; }},
            {"force", "N", [](const R &r) { return r.force; }},
            {"force_support", "N", [](const R &r) { return r.force_support; }},
            {"force_load", "N", [](const R &r) { return r.force_load; }},
            {"contact_iterations", "1", [](const R &r) { return double(r.contact_iterations); }},
            {"linear_iterations", "1", [](const R &r) { return double(r.linear_iterations); }},
            {"active_contact_points", "1", [](const R &r) { return double(r.n_active); }},
            {"slipping_contact_points", "1", [](const R &r) { return double(r.n_slip); }},
            {"max_penetration", "m", [](const R &r) { return r.max_penetration; }},
            {"pressure_min", "Pa", [](const R &r) { return r.pressure_min; }},
            {"pressure_max", "Pa", [](const R &r) { return r.pressure_max; }},
            {"wall_time", "s", [](const R &r) { return r.wall_time; }},
            {"friction_cone_excess", "1", [](const R &r) { return r.friction_cone_excess; }},
            {"friction_slip_law_error", "1", [](const R &r) { return r.friction_slip_law_error; }},
            {"friction_direction_error", "1",
             [](const R &r) { return r.friction_direction_error; }}};
  }

  std::vector<std::string> force_penetration_comments(const FeScene &scene)
  {
    return {
      "clearjoint fe_stage: force-penetration curve, study " + to_string(scene.study) +
        ", journal loading " + to_string(scene.loading.journal),
      "force = total contact force of the FULL body: the modelled part's nodal contact "
      "forces times the symmetry factor (4 for the quarter model, 2 for the half model of "
      "the misalignment study, 1 for --full-model)",
      "force_support = the same force measured as the reaction of the supports (equilibrium "
      "check); force_load = the reaction on the journal's loaded set (the paper's measure)",
      "delta = push of the rigid obstacle beyond first touch",
      "friction_* = Coulomb's law checked at every contact node of the converged increment, "
      "as fractions of mu*lambda_max: cone_excess = max(|t_T| - mu*lambda)+, slip_law_error = "
      "max ||t_T| - mu*lambda| at slipping nodes, direction_error = max 1 + cos(t_T, slip); "
      "0 without friction",
      scene.contact.mu > 0.0 ? "Coulomb friction mu = " + format_value(scene.contact.mu) +
                                 " (stick/slip active set); slipping_contact_points of the active "
                                 "points slip, the rest stick" :
                               "frictionless contact (mu = 0)"};
  }

  Columns<AdaptiveCycleRow> adaptive_cycles_columns()
  {
    using C = AdaptiveCycleRow;
    return {{"cycle", "1", [](const C &c) { return double(c.cycle); }},
            {"n_cells", "1", [](const C &c) { return double(c.mesh.n_cells); }},
            {"n_dofs", "1", [](const C &c) { return double(c.mesh.n_dofs); }},
            {"force_at_delta_max", "N", [](const C &c) { return c.mesh.force; }},
            {"contact_iterations", "1",
             [](const C &c) { return double(c.mesh.contact_iterations); }},
            {"wall_time", "s", [](const C &c) { return c.mesh.wall_time; }}};
  }

  std::vector<std::string> adaptive_cycles_comments(const FeScene &scene, const RunResult &result)
  {
    const auto &M = scene.mesh;
    return {"clearjoint fe_stage: adaptive refinement, mesh.adaptive_cycles = " +
              std::to_string(M.adaptive_cycles) + ", adaptive_fraction = " +
              format_value(M.adaptive_fraction) + " (Kelly indicator, fixed fraction of the cells)",
            (result.adaptive_marking_delta > 0.0 ?
               "force_at_delta_max = the static F at the impact's expected delta_max, " +
                 format_value(result.adaptive_marking_delta) +
                 " m, where the meshes were marked (full body; " :
               std::string("force_at_delta_max = F at delta_max on that mesh (full body; ")) +
              "marking meshes pushed in mesh.adaptive_increments = " +
              std::to_string(M.adaptive_increments) + " steps); the last row is the run's mesh" +
              (M.adaptive_target_error > 0.0 ?
                 std::string("; target error ") + format_value(M.adaptive_target_error) +
                   (result.adaptive_target_reached ? " reached" : " NOT reached") :
                 std::string())};
  }

  nlohmann::json yield_check_json(const YieldCheck &y)
  {
    nlohmann::json bodies = nlohmann::json::array();
    for (const auto &b : y.bodies)
      bodies.push_back(
        {{"body", b.name},
         {"volume", {{"value", b.volume}, {"unit", "m^3"}}},
         {"volume_above_yield", {{"value", b.volume_above_yield}, {"unit", "m^3"}}},
         {"fraction_above_yield", b.volume > 0.0 ? b.volume_above_yield / b.volume : 0.0},
         {"max_von_mises", {{"value", b.max_von_mises}, {"unit", "Pa"}}},
         {"max_location", {{"value", b.max_location}, {"unit", "m"}}}});
    return {{"yield_stress", {{"value", y.yield_stress}, {"unit", "Pa"}}},
            {"exceeded", y.exceeded()},
            {"note", "linear-elastic model: von Mises above the yield stress means the result "
                     "is not valid there (field plastic_zone: volume fraction above yield)"},
            {"bodies", bodies}};
  }

  CaseOutput::CaseOutput(const FeScene &scene, const std::string &dir, const int argc, char **argv,
                         const PresetUse &preset)
    : scene_(scene)
    , dir_(dir)
  {
    manifest_ = std::make_unique<Manifest>("fe_stage", dir + "/manifest.json", argc, argv);
    if (!scene.source_file.empty())
      manifest_->add_input(scene.source_file);
    for (const auto &[k, v] : fe_library_versions())
      manifest_->set_library_version(k, v);
    if (!scene.geometry.mesh.empty())
      manifest_->add_input(scene.geometry.mesh);
    if (!preset.name.empty())
      {
        manifest_->add_input(preset.file);
        nlohmann::json o = nlohmann::json::object();
        for (const auto &[k, v] : preset.overrides)
          o[k] = v;
        manifest_->extra()["preset"] = {{"name", preset.name},
                                        {"file", preset.file},
                                        {"scene_keys", o}};
      }
    manifest_->extra()["scene"] = scene_to_json(scene);
    curve_ = std::make_unique<RecordCsv<IncrementRecord>>(dir + "/force_penetration.csv",
                                                          force_penetration_columns(),
                                                          force_penetration_comments(scene));
    curve_->write(IncrementRecord{});
    // Study impact: force_penetration.csv holds the quasi-static reference curve of the same
    // mesh; the time history goes to impact_history.csv (its t = 0 row comes from the run,
    // which knows the journal's mass: a deformable journal's is its mesh's).
    if (scene.study == Study::impact)
      impact_history_ =
        std::make_unique<RecordCsv<DynamicStepRecord>>(dir + "/impact_history.csv",
                                                       impact_history_columns(),
                                                       impact_history_comments(scene));
    // Study rolling: the time history and, at the end, the strain profile.
    if (scene.study == Study::rolling)
      {
        rolling_history_ =
          std::make_unique<RecordCsv<RollingStepRecord>>(dir + "/rolling_history.csv",
                                                         rolling_history_columns(),
                                                         rolling_history_comments(scene));
        rolling_history_->write(RollingStepRecord{});
      }
  }

  CaseOutput::~CaseOutput() = default;

  void CaseOutput::write_increment(const IncrementRecord &r) { curve_->write(r); }

  void CaseOutput::write_dynamic_step(const DynamicStepRecord &r)
  {
    if (impact_history_)
      impact_history_->write(r);
  }

  void CaseOutput::write_rolling_step(const RollingStepRecord &r)
  {
    if (rolling_history_)
      rolling_history_->write(r);
  }

  void CaseOutput::finish(const RunResult &result, const bool plots, const std::string &shown_dir)
  {
    curve_->commit(result.complete, result.message);
    manifest_->add_output(dir_ + "/force_penetration.csv");
    if (impact_history_)
      finish_impact(result, plots);
    if (rolling_history_)
      finish_rolling(result, plots);
    for (const auto &f : result.field_files)
      manifest_->add_output(f);
    // F–δ, linear and log–log (a warning, not a failure, if Python/matplotlib is missing)
    if (plots && !result.increments.empty() &&
        run_plot_script("fe", {dir_ + "/force_penetration.png", dir_}))
      manifest_->add_output(dir_ + "/force_penetration.png");
    if (!result.adaptive_cycles.empty())
      write_adaptive_cycles(result);
    record_run(result);
    manifest_->write(result.complete ? "complete" : "incomplete", result.message);
    log_result(result, shown_dir);
  }

  void CaseOutput::finish_impact(const RunResult &result, const bool plots)
  {
    impact_history_->commit(result.complete, result.message);
    manifest_->add_output(dir_ + "/impact_history.csv");
    manifest_->extra()["impact"] = impact_summary_json(result.impact);
    // F(t), δ(t), F(δ) over the quasi-static curve, and the energies
    if (plots && !result.dynamic_steps.empty() &&
        run_plot_script("fe_impact", {dir_ + "/impact.png", dir_}))
      manifest_->add_output(dir_ + "/impact.png");
  }

  void CaseOutput::finish_rolling(const RunResult &result, const bool plots)
  {
    rolling_history_->commit(result.complete, result.message);
    manifest_->add_output(dir_ + "/rolling_history.csv");
    const std::string profile_path = dir_ + "/rolling_strain_profile.csv";
    RecordCsv<StrainProfilePoint> profile(profile_path, strain_profile_columns(),
                                          strain_profile_comments());
    for (const auto &p : result.strain_profile)
      profile.write(p);
    profile.commit(result.complete, result.message);
    manifest_->add_output(profile_path);
    manifest_->extra()["rolling"] =
      rolling_summary_json(result.rolling,
                           result.rolling_steps.empty() ? nullptr : &result.rolling_steps.back());
    // the slip stages go to the plot as text: the manifest is written after it
    if (plots && !result.rolling_steps.empty() &&
        run_plot_script("fe_rolling",
                        {dir_ + "/rolling.png", dir_, manifest_->extra()["rolling"].dump()}))
      manifest_->add_output(dir_ + "/rolling.png");
  }

  /// One row per adaptive mesh: what a convergence plot needs (the last row is the recorded
  /// curve's mesh), and the error estimate from the sequence.
  void CaseOutput::write_adaptive_cycles(const RunResult &result)
  {
    const auto &M = scene_.mesh;
    const std::string path = dir_ + "/adaptive_cycles.csv";
    RecordCsv<AdaptiveCycleRow> cycles(path, adaptive_cycles_columns(),
                                       adaptive_cycles_comments(scene_, result));
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t k = 0; k < result.adaptive_cycles.size(); ++k)
      {
        const auto &c = result.adaptive_cycles[k];
        cycles.write({k, c});
        rows.push_back({{"n_cells", c.n_cells},
                        {"n_dofs", c.n_dofs},
                        {"force_at_delta_max", {{"value", c.force}, {"unit", "N"}}},
                        {"contact_iterations", c.contact_iterations},
                        {"wall_time", {{"value", c.wall_time}, {"unit", "s"}}}});
      }
    cycles.commit(true, "");
    manifest_->add_output(path);
    auto &a = manifest_->extra()["adaptive"];
    a = {{"cycles", rows},
         {"fraction", M.adaptive_fraction},
         {"marking_increments", M.adaptive_increments}};
    if (result.adaptive_marking_delta > 0.0)  // the impact's: its expected peak penetration
      a["marking_delta"] = {{"value", result.adaptive_marking_delta}, {"unit", "m"}};
    if (M.adaptive_target_error > 0.0)
      a["target_error"] = {{"value", M.adaptive_target_error},
                           {"unit", "1"},
                           {"reached", result.adaptive_target_reached},
                           {"max_cycles", M.adaptive_cycles}};
    if (result.adaptive_error >= 0.0)
      a["estimated_error_F_max"] = {{"value", result.adaptive_error},
                                    {"unit", "1"},
                                    {"method", result.adaptive_error_method}};
    if (result.adaptive_order > 0.0)
      a["extrapolated_force"] = {{"value", result.adaptive_extrapolated_force}, {"unit", "N"}};
  }

  /// The run's size, timing, friction and checks in the manifest.
  void CaseOutput::record_run(const RunResult &result)
  {
    auto &x = manifest_->extra();
    if (scene_.contact.sliding == Contact::Sliding::finite)
      x["finite_sliding"] = {{"pattern_rebuilds", result.sliding_rebuilds},
                             {"increments_solved_again", result.sliding_resolves}};
    x["n_dofs"] = result.n_dofs;
    x["n_cells"] = result.n_cells;
    x["n_mpi_ranks"] = result.n_ranks;
    x["symmetry_factor"] = result.symmetry_factor;
    x["h_min"] = {{"value", result.h_min}, {"unit", "m"}};
    x["setup_time"] = {{"value", result.setup_time}, {"unit", "s"}};
    // what the VTU's contact fields hold (docs/fe.md): Abaqus's CSTATUS codes
    x["contact_fields"] = {{"status_codes", {{"0", "open"}, {"1", "slip"}, {"2", "stick"}}},
                           {"note",
                            "contact_shear is the friction traction (zero without friction); "
                            "contact_slip is nonzero only at contact points"}};
    x["friction"] = {{"mu", scene_.contact.mu},
                     {"model",
                      scene_.contact.mu > 0.0 ? "Coulomb, stick/slip active set" : "frictionless"}};
    if (!result.increments.empty())
      {
        x["force_at_delta_max"] = {{"value", result.increments.back().force}, {"unit", "N"}};
        x["yield_check"] = yield_check_json(result.yield_check);
      }
  }

  void CaseOutput::log_result(const RunResult &result, const std::string &shown_dir) const
  {
    const double delta = result.increments.empty() ? 0.0 : result.increments.back().delta;
    const double force = result.increments.empty() ? 0.0 : result.increments.back().force;
    log::info("fe_stage: " + shown_dir + ": F(" + format_value(delta) +
              " m) = " + format_value(force) + " N, " + log::format_duration(result.wall_time));
    if (result.field_files.empty())
      return;
    log::info("fe_stage: fields: open " + shown_dir +
              "/fields/solution.pvd in ParaView (displacement, stress, von_mises_stress, " +
              (scene_.study == Study::rolling ?
                 "principal strains, equivalent_plastic_strain, von_mises_stress_max, "
                 "contact fields; each body in its own frame turning with it "
                 "(the bearing's co-rotating frame; a deformable journal as meshed, its "
                 "displacement in its frame), every " +
                   std::to_string(scene_.rolling.field_stride) + " steps and at the end)" :
                 std::string("plastic_zone, contact_pressure, contact_status, "
                             "contact_shear, contact_slip; one step per increment)")));
  }
}  // namespace clearjoint::fe
