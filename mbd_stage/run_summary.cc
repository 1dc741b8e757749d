#include "mbd_stage/run_summary.h"

#include <algorithm>
#include <cstdio>

namespace clearjoint::mbd
{
  namespace
  {
    std::string fmt(const char *f, const double v)
    {
      char buf[64];
      std::snprintf(buf, sizeof buf, f, v);
      return buf;
    }

    double num(const nlohmann::json &j, const char *key, const double fallback = 0.0)
    {
      const auto it = j.find(key);
      return it != j.end() && it->is_number() ? it->get<double>() : fallback;
    }
  } // namespace

  RunSummaryLines make_run_summary(const nlohmann::json &s, const std::string &output_dir,
                                   const bool plots)
  {
    RunSummaryLines out;
    const nlohmann::json &st = s.at("step_statistics");
    std::string head = "mbd_stage " + s.value("scene", std::string()) + ": " +
                       s.value("status", std::string()) + ", t = " +
                       fmt("%.6g", num(s.at("t_reached"), "value")) + " of " +
                       fmt("%.6g", num(s.at("duration"), "value")) + " s in " +
                       fmt("%.3g", num(s.at("wall_time"), "value")) + " s (" +
                       std::to_string(st.value("n_steps", 0L)) + " steps, " +
                       std::to_string(st.value("n_rhs_evaluations", 0L)) + " force evaluations, " +
                       s.at("integrator").value("method", std::string()) + " rtol " +
                       fmt("%.0e", num(s.at("integrator"), "rtol")) + ")";
    out.info.push_back(head);
    if (s.contains("failure"))
      out.info.push_back("  failure: " + s["failure"].get<std::string>());

    for (const nlohmann::json &cj : s.value("clearance_joints", nlohmann::json::array()))
    {
      const nlohmann::json &n = cj.at("n_impacts");
      const long radial = n.value("radial", 0L), pos = n.value("axial_pos", 0L),
                 neg = n.value("axial_neg", 0L);
      out.info.push_back("  " + cj.value("name", std::string()) + ": " + std::to_string(radial) +
                         " radial impacts, " + std::to_string(pos + neg) + " face impacts (+" +
                         std::to_string(pos) + "/-" + std::to_string(neg) +
                         "); peak normal force " + fmt("%.1f", num(cj.at("peak_normal_force"), "value")) +
                         " N");
      const long n_range = cj.value("law_out_of_range_accepted_steps", 0L);
      if (n_range > 0)
      {
        const nlohmann::json &o = cj.at("normal_model").value("out_of_range", nlohmann::json::object());
        out.warnings.push_back("  " + cj.value("name", std::string()) + ": " +
                               std::to_string(n_range) +
                               " accepted steps with a contact law outside its valid range "
                               "(policy " + o.value("policy", std::string("?")) +
                               ", deepest accepted " +
                               fmt("%.3g", 1e3 * num(o, "max_delta_accepted")) + " mm)");
      }
      if (const auto g = cj.find("depth_guard"); g != cj.end() && g->contains("n_evaluations_beyond_allowance"))
      {
        long n_beyond = 0;
        double deepest = 0.0;
        for (const auto &[c, v] : (*g)["n_evaluations_beyond_allowance"].items())
          n_beyond += v.get<long>();
        const nlohmann::json stages = g->value("max_delta_any_stage", nlohmann::json::object());
        for (const auto &[c, v] : stages.items())  // (not on the temporary: items() refers to it)
          deepest = std::max(deepest, v.get<double>());
        if (n_beyond > 0)
          out.warnings.push_back(
            "  " + cj.value("name", std::string()) + ": " + std::to_string(n_beyond) +
            " force evaluations (trial stages included) deeper than the depth guard allows (" +
            fmt("%.3g", 1e6 * num(*g, "allowance")) + " um, or the accepted depth + half of it; " +
            "deepest " + fmt("%.3g", 1e6 * deepest) + " um): a smaller integrator.max_step keeps " +
            "the steps shorter");
      }
      const nlohmann::json &fl = cj.at("impact_velocity_floor");
      const nlohmann::json &nf = fl.at("n_onsets_floored");
      const long floored = nf.value("radial", 0L) + nf.value("axial_pos", 0L) + nf.value("axial_neg", 0L);
      if (floored > 0)
        out.info.push_back("  " + cj.value("name", std::string()) + ": impact-velocity floor (" +
                           fmt("%.3g", num(fl, "radial")) + " m/s radial, " +
                           fmt("%.3g", num(fl, "axial")) + " m/s axial) used at " +
                           std::to_string(floored) + " of " + std::to_string(radial + pos + neg) +
                           " onsets");
    }
    const nlohmann::json &pk = s.at("peaks");
    if (!s.value("clearance_joints", nlohmann::json::array()).empty())
      out.info.push_back("  peak contact force " + fmt("%.1f", num(pk, "contact_force_max")) +
                         " N at t = " + fmt("%.5g", num(pk, "contact_force_max_time")) +
                         " s; first impact " + fmt("%.1f", num(pk, "first_impact_peak_force")) +
                         " N; deepest penetration " + fmt("%.3g", 1e6 * num(pk, "penetration_max")) +
                         " um");
    const nlohmann::json &e = s.at("energy");
    out.info.push_back("  energy: E0 = " + fmt("%.5g", num(e, "E0")) +
                       " J, balance error max " + fmt("%.2g", num(e, "max_relative_balance_error")) +
                       " of E0 (friction " + fmt("%.3g", num(e, "W_friction")) + " J, damping " +
                       fmt("%.3g", num(e, "W_damping")) + " J, drivers " +
                       fmt("%.3g", num(e, "W_drivers")) + " J)");
    out.info.push_back("  outputs: " + output_dir + "/{timeseries.csv, summary.json, manifest.json" +
                       std::string(plots ? ", plots/}" : "}"));
    return out;
  }
} // namespace clearjoint::mbd
