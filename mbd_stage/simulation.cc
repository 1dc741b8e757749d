#include "mbd_stage/simulation.h"

#include "common/error.h"
#include "common/interrupt.h"
#include "common/log.h"
#include "common/units.h"

#include <chrono>
#include <cmath>

namespace clearjoint::mbd
{
  std::vector<double> SimulationResult::column(const std::string &name) const
  {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name)
      {
        std::vector<double> v;
        v.reserve(rows.size());
        for (const auto &r : rows)
          v.push_back(r[c]);
        return v;
      }
    throw std::out_of_range("no column " + name);
  }

  namespace
  {
    const char *contact_names[3] = {"radial", "axial_pos", "axial_neg"};

    /// Rotation angle [rad] of e relative to e0 about the unit axis a (ground frame), in (−π, π].
    double relative_angle(const Vector4 &e, const Vector4 &e0, const Vector3 &a)
    {
      const Eigen::Quaterniond q(e[0], e[1], e[2], e[3]), q0(e0[0], e0[1], e0[2], e0[3]);
      const Eigen::Quaterniond r = q.normalized() * q0.normalized().conjugate();
      return std::remainder(2.0 * std::atan2(r.vec().dot(a), r.w()), 2.0 * units::pi);
    }
    /// The scene's budget (issue 16): thrown as a NumericalError from the step callback, so
    /// the run stops like any numerical failure (partial outputs kept, marked incomplete).
    void check_budget(const Scene &scene, const long n_steps, const double t,
                      const std::chrono::steady_clock::time_point start)
    {
      const auto where = [&] {
        return "at t = " + format_value(t) + " s of " + format_value(scene.duration) +
               " s; the scene's budget (keys budget.wall_time, budget.steps) stops runs that "
               "would otherwise go on for days — a step size collapsing to nothing usually "
               "means a stiff or badly scaled scene";
      };
      if (n_steps > scene.max_steps)
        throw NumericalError("step budget exceeded: " + std::to_string(scene.max_steps) +
                             " integrator steps taken " + where());
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (seconds > scene.max_wall_time)
        throw NumericalError("wall-clock budget exceeded: " + format_value(seconds) +
                             " s > budget.wall_time = " + format_value(scene.max_wall_time) +
                             " s " + where());
    }

    /// "" if every value is finite, else which column and time holds the first that is not.
    std::string first_non_finite(const SimulationResult &res)
    {
      for (const auto &row : res.rows)
        for (std::size_t c = 0; c < row.size(); ++c)
          if (!std::isfinite(row[c]))
            return "non-finite value (" + format_value(row[c]) + ") in output column '" +
                   res.columns[c] + "' at t = " + format_value(row[0]) + " s";
      return "";
    }
  } // namespace

  SimulationResult simulate(Scene &scene)
  {
    const auto start = std::chrono::steady_clock::now();
    MultibodySystem &sys = *scene.system;
    SimulationResult res;
    auto &C = res.columns;
    auto &U = res.units;
    const auto col = [&](const std::string &n, const std::string &u) {
      C.push_back(n);
      U.push_back(u);
    };
    col("t", "s");
    int slider = -1, crank = -1;
    if (scene.slider)
    {
      slider = sys.body_index(scene.slider->body);
      col("slider_position", "m");
      col("slider_velocity", "m/s");
      col("slider_acceleration", "m/s^2");
    }
    if (scene.crank)
    {
      crank = sys.body_index(scene.crank->body);
      col("crank_angle", "rad");
      col("crank_rate", "rad/s");
    }
    for (const auto &cj : sys.clearance_joints())
    {
      const std::string p = cj->name() + "_";
      col(p + "ecc_1", "m");
      col(p + "ecc_2", "m");
      col(p + "eccentricity", "m");
      col(p + "theta", "rad");
      for (int c = 0; c < 3; ++c)
      {
        const std::string q = p + contact_names[c] + "_";
        col(q + "delta", "m");
        col(q + "delta_dot", "m/s");
        col(q + "F_n", "N");
        col(q + "F_t", "N");
      }
    }
    std::vector<int> ground_joints;
    for (std::size_t j = 0; j < sys.joints().size(); ++j)
    {
      const Joint &J = sys.joints()[j];
      if (J.body_i() == ground_index || J.body_j() == ground_index)
      {
        ground_joints.push_back(static_cast<int>(j));
        for (const char *a : {"_Fx", "_Fy", "_Fz"})
          col(J.name() + a, "N");
      }
    }
    for (const char *n : {"E_kin", "E_pot", "E_el", "E_total", "W_friction", "W_damping",
                          "W_drivers", "energy_error"})
      col(n, "J");
    col("phi_max", "m|1");
    col("phi_dot_max", "m/s|1/s");
    col("euler_norm_error", "1");

    const Vector4 crank_e0 = crank >= 0 ? sys.initial_state().segment<4>(7 * crank + 3)
                                        : Vector4(1, 0, 0, 0);
    double crank_angle_prev = 0.0, crank_turns = 0.0;
    std::vector<double> ydot(static_cast<std::size_t>(sys.n_states()));
    SystemEvaluation ev;
    bool have_E0 = false;
    double peak_acc = 0.0, peak_delta = 0.0, peak_force_t = 0.0;
    std::vector<double> peak_F(sys.clearance_joints().size(), 0.0);

    const auto track_peaks = [&](const double t, const SystemEvaluation &e) {
      for (std::size_t c = 0; c < e.clearance.size(); ++c)
      {
        const ContactResult &r = e.clearance[c].contacts[0];
        if (r.F_n > peak_F[c])
          peak_F[c] = r.F_n;
        if (r.F_n > res.peak_contact_force)
        {
          res.peak_contact_force = r.F_n;
          peak_force_t = t;
        }
        peak_delta = std::max(peak_delta, r.delta);
        const ContactState &s = sys.clearance_joints()[c]->state(0);
        if (c == 0 && s.n_impacts == 1 && s.active)
          res.first_impact_peak_force = std::max(res.first_impact_peak_force, r.F_n);
      }
      if (slider >= 0)
        peak_acc = std::max(peak_acc, std::abs(e.acceleration_G(slider).dot(scene.slider->axis)));
    };

    const auto on_output = [&](const double t, const Eigen::VectorXd &y) {
      sys.rhs(t, y.data(), ydot.data(), &ev);
      std::vector<double> row;
      row.reserve(C.size());
      row.push_back(t);
      if (slider >= 0)
      {
        const Vector3 &a = scene.slider->axis;
        row.push_back(ev.bodies[slider].r.dot(a));
        row.push_back(ev.bodies[slider].v.dot(a));
        row.push_back(ev.acceleration_G(slider).dot(a));
      }
      if (crank >= 0)
      {
        const Vector3 &a = scene.crank->axis;
        const double ang = relative_angle(ev.bodies[crank].e, crank_e0, a);
        if (ang - crank_angle_prev > units::pi)
          crank_turns -= 1.0;
        else if (ang - crank_angle_prev < -units::pi)
          crank_turns += 1.0;
        crank_angle_prev = ang;
        row.push_back(ang + 2.0 * units::pi * crank_turns);
        row.push_back(ev.bodies[crank].w_G().dot(a));
      }
      for (const ClearanceOutput &o : ev.clearance)
      {
        row.push_back(o.ecc_1);
        row.push_back(o.ecc_2);
        row.push_back(std::hypot(o.ecc_1, o.ecc_2));
        row.push_back(o.theta);
        for (const ContactResult &r : o.contacts)
        {
          row.push_back(r.delta);
          row.push_back(r.delta_dot);
          row.push_back(r.F_n);
          row.push_back(r.F_t);
        }
      }
      for (const int j : ground_joints)
        for (int a = 0; a < 3; ++a)
          row.push_back(ev.joint_force_on_j[j][a]);
      const double E = ev.E_kin + ev.E_pot + ev.E_el;
      if (!have_E0)
      {
        res.E0 = E;
        have_E0 = true;
      }
      const double W = ev.W_friction + ev.W_damping + ev.W_drivers;
      const double err = E - W - res.E0;
      for (const double v : {ev.E_kin, ev.E_pot, ev.E_el, E, ev.W_friction, ev.W_damping,
                             ev.W_drivers, err})
        row.push_back(v);
      row.push_back(ev.phi_norm);
      row.push_back(ev.phi_dot_norm);
      row.push_back(ev.euler_norm_error);
      res.rows.push_back(std::move(row));
      res.max_relative_energy_error =
        std::max(res.max_relative_energy_error, std::abs(err) / std::max(std::abs(res.E0), 1e-300));
      res.max_energy_gain = std::max(res.max_energy_gain, E - res.E0 - ev.W_drivers);
      res.max_phi = std::max(res.max_phi, ev.phi_norm);
      res.max_euler_norm_error = std::max(res.max_euler_norm_error, ev.euler_norm_error);
      track_peaks(t, ev);
    };
    SystemEvaluation ev_step;
    long n_steps_taken = 0;
    const auto on_step = [&](const double t, const Eigen::VectorXd &y, const bool interior) {
      if (!interior)
      {
        check_budget(scene, ++n_steps_taken, t, start);
        interrupt::throw_if_requested("at t = " + format_value(t) + " s");
        sys.rhs(t, y.data(), ydot.data(), &ev_step);
        track_peaks(t, ev_step);
        return;
      }
      // Interior samples while in contact: only the contact-force peaks (no constraint solve).
      const std::vector<double> F = sys.radial_forces(y.data());
      for (std::size_t c = 0; c < F.size(); ++c)
      {
        peak_F[c] = std::max(peak_F[c], F[c]);
        if (F[c] > res.peak_contact_force)
        {
          res.peak_contact_force = F[c];
          peak_force_t = t;
        }
        const ContactState &s = sys.clearance_joints()[c]->state(0);
        if (c == 0 && s.n_impacts == 1 && s.active)
          res.first_impact_peak_force = std::max(res.first_impact_peak_force, F[c]);
      }
    };

    Integrator integrator(sys, scene.integrator);
    log::Progress progress("mbd_stage " + scene.name, scene.duration, "s");
    try
    {
      integrator.run(0.0, scene.duration, scene.output_interval,
                     [&](double t, const Eigen::VectorXd &y) {
                       on_output(t, y);
                       progress.update(t);
                     },
                     on_step);
      res.complete = true;
    }
    catch (const NumericalError &e)
    {
      res.failure = e.what();
    }
    // No run ends "complete" with a NaN or Inf in its outputs.
    if (const std::string bad = first_non_finite(res); res.complete && !bad.empty())
    {
      res.complete = false;
      res.failure = bad;
    }
    progress.finish();
    res.statistics = integrator.statistics();
    res.events = integrator.events();
    res.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // Summary
    nlohmann::json &s = res.summary;
    s["schema"] = "clearjoint.mbd_summary/1";
    s["scene"] = scene.name;
    s["scene_file"] = scene.file;
    s["description"] = scene.description;
    s["status"] = res.complete ? "complete" : "failed";
    if (!res.complete)
      s["failure"] = res.failure;
    s["duration"] = {{"value", scene.duration}, {"unit", "s"}};
    s["t_reached"] = {{"value", res.rows.empty() ? 0.0 : res.rows.back()[0]}, {"unit", "s"}};
    const IntegratorSettings &is = scene.integrator;
    s["integrator"] = {{"method", Integrator::method_name(is.method)},
                       {"rtol", is.rtol},
                       {"atol_position", is.atol_position},
                       {"atol_velocity", is.atol_velocity},
                       {"max_step", is.max_step},
                       {"output_interval", scene.output_interval},
                       {"units", {{"atol_position", "m"}, {"atol_velocity", "m/s"},
                                  {"max_step", "s (0: none)"}, {"output_interval", "s"}}}};
    const StepStatistics &st = res.statistics;
    s["step_statistics"] = {{"n_steps", st.n_steps},
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
    double W_f = 0, W_d = 0, W_drv = 0, E_end = 0, err_end = 0;
    if (!res.rows.empty())
    {
      const auto &last = res.rows.back();
      const auto at = [&](const std::string &n) {
        for (std::size_t c = 0; c < C.size(); ++c)
          if (C[c] == n)
            return last[c];
        return 0.0;
      };
      W_f = at("W_friction");
      W_d = at("W_damping");
      W_drv = at("W_drivers");
      E_end = at("E_total");
      err_end = at("energy_error");
    }
    s["energy"] = {{"E0", res.E0},
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
    s["constraints"] = {{"n_equations", sys.n_constraints()},
                        {"n_redundant", sys.n_redundant_constraints()},
                        {"max_abs_phi", res.max_phi},
                        {"max_euler_norm_error", res.max_euler_norm_error},
                        {"initial_velocity_correction", sys.initial_velocity_correction()},
                        {"units", {{"max_abs_phi", "m (position rows) or 1 (angle rows)"},
                                   {"initial_velocity_correction", "sqrt(kg) m/s (M-norm)"}}}};
    s["peaks"] = {{"slider_acceleration_max_abs", peak_acc},
                  {"contact_force_max", res.peak_contact_force},
                  {"contact_force_max_time", peak_force_t},
                  {"first_impact_peak_force", res.first_impact_peak_force},
                  {"penetration_max", peak_delta},
                  {"units", {{"slider_acceleration_max_abs", "m/s^2"},
                             {"contact_force_max", "N"}, {"contact_force_max_time", "s"},
                             {"first_impact_peak_force", "N"}, {"penetration_max", "m"}}}};
    nlohmann::json cjs = nlohmann::json::array();
    for (std::size_t c = 0; c < sys.clearance_joints().size(); ++c)
    {
      const ClearanceJoint &cj = *sys.clearance_joints()[c];
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
      j["n_impacts"] = {{"radial", cj.state(0).n_impacts},
                        {"axial_pos", cj.state(1).n_impacts},
                        {"axial_neg", cj.state(2).n_impacts}};
      j["peak_normal_force"] = {{"value", peak_F[c]}, {"unit", "N"}};
      // Counted at accepted states only (trial stages never count, docs/mbd.md §5).
      j["law_out_of_range_accepted_steps"] =
        cj.radial_model().n_out_of_range() + cj.axial_model().n_out_of_range();
      j["impact_velocity_floor"] = {
        {"radial", cj.radial_model().min_impact_velocity()},
        {"axial", cj.axial_model().min_impact_velocity()},
        {"unit", "m/s"},
        {"n_onsets_floored", {{"radial", cj.state(0).n_impact_velocity_floored},
                              {"axial_pos", cj.state(1).n_impact_velocity_floored},
                              {"axial_neg", cj.state(2).n_impact_velocity_floored}}},
        {"note", "onsets whose recorded impact velocity was below the floor: the damping "
                 "term of that contact period used the floor"}};
      const double guard = scene.integrator.depth_guard * cj.geometry().c_r();
      j["depth_guard"] = {{"fraction_of_c_r", scene.integrator.depth_guard},
                          {"allowance", guard},
                          {"max_delta_any_stage", {{"radial", cj.max_delta_any_stage(0)},
                                                   {"axial_pos", cj.max_delta_any_stage(1)},
                                                   {"axial_neg", cj.max_delta_any_stage(2)}}},
                          {"n_evaluations_beyond_allowance",
                           {{"radial", cj.n_evaluations_beyond_allowance(0)},
                            {"axial_pos", cj.n_evaluations_beyond_allowance(1)},
                            {"axial_neg", cj.n_evaluations_beyond_allowance(2)}}},
                          {"units", {{"allowance", "m"}, {"max_delta_any_stage", "m"}}},
                          {"note", "max_delta_any_stage includes the trial stages of every "
                                   "step; a step may reach max(allowance, accepted delta + "
                                   "allowance/2); n_evaluations_beyond_allowance counts "
                                   "evaluations (trial stages included) that went deeper than "
                                   "that"}};
      cjs.push_back(j);
    }
    s["clearance_joints"] = cjs;
    nlohmann::json evs = nlohmann::json::array();
    for (std::size_t i = 0; i < res.events.size() && i < 500; ++i)
    {
      const ContactEvent &e = res.events[i];
      evs.push_back({{"t", e.t}, {"joint", e.joint}, {"contact", contact_names[e.contact]},
                     {"kind", e.onset ? "onset" : "release"}, {"delta_dot", e.delta_dot}});
    }
    s["contact_events"] = {{"n_events", res.events.size()},
                           {"first_500", evs},
                           {"units", {{"t", "s"}, {"delta_dot", "m/s"}}}};
    s["wall_time"] = {{"value", res.wall_time}, {"unit", "s"}};
    return res;
  }
} // namespace clearjoint::mbd
