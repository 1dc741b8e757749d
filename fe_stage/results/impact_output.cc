#include "fe_stage/results/impact_output.h"

#include "common/error.h"

namespace clearjoint::fe
{
  std::vector<std::string> impact_history_columns()
  {
    return {"time", "time_step", "delta", "delta_rate", "force", "force_support",
            "kinetic_journal", "kinetic_bearing", "strain_bearing", "strain_journal",
            "work_contact",
            "numerical_dissipation", "journal_iterations", "contact_iterations",
            "linear_iterations", "active_contact_points", "cuts", "wall_time"};
  }

  std::vector<std::string> impact_history_units()
  {
    return {"s", "s", "m", "m/s", "N", "N", "J", "J", "J", "J", "J", "J", "1", "1", "1", "1", "1",
            "s"};
  }

  std::vector<std::string> impact_history_comments(const FeScene &scene)
  {
    return {
      "clearjoint fe_stage: impact study (paper 3.2), " +
        std::string(scene.loading.journal == JournalLoading::rigid ? "rigid" : "deformable") +
        " journal launched at first touch "
      "toward the bearing (-y) at " + format_value(scene.impact.velocity) + " m/s; HHT alpha = " +
        format_value(scene.impact.alpha),
      "delta = the journal's displacement toward the bearing beyond first touch (a deformable "
      "journal's centre of mass); delta_rate > 0 approaching",
      "force = contact force on the journal (full body); force_support = the bearing supports' "
      "reaction (full body; differs from force by the bearing's inertia)",
      "kinetic_*, strain_* = energies of the full bodies (strain_journal 0 for a rigid journal); work_contact = net work of the "
      "contact forces on both bodies since t = 0 (trapezoidal; negative = lost where contact "
      "points close inside a step); numerical_dissipation = HHT's since t = 0 "
      "(work_contact - change of kinetic and strain energy; 0 to round-off for alpha = 0)",
      "energy balance: kinetic_journal + kinetic_bearing + strain_bearing + strain_journal + "
      "numerical_dissipation - work_contact = the initial kinetic energy",
      "journal_iterations = contact solves to find the journal's position in the step; "
      "cuts = halvings of the time step before it converged",
      scene.contact.mu > 0.0 ? "Coulomb friction mu = " + format_value(scene.contact.mu) :
                               std::string("frictionless contact (mu = 0)")};
  }

  std::vector<double> impact_history_row(const DynamicStepRecord &r)
  {
    return {r.time,
            r.time_step,
            r.delta,
            r.delta_rate,
            r.force,
            r.force_support,
            r.kinetic_journal,
            r.kinetic_bearing,
            r.strain_bearing,
            r.strain_journal,
            r.work_contact,
            r.numerical_dissipation,
            double(r.journal_iterations),
            double(r.contact_iterations),
            double(r.linear_iterations),
            double(r.n_active),
            double(r.cuts),
            r.wall_time};
  }

  std::vector<double> impact_history_start(const FeScene &scene)
  {
    const double m_J = rigid_journal_mass(scene);
    const double v = scene.impact.velocity;
    std::vector<double> row(impact_history_columns().size(), 0.0);
    row[3] = v;
    row[6] = 0.5 * m_J * v * v;
    return row;
  }

  // The columns impact_compare (mbd_stage) reads: v_in_m_per_s, peak_force_N, delta_max_m,
  // contact_duration_s, restitution, journal_mass_kg.
  std::vector<std::string> impact_sweep_columns()
  {
    return {"v_in_m_per_s", "peak_force_N", "delta_max_m", "contact_duration_s", "restitution",
            "journal_mass_kg", "time_of_peak_s", "delta_at_peak_m",
            "quasi_static_force_at_peak_delta_N", "dynamic_gap", "bearing_energy_left_J",
            "kinetic_initial_J", "numerical_dissipation_J", "work_contact_J", "time_step_s",
            "contact_period_s", "separated", "n_steps"};
  }

  std::vector<std::string> impact_sweep_units()
  {
    return {"m/s", "N", "m", "s", "1", "kg", "s", "m", "N", "1", "J", "J", "J", "J", "s", "s",
            "1", "1"};
  }

  std::vector<double> impact_sweep_row(const ImpactSummary &s)
  {
    return {s.velocity_in,
            s.peak_force,
            s.delta_max,
            s.contact_duration,
            s.restitution,
            s.journal_mass,
            s.time_of_peak,
            s.delta_at_peak,
            s.quasi_static_force_at_peak_delta,
            s.dynamic_gap,
            s.bearing_energy_left,
            s.kinetic_initial,
            s.numerical_dissipation,
            s.work_contact,
            s.time_step,
            s.contact_period,
            s.separated ? 1.0 : 0.0,
            double(s.n_steps)};
  }

  nlohmann::json impact_summary_json(const ImpactSummary &s)
  {
    auto q = [](double v, const char *unit) { return nlohmann::json{{"value", v}, {"unit", unit}}; };
    return {{"velocity_in", q(s.velocity_in, "m/s")},
            {"journal_mass", q(s.journal_mass, "kg")},
            {"contact_stiffness", q(s.contact_stiffness, "N/m")},
            {"contact_period", q(s.contact_period, "s")},
            {"time_step", q(s.time_step, "s")},
            {"alpha", s.alpha},
            {"peak_force", q(s.peak_force, "N")},
            {"time_of_peak", q(s.time_of_peak, "s")},
            {"delta_at_peak", q(s.delta_at_peak, "m")},
            {"delta_max", q(s.delta_max, "m")},
            {"quasi_static_force_at_peak_delta", q(s.quasi_static_force_at_peak_delta, "N")},
            {"dynamic_gap", q(s.dynamic_gap, "1")},
            {"separated", s.separated},
            {"contact_duration", q(s.contact_duration, "s")},
            {"velocity_out", q(s.velocity_out, "m/s")},
            {"restitution", q(s.restitution, "1")},
            {"kinetic_initial", q(s.kinetic_initial, "J")},
            {"bearing_energy_left", q(s.bearing_energy_left, "J")},
            {"numerical_dissipation", q(s.numerical_dissipation, "J")},
            {"work_contact", q(s.work_contact, "J")},
            {"n_steps", s.n_steps},
            {"notes",
             {"the journal starts at first touch (equivalent to the paper's coaxial start: "
              "free flight across the clearance changes nothing)",
              "dt = contact_period / impact.steps_per_period unless impact.time_step is given; "
              "contact_period = 2 pi sqrt(journal_mass / contact_stiffness), the secant "
              "stiffness of the quasi-static curve at the expected delta_max",
              "dynamic_gap = peak_force / (quasi-static force at delta_at_peak) - 1"}}};
  }
} // namespace clearjoint::fe
