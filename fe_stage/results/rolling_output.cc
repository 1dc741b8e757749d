#include "fe_stage/results/rolling_output.h"

#include "common/error.h"

namespace clearjoint::fe
{
  Columns<RollingStepRecord> rolling_history_columns()
  {
    using R = RollingStepRecord;
    return {{"time", "s", [](const R &r) { return r.time; }},
            {"delta", "m", [](const R &r) { return r.delta; }},
            {"force_normal", "N", [](const R &r) { return r.force_normal; }},
            {"force_tangential", "N", [](const R &r) { return r.force_tangential; }},
            {"phi", "rad", [](const R &r) { return r.phi; }},
            {"gamma", "rad", [](const R &r) { return r.gamma; }},
            {"phi_rate", "rad/s", [](const R &r) { return r.phi_rate; }},
            {"gamma_rate", "rad/s", [](const R &r) { return r.gamma_rate; }},
            {"slip_speed", "m/s", [](const R &r) { return r.slip_speed; }},
            {"torque_drive", "N m", [](const R &r) { return r.torque_drive; }},
            {"torque_journal", "N m", [](const R &r) { return r.torque_journal; }},
            {"work_drive", "J", [](const R &r) { return r.work_drive; }},
            {"work_push", "J", [](const R &r) { return r.work_push; }},
            {"elastic_energy", "J", [](const R &r) { return r.elastic_energy; }},
            {"plastic_dissipation", "J", [](const R &r) { return r.plastic_dissipation; }},
            {"friction_dissipation", "J", [](const R &r) { return r.friction_dissipation; }},
            {"kinetic_energy", "J", [](const R &r) { return r.kinetic_energy; }},
            {"energy_balance_error", "J", [](const R &r) { return r.energy_balance_error; }},
            {"work_frame", "J", [](const R &r) { return r.work_frame; }},
            {"frame_balance_error", "J", [](const R &r) { return r.frame_balance_error; }},
            {"max_plastic_strain", "1", [](const R &r) { return r.max_plastic_strain; }},
            {"max_strain", "1", [](const R &r) { return r.max_strain; }},
            {"plastic_volume", "m^3", [](const R &r) { return r.plastic_volume; }},
            {"active_contact_points", "1", [](const R &r) { return double(r.n_active); }},
            {"slipping_contact_points", "1", [](const R &r) { return double(r.n_slip); }},
            {"spin_iterations", "1", [](const R &r) { return double(r.spin_iterations); }},
            {"newton_iterations", "1", [](const R &r) { return double(r.newton_iterations); }},
            {"line_search_steps", "1", [](const R &r) { return double(r.line_search_steps); }},
            {"contact_iterations", "1", [](const R &r) { return double(r.contact_iterations); }},
            {"linear_iterations", "1", [](const R &r) { return double(r.linear_iterations); }},
            {"cuts", "1", [](const R &r) { return double(r.cuts); }},
            {"spin_coupled", "1", [](const R &r) { return double(r.spin_coupled); }},
            {"phi_paper", "rad", [](const R &r) { return r.phi_paper; }},
            {"gamma_paper", "rad", [](const R &r) { return r.gamma_paper; }},
            {"phi_rate_paper", "rad/s", [](const R &r) { return r.phi_rate_paper; }},
            {"gamma_rate_paper", "rad/s", [](const R &r) { return r.gamma_rate_paper; }},
            {"wall_time", "s", [](const R &r) { return r.wall_time; }}};
  }

  std::vector<std::string> rolling_history_comments(const FeScene &scene)
  {
    const auto &R = scene.rolling;
    const bool rigid = scene.loading.journal == JournalLoading::rigid;
    return {
      "clearjoint fe_stage: rolling study (paper 3.4): the bearing turns at omega_B = " +
        format_value(R.omega_B) + " rad/s; the " + (rigid ? "rigid" : "deformable") +
        " journal's axis is pushed along -y to " + format_value(scene.loading.delta_max) +
        " m at " + format_value(R.ramp_time) +
        " s and turns freely, driven by Coulomb friction mu = " + format_value(scene.contact.mu),
      rigid ? "elastoplastic bearing (von Mises, isotropic hardening table), computed in its "
              "co-rotating frame; angles counter-clockwise about +z in the fixed frame" :
              "elastoplastic bearing and journal (von Mises, isotropic hardening table), each "
              "computed in its own frame turning with it (the journal's core clamped in its "
              "frame); angles counter-clockwise about +z in the fixed frame",
      "force_normal = contact force on the journal along +y, force_tangential along +x (full "
      "body); slip_speed = omega_B (R_B + delta) - gamma_rate R_J (0: rolling without slip; a "
      "deformable journal: omega_B r_B - gamma_rate r_J with the radii from each axis to the "
      "contact node carrying the largest normal force)",
      "torque_drive = the supports' torque on the bearing; torque_journal = the contact's "
      "torque on the journal; work_drive = int torque_drive dphi, work_push = int force dδ",
      "energy balance: work_drive + work_push = elastic_energy + plastic_dissipation + "
      "friction_dissipation + kinetic_energy + energy_balance_error; in the bearing's frame "
      "work_frame (the contact forces' work on it) = elastic_energy + plastic_dissipation + "
      "frame_balance_error (the bearing's own elastic and plastic energy)",
      "phi_paper, gamma_paper = paper Eqs. 4-6 on the bore node and the journal point that "
      "touch at t = 0 (bottom of the mid-plane), from their displacement vectors; "
      "*_rate_paper = Eqs. 7-8 (angle / t); phi, gamma = the exact angles"};
  }

  Columns<StrainProfilePoint> strain_profile_columns()
  {
    using P = StrainProfilePoint;
    return {{"angle", "rad", [](const P &p) { return p.angle; }},
            {"arc", "m", [](const P &p) { return p.arc; }},
            {"strain_radial", "1", [](const P &p) { return p.strain_radial; }},
            {"strain_tangential", "1", [](const P &p) { return p.strain_tangential; }},
            {"strain_axial", "1", [](const P &p) { return p.strain_axial; }},
            {"plastic_strain", "1", [](const P &p) { return p.plastic_strain; }},
            {"von_mises", "Pa", [](const P &p) { return p.von_mises; }},
            {"body", "1", [](const P &p) { return double(p.body); }}};
  }

  std::vector<std::string> strain_profile_comments()
  {
    return {"clearjoint fe_stage: the bore's (body 0) and a deformable "
            "journal's (body 1) strains across the contact zone at the end "
            "of the rolling study (paper Fig. 12), axial mid-plane, angle "
            "from the contact point about the body's own axis "
            "(counter-clockwise, fixed frame), arc = R_B or R_J times it; "
            "strains are total; plastic_strain and von_mises are the largest of the "
            "sample's cell, each of its material points with its own plastic strain"};
  }

  nlohmann::json rolling_summary_json(const RollingSummary &s, const RollingStepRecord *last)
  {
    nlohmann::json j = {
      {"journal_inertia", {{"value", s.journal_inertia}, {"unit", "kg m^2"}}},
      {"rolling_rate",
       {{"value", s.rolling_rate},
        {"unit", "rad/s"},
        {"meaning", "omega_B (R_B + delta_max) / R_J: the spin of rolling without slip at the end "
                    "of the push"}}},
      {"time_step", {{"value", s.time_step}, {"unit", "s"}}},
      {"slip_stages",
       {{"found", s.stages_found},
        {"slip_speed_max", {{"value", s.slip_speed_max}, {"unit", "m/s"}}},
        {"end_of_slip",
         {{"value", s.end_of_slip},
          {"unit", "s"},
          {"meaning", "the slip speed first falls below half its largest value"}}},
        {"settled",
         {{"value", s.settled},
          {"unit", "s"},
          {"meaning", "from here the slip speed stays within 5 % of its largest "
                      "value about its final value"}}},
        {"slip_speed_final", {{"value", s.slip_speed_final}, {"unit", "m/s"}}}}},
      {"max_plastic_strain", s.max_plastic_strain},
      {"max_strain",
       {{"value", s.max_strain},
        {"meaning", "largest principal total strain: small strain is accurate "
                    "while this stays well below ~0.01"}}},
      {"energy_balance_error",
       {{"value", s.energy_balance_error},
        {"meaning", "|error| / (|work_drive| + |work_push|) at the end"}}}};
    if (last)
      j["final"] = {{"time", last->time},
                    {"force_normal", last->force_normal},
                    {"gamma_rate", last->gamma_rate},
                    {"phi_rate_paper", last->phi_rate_paper},
                    {"gamma_rate_paper", last->gamma_rate_paper},
                    {"work_drive", last->work_drive},
                    {"work_push", last->work_push},
                    {"elastic_energy", last->elastic_energy},
                    {"plastic_dissipation", last->plastic_dissipation},
                    {"friction_dissipation", last->friction_dissipation},
                    {"units", "s, N, rad/s, rad/s, rad/s, J, J, J, J, J"}};
    return j;
  }
}  // namespace clearjoint::fe
