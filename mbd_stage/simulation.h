// Runs a scene: integrates it, evaluates the outputs of SPEC §4 at every output time (slider
// motion, crank, journal eccentricity, contact forces, ground reactions, energies and work,
// constraint violation, Euler-parameter norm error), and builds the summary (peaks, energy
// balance, step statistics, contact events, law-range violations).
#pragma once

#include "mbd_stage/scene.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace clearjoint::mbd
{
  struct SimulationResult
  {
    std::vector<std::string> columns, units;
    std::vector<std::vector<double>> rows;  ///< one per output time
    nlohmann::json summary;
    StepStatistics statistics;
    std::vector<ContactEvent> events;
    bool complete = false;
    std::string failure;  ///< NumericalError message if the run stopped early

    // Scalars the tests use (also in the summary).
    double E0 = 0.0;                       ///< [J] E_kin + E_pot + E_el at t = 0
    double max_relative_energy_error = 0;  ///< [1] max |E − W − E0| / |E0|
    double max_energy_gain = 0.0;          ///< [J] max (E − E0 − W_drivers): > 0 means energy
                                           ///< appeared without work put in
    double max_phi = 0.0;                  ///< max |Φ_k| over outputs
    double max_euler_norm_error = 0.0;     ///< [1]
    double peak_contact_force = 0.0;       ///< [N] max radial F_n over steps and outputs
    double first_impact_peak_force = 0.0;  ///< [N] max radial F_n during the first contact
    double wall_time = 0.0;                ///< [s]

    std::vector<double> column(const std::string &name) const;
  };

  /// Integrates the scene. NumericalError inside the integration is caught and reported in
  /// `failure` (complete = false) with the rows reached so far.
  SimulationResult simulate(Scene &scene);
} // namespace clearjoint::mbd
