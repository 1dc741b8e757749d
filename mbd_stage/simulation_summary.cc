#include "mbd_stage/simulation_summary.h"

#include "mbd_stage/output_rows.h"

namespace clearjoint::mbd
{
  namespace
  {
    nlohmann::json integrator_block(const Scene &scene)
    {
      const IntegratorSettings &is = scene.integrator;
      return {{"method", Integrator::method_name(is.method)},
              {"rtol", is.rtol},
              {"atol_position", is.atol_position},
              {"atol_velocity", is.atol_velocity},
              {"max_step", is.max_step},
              {"output_interval", scene.output_interval},
              {"units", {{"atol_position", "m"}, {"atol_velocity", "m/s"},
                         {"max_step", "s (0: none)"}, {"output_interval", "s"}}}};
    }

    nlohmann::json step_statistics_block(const StepStatistics &st)
    {
      return {{"n_steps", st.n_steps},
              {"n_rhs_evaluations", st.n_rhs},
              {"n_error_test_failures", st.n_error_test_failures},
              {"n_restarts_at_contact_events", st.n_restarts},
              {"n_root_returns", st.n_roots},
              {"n_event_state_steps", st.n_event_resteps},
              {"n_jacobian_evaluations", st.n_jacobians},
              {"n_nonlinear_convergence_failures", st.n_nonlinear_failures},
              {"h_min", st.h_min},
              {"h_max", st.h_max},
              {"units", {{"h_min", "s"}, {"h_max", "s"}}}};
    }

    /// The energy balance at the last output row (all 0 when the run wrote none).
    nlohmann::json energy_block(const SimulationResult &res)
    {
      double W_f = 0, W_d = 0, W_drv = 0, E_end = 0, err_end = 0;
      if (!res.rows.empty())
      {
        const auto &last = res.rows.back();
        const auto at = [&](const std::string &n) {
          for (std::size_t c = 0; c < res.columns.size(); ++c)
            if (res.columns[c] == n)
              return last[c];
          return 0.0;
        };
        W_f = at("W_friction");
        W_d = at("W_damping");
        W_drv = at("W_drivers");
        E_end = at("E_total");
        err_end = at("energy_error");
      }
      return {{"E0", res.E0},
              {"E_total_final", E_end},
              {"W_friction", W_f},
              {"W_damping", W_d},
              {"W_drivers", W_drv},
              {"balance_error_final", err_end},
              {"max_relative_balance_error", res.max_relative_energy_error},
              {"max_gain_without_work", res.max_energy_gain},
              {"note", "E_total = E_kin + E_pot (zero at z = 0) + E_el; balance error = "
                       "E_total - (W_friction + W_damping + W_drivers) - E0"},
              {"units", "J (relative: 1)"}};
    }

    nlohmann::json constraints_block(const MultibodySystem &sys, const SimulationResult &res)
    {
      return {{"n_equations", sys.n_constraints()},
              {"n_redundant", sys.n_redundant_constraints()},
              {"max_abs_phi", res.max_phi},
              {"max_euler_norm_error", res.max_euler_norm_error},
              {"initial_velocity_correction", sys.initial_velocity_correction()},
              {"units", {{"max_abs_phi", "m (position rows) or 1 (angle rows)"},
                         {"initial_velocity_correction", "sqrt(kg) m/s (M-norm)"}}}};
    }

    nlohmann::json peaks_block(const RunPeaks &peaks)
    {
      return {{"slider_acceleration_max_abs", peaks.slider_acceleration},
              {"contact_force_max", peaks.contact_force},
              {"contact_force_max_time", peaks.contact_force_time},
              {"first_impact_peak_force", peaks.first_impact_force},
              {"penetration_max", peaks.penetration},
              {"units", {{"slider_acceleration_max_abs", "m/s^2"},
                         {"contact_force_max", "N"}, {"contact_force_max_time", "s"},
                         {"first_impact_peak_force", "N"}, {"penetration_max", "m"}}}};
    }

    /// One value per contact of a clearance joint, keyed by the contact's name.
    template <typename PerContact>
    nlohmann::json per_contact(const PerContact &value)
    {
      return {{contact_names[0], value(0)},
              {contact_names[1], value(1)},
              {contact_names[2], value(2)}};
    }

    nlohmann::json depth_guard_block(const ClearanceJoint &cj, const double fraction)
    {
      return {{"fraction_of_c_r", fraction},
              {"allowance", fraction * cj.geometry().c_r()},
              {"max_delta_any_stage",
               per_contact([&](int c) { return cj.max_delta_any_stage(c); })},
              {"n_evaluations_beyond_allowance",
               per_contact([&](int c) { return cj.n_evaluations_beyond_allowance(c); })},
              {"units", {{"allowance", "m"}, {"max_delta_any_stage", "m"}}},
              {"note", "max_delta_any_stage includes the trial stages of every "
                       "step; a step may reach max(allowance, accepted delta + "
                       "allowance/2); n_evaluations_beyond_allowance counts "
                       "evaluations (trial stages included) that went deeper than "
                       "that"}};
    }

    nlohmann::json clearance_joint_block(const ClearanceJoint &cj, const double peak_force,
                                         const double depth_guard)
    {
      nlohmann::json j;
      j["name"] = cj.name();
      j["geometry"] = {{"R_B", cj.geometry().R_B}, {"R_J", cj.geometry().R_J},
                       {"L_B", cj.geometry().L_B}, {"L_J", cj.geometry().L_J},
                       {"c_r", cj.geometry().c_r()}, {"c_a", cj.geometry().c_a()},
                       {"unit", "m"}};
      j["normal_model"] = cj.radial_model().describe();
      j["axial_model"] = cj.axial_model().describe();
      j["friction"] = {{"mu", cj.friction().mu}, {"v0", cj.friction().v0},
                       {"v1", cj.friction().v1}, {"units", {{"v0", "m/s"}, {"v1", "m/s"}}}};
      j["n_impacts"] = per_contact([&](int c) { return cj.state(c).n_impacts; });
      j["peak_normal_force"] = {{"value", peak_force}, {"unit", "N"}};
      // Counted at accepted states only (trial stages never count, docs/mbd.md §5).
      j["law_out_of_range_accepted_steps"] =
        cj.radial_model().n_out_of_range() + cj.axial_model().n_out_of_range();
      j["impact_velocity_floor"] = {
        {"radial", cj.radial_model().min_impact_velocity()},
        {"axial", cj.axial_model().min_impact_velocity()},
        {"unit", "m/s"},
        {"n_onsets_floored",
         per_contact([&](int c) { return cj.state(c).n_impact_velocity_floored; })},
        {"note", "onsets whose recorded impact velocity was below the floor: the damping "
                 "term of that contact period used the floor"}};
      j["depth_guard"] = depth_guard_block(cj, depth_guard);
      return j;
    }

    /// The number of contact events and the first 500 of them (a chattering contact can
    /// produce many thousands).
    nlohmann::json contact_events_block(const std::vector<ContactEvent> &events)
    {
      nlohmann::json first = nlohmann::json::array();
      for (std::size_t i = 0; i < events.size() && i < 500; ++i)
      {
        const ContactEvent &e = events[i];
        first.push_back({{"t", e.t}, {"joint", e.joint}, {"contact", contact_names[e.contact]},
                         {"kind", e.onset ? "onset" : "release"}, {"delta_dot", e.delta_dot}});
      }
      return {{"n_events", events.size()},
              {"first_500", first},
              {"units", {{"t", "s"}, {"delta_dot", "m/s"}}}};
    }
  } // namespace

  nlohmann::json make_summary(const Scene &scene, const SimulationResult &res,
                              const RunPeaks &peaks)
  {
    const MultibodySystem &sys = *scene.system;
    nlohmann::json s;
    s["schema"] = "clearjoint.mbd_summary/1";
    s["scene"] = scene.name;
    s["scene_file"] = scene.file;
    s["description"] = scene.description;
    s["status"] = res.complete ? "complete" : "failed";
    if (!res.complete)
      s["failure"] = res.failure;
    s["duration"] = {{"value", scene.duration}, {"unit", "s"}};
    s["t_reached"] = {{"value", res.rows.empty() ? 0.0 : res.rows.back()[0]}, {"unit", "s"}};
    s["integrator"] = integrator_block(scene);
    s["step_statistics"] = step_statistics_block(res.statistics);
    s["energy"] = energy_block(res);
    s["constraints"] = constraints_block(sys, res);
    s["peaks"] = peaks_block(peaks);
    nlohmann::json joints = nlohmann::json::array();
    for (std::size_t c = 0; c < sys.clearance_joints().size(); ++c)
      joints.push_back(clearance_joint_block(*sys.clearance_joints()[c], peaks.joint_force[c],
                                             scene.integrator.depth_guard));
    s["clearance_joints"] = joints;
    s["contact_events"] = contact_events_block(res.events);
    s["wall_time"] = {{"value", res.wall_time}, {"unit", "s"}};
    return s;
  }
} // namespace clearjoint::mbd
