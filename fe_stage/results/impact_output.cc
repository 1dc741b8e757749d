#include "fe_stage/results/impact_output.h"

#include "common/error.h"

namespace clearjoint::fe
{
  namespace
  {
    /// "moderate_dissipation: HHT alpha = …, beta = …, gamma = …" (α overridden: said so), or
    /// "quasi_static: backward Euler". The scene is valid here.
    std::string integrator_description(const FeScene &scene)
    {
      const auto &I = scene.impact;
      const HhtAlpha h = HhtAlpha::for_application(I.application, I.alpha);
      std::string s = std::string("Abaqus application ") + application_name(I.application) + ": ";
      if (h.op() == HhtAlpha::Operator::backward_euler)
        return s + "backward Euler";
      return s + "HHT alpha = " + format_value(h.alpha()) + (I.alpha ? " (given)" : "") +
             ", beta = " + format_value(h.beta()) + ", gamma = " + format_value(h.gamma());
    }
  }  // namespace

  Columns<DynamicStepRecord> impact_history_columns()
  {
    using R = DynamicStepRecord;
    return {{"time", "s", [](const R &r) { return r.time; }},
            {"time_step", "s", [](const R &r) { return r.time_step; }},
            {"delta", "m", [](const R &r) { return r.delta; }},
            {"delta_rate", "m/s", [](const R &r) { return r.delta_rate; }},
            {"force", "N", [](const R &r) { return r.force; }},
            {"force_support", "N", [](const R &r) { return r.force_support; }},
            {"kinetic_journal", "J", [](const R &r) { return r.kinetic_journal; }},
            {"kinetic_bearing", "J", [](const R &r) { return r.kinetic_bearing; }},
            {"strain_bearing", "J", [](const R &r) { return r.strain_bearing; }},
            {"strain_journal", "J", [](const R &r) { return r.strain_journal; }},
            {"work_contact", "J", [](const R &r) { return r.work_contact; }},
            {"numerical_dissipation", "J", [](const R &r) { return r.numerical_dissipation; }},
            {"journal_iterations", "1", [](const R &r) { return double(r.journal_iterations); }},
            {"contact_iterations", "1", [](const R &r) { return double(r.contact_iterations); }},
            {"linear_iterations", "1", [](const R &r) { return double(r.linear_iterations); }},
            {"active_contact_points", "1", [](const R &r) { return double(r.n_active); }},
            {"cuts", "1", [](const R &r) { return double(r.cuts); }},
            {"wall_time", "s", [](const R &r) { return r.wall_time; }}};
  }

  std::vector<std::string> impact_history_comments(const FeScene &scene)
  {
    return {
      "clearjoint fe_stage: impact study (paper 3.2), " +
        std::string(scene.loading.journal == JournalLoading::rigid ? "rigid" : "deformable") +
        " journal launched at first touch "
        "toward the bearing (-y) at " +
        format_value(scene.impact.velocity) +
        " m/s; " + integrator_description(scene),
      "delta = the journal's displacement toward the bearing beyond first touch (a deformable "
      "journal's centre of mass); delta_rate > 0 approaching",
      "force = contact force on the journal (full body); force_support = the bearing supports' "
      "reaction (full body; differs from force by the bearing's inertia)",
      "kinetic_*, strain_* = energies of the full bodies (strain_journal 0 for a rigid journal); "
      "work_contact = net work of the "
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

  // The columns impact_compare (mbd_stage) reads: v_in_m_per_s, peak_force_N, delta_max_m,
  // contact_duration_s, restitution, journal_mass_kg.
  Columns<ImpactSummary> impact_sweep_columns()
  {
    using S = ImpactSummary;
    return {{"v_in_m_per_s", "m/s", [](const S &s) { return s.velocity_in; }},
            {"peak_force_N", "N", [](const S &s) { return s.peak_force; }},
            {"delta_max_m", "m", [](const S &s) { return s.delta_max; }},
            {"contact_duration_s", "s", [](const S &s) { return s.contact_duration; }},
            {"restitution", "1", [](const S &s) { return s.restitution; }},
            {"journal_mass_kg", "kg", [](const S &s) { return s.journal_mass; }},
            {"time_of_peak_s", "s", [](const S &s) { return s.time_of_peak; }},
            {"delta_at_peak_m", "m", [](const S &s) { return s.delta_at_peak; }},
            {"quasi_static_force_at_peak_delta_N", "N",
             [](const S &s) { return s.quasi_static_force_at_peak_delta; }},
            {"dynamic_gap", "1", [](const S &s) { return s.dynamic_gap; }},
            {"impulse_Ns", "N s", [](const S &s) { return s.impulse; }},
            {"mean_force_N", "N", [](const S &s) { return s.mean_force; }},
            {"bearing_energy_left_J", "J", [](const S &s) { return s.bearing_energy_left; }},
            {"kinetic_initial_J", "J", [](const S &s) { return s.kinetic_initial; }},
            {"numerical_dissipation_J", "J", [](const S &s) { return s.numerical_dissipation; }},
            {"work_contact_J", "J", [](const S &s) { return s.work_contact; }},
            {"time_step_s", "s", [](const S &s) { return s.time_step; }},
            {"contact_period_s", "s", [](const S &s) { return s.contact_period; }},
            {"separated", "1", [](const S &s) { return s.separated ? 1.0 : 0.0; }},
            {"n_steps", "1", [](const S &s) { return double(s.n_steps); }}};
  }

  std::vector<std::string> impact_sweep_comments()
  {
    return {"fe_stage impact sweep (paper 3.2); one folder per case (every velocity at every "
            "journal mass)",
            "impulse = integral of the contact force over the steps (trapezoidal); mean_force = "
            "impulse / contact_duration",
            "dynamic_gap = peak force / quasi-static force at the same delta - 1; "
            "restitution = journal speed away / speed in (0 if it had not left the "
            "bearing: separated = 0)",
            "bearing_energy_left = kinetic + strain energy of the bearing's vibration "
            "when the journal left"};
  }

  nlohmann::json impact_summary_json(const ImpactSummary &s)
  {
    auto q = [](double v, const char *unit) {
      return nlohmann::json{{"value", v}, {"unit", unit}};
    };
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
            {"impulse", q(s.impulse, "N s")},
            {"mean_force", q(s.mean_force, "N")},
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
}  // namespace clearjoint::fe
