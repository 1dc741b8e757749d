// The FE contact model's interface: run one scene (one force–penetration curve) and get the
// rows of force_penetration.csv back. No deal.II types here, so tests and main() compile fast;
// the deal.II code lives in fe_stage/{mesh,core,contact,solve,results}/ (fe_stage/README.md).
#pragma once

#include "fe_stage/scene.h"

#include <mpi.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// One converged load increment.
  struct IncrementRecord
  {
    double delta = 0.0;          // [m] push beyond first touch
    double force = 0.0;          // [N] contact force of the FULL body (symmetry factor applied)
    double force_support = 0.0;  // [N] reaction at the supports (fixed set), full body
    double force_load = 0.0;     // [N] reaction on the journal's loaded set (the paper's measure;
                                 //     rigid journal: the obstacle's force), full body
    unsigned int contact_iterations = 0;  // active-set iterations
    unsigned int linear_iterations = 0;   // summed over the active-set iterations
    unsigned int n_active = 0;            // active contact nodes (of the modelled part)
    unsigned int n_slip = 0;              // of these, slipping (friction); the rest stick
    double max_penetration = 0.0;         // [m] largest penetration at any contact candidate node
    double pressure_min = 0.0;            // [Pa] min/max nodal pressure over the active nodes
    double pressure_max = 0.0;
    double wall_time = 0.0;  // [s] since the start of the run
    // Coulomb's law at the converged state (contact.mu > 0; all ranks), as fractions of
    // μ·λ_max (λ_max the largest nodal normal force): the largest |t_T| − μλ at an active node
    // (the cone; ≤ 0 inside it), the largest ||t_T| − μλ| at a slipping node, and the largest
    // 1 + t̂_T·ŝ_T at a slipping node that slid in this increment (0: the friction force
    // exactly opposes the slip; sliding means more than 1e-6 of the increment's push).
    double friction_cone_excess = 0.0;
    double friction_slip_law_error = 0.0;
    double friction_direction_error = 0.0;
  };

  /// Where the linear-elastic von Mises stress exceeds the scene's yield stress, per body, at
  /// the last converged increment (the model stays elastic: this says where it stops being
  /// valid). Volumes are of the full body (symmetry factor applied).
  struct YieldCheck
  {
    struct Body
    {
      std::string name;                      // bearing, journal, block, indenter
      double volume = 0.0;                   // [m^3]
      double volume_above_yield = 0.0;       // [m^3]
      double max_von_mises = 0.0;            // [Pa] largest at a quadrature point
      std::array<double, 3> max_location{};  // [m] where (the modelled part's coordinates)
    };
    double yield_stress = 0.0;  // [Pa] scene material.yield_stress
    std::vector<Body> bodies;
    bool exceeded() const
    {
      for (const auto &b : bodies)
        if (b.volume_above_yield > 0.0)
          return true;
      return false;
    }
  };

  /// One adaptive refinement cycle (mesh.adaptive_cycles): the curve computed on its mesh.
  struct AdaptiveCycle
  {
    unsigned long n_dofs = 0;
    unsigned long n_cells = 0;
    double force = 0.0;                   // [N] F(δ_max), full body
    unsigned int contact_iterations = 0;  // over the curve's increments
    double wall_time = 0.0;               // [s] of the curve on this mesh
  };

  /// One converged time step of the impact study (study impact). Forces and energies are of
  /// the FULL bodies (symmetry factor applied); δ > 0 is the journal's displacement toward the
  /// bearing (−y) beyond first touch.
  struct DynamicStepRecord
  {
    unsigned int step = 0;
    double time = 0.0;                   // [s] t_{n+1}
    double time_step = 0.0;              // [s] Δt of this step
    double delta = 0.0;                  // [m] journal displacement beyond first touch (deformable:
                                         //     of its centre of mass)
    double delta_rate = 0.0;             // [m/s] dδ/dt (> 0 approaching)
    double force = 0.0;                  // [N] contact force at t_{n+1} (on the journal, +y)
    double force_support = 0.0;          // [N] reaction of the bearing's supports at t_{n+1}
    double kinetic_journal = 0.0;        // [J] ½ m_J δ̇² (deformable: ½ v_Jᵀ M v_J)
    double kinetic_bearing = 0.0;        // [J] ½ vᵀMv
    double strain_bearing = 0.0;         // [J] ½ uᵀKu of the bearing
    double strain_journal = 0.0;         // [J] of a deformable journal (0: rigid)
    double work_contact = 0.0;           // [J] net work of the contact forces on both bodies since
                                         //     t = 0 (trapezoidal; ≤ 0: lost where nodes close)
    double numerical_dissipation = 0.0;  // [J] HHT's, since t = 0: W_c − ΔT − ΔU (EnergyLedger;
                                         //     0 to round-off for α = 0)
    unsigned int journal_iterations = 0;  // contact solves to find the journal's position
    unsigned int contact_iterations = 0;  // active-set iterations over those solves
    unsigned int linear_iterations = 0;
    unsigned int n_active = 0;
    unsigned int cuts = 0;   // halvings of Δt before this step converged
    double wall_time = 0.0;  // [s] since the start of the run
  };

  /// What an impact case found (study impact); NaN/false where the run did not get there.
  struct ImpactSummary
  {
    double velocity_in = 0.0;        // [m/s] at first touch
    double journal_mass = 0.0;       // [kg] full body (rigid: impact.journal_mass or ρ π R_J² L_J)
    double contact_stiffness = 0.0;  // [N/m] secant k_c = F(δ_est)/δ_est of the static curve
    double contact_period = 0.0;     // [s] T_c = 2π √(m_J/k_c)
    double time_step = 0.0;          // [s] Δt at the start
    double alpha = 0.0;
    double peak_force = 0.0;                        // [N]
    double time_of_peak = 0.0;                      // [s]
    double delta_at_peak = 0.0;                     // [m]
    double delta_max = 0.0;                         // [m] deepest penetration
    double quasi_static_force_at_peak_delta = 0.0;  // [N] static curve at δ(peak)
    double dynamic_gap = 0.0;            // [1] (F_peak − F_qs(δ_peak)) / F_qs(δ_peak)
    bool separated = false;              // the journal left the bearing before the end time
    double contact_duration = 0.0;       // [s] from first touch to F = 0 (interpolated)
    double velocity_out = 0.0;           // [m/s] journal speed away from the bearing (separated)
    double restitution = 0.0;            // [1] v_out / v_in (separated; else 0)
    double impulse = 0.0;     // [N s] ∫F dt over the steps (trapezoidal; F = 0 at t = 0)
    double mean_force = 0.0;  // [N] impulse / contact_duration (separated; else 0)
    double kinetic_initial = 0.0;        // [J] ½ m_J v²
    double bearing_energy_left = 0.0;    // [J] kinetic + strain of the bearing at the end
    double numerical_dissipation = 0.0;  // [J]
    double work_contact = 0.0;           // [J]
    unsigned int n_steps = 0;
  };

  /// One converged time step of the rolling study (study rolling). Forces, torques and
  /// energies are of the FULL bodies (symmetry factor applied); angles in the fixed frame,
  /// counter-clockwise about +z.
  struct RollingStepRecord
  {
    unsigned int step = 0;
    double time = 0.0;                 // [s]
    double delta = 0.0;                // [m] push of the journal's axis beyond first touch
    double force_normal = 0.0;         // [N] contact force on the journal along the push (+y)
    double force_tangential = 0.0;     // [N] its component along +x (friction at the bottom)
    double phi = 0.0;                  // [rad] bearing angle ω_B t (prescribed)
    double gamma = 0.0;                // [rad] journal angle
    double phi_rate = 0.0;             // [rad/s] ω_B
    double gamma_rate = 0.0;           // [rad/s] journal spin rate
    double slip_speed = 0.0;           // [m/s] ω_B R_B − γ̇ R_J: the bore's surface speed over
                                       //       the journal's (0: rolling without slip)
    double torque_drive = 0.0;         // [N m] the support's torque on the bearing about +z
    double torque_journal = 0.0;       // [N m] the contact's torque on the journal about its axis
    double work_drive = 0.0;           // [J] ∫ torque_drive dφ (trapezoidal)
    double work_push = 0.0;            // [J] ∫ F dδ of the journal's push (trapezoidal)
    double elastic_energy = 0.0;       // [J] stored in the bearing, ½ (ε−ε_p):C:(ε−ε_p)
    double plastic_dissipation = 0.0;  // [J] ∫ σ:dε_p since t = 0
    double friction_dissipation = 0.0;  // [J] Σ −t_T·Δs_T over the contact nodes since t = 0
    double kinetic_energy = 0.0;        // [J] ½ I γ̇² of the journal's spin
    double energy_balance_error = 0.0;  // [J] work_drive + work_push − the four above
    // [J] Σ ½(f_n + f_{n+1})·Δu of the contact forces on the bearing in its frame (the
    // supports do no work there): the bearing's own balance is work_frame = elastic + plastic
    double work_frame = 0.0;
    double frame_balance_error = 0.0;  // [J] work_frame − elastic_energy − plastic_dissipation
    double max_plastic_strain = 0.0;   // [1] largest equivalent plastic strain
    double max_strain = 0.0;           // [1] largest principal total strain magnitude
    double plastic_volume = 0.0;       // [m^3] where ε_p > 0 (full body)
    unsigned int n_active = 0, n_slip = 0;
    // what the step cost, over its attempts (a failed one included as far as it got):
    unsigned int spin_iterations = 0;    // torque-balance evaluations (coupled: iterations)
    unsigned int newton_iterations = 0;  // material Newton iterations
    unsigned int line_search_steps = 0;  // their line searches' rejected trial points
    unsigned int contact_iterations = 0, linear_iterations = 0;  // active-set, linear solver
    unsigned int cuts = 0;                                       // halvings of Δt
    bool spin_coupled = false;  // the coupled iteration solved it (else the root finder)
    // the paper's Eqs. 4–8 on the bore node and the journal point that touch at t = 0
    // (bottom, mid-plane): angles from their displacement vectors, and the rates φ/t, γ/t
    double phi_paper = 0.0, gamma_paper = 0.0;            // [rad]
    double phi_rate_paper = 0.0, gamma_rate_paper = 0.0;  // [rad/s]
    double wall_time = 0.0;                               // [s] since the start of the run
  };

  /// The rolling study's strain profile across the contact zone at the end (the paper's Fig.
  /// 12): one point of the bore at the axial mid-plane.
  struct StrainProfilePoint
  {
    double angle = 0.0;  // [rad] from the contact point (fixed frame, + counter-clockwise)
    double arc = 0.0;    // [m] R · angle (R_B on the bore, R_J on the journal)
    double strain_radial = 0.0, strain_tangential = 0.0, strain_axial = 0.0;  // [1] total
    double plastic_strain = 0.0;  // [1] equivalent: the largest of the sample's cell
    double von_mises = 0.0;       // [Pa] the largest of the sample's cell's material points
    unsigned int body = 0;  // 0: the bearing's bore, 1: the deformable journal's surface
  };

  struct RollingSummary
  {
    double journal_inertia = 0.0;  // [kg m^2]
    double rolling_rate = 0.0;     // [rad/s] ω_B (R_B + δ_max) / R_J
    double time_step = 0.0;        // [s] nominal
    bool stages_found = false;
    double slip_speed_max = 0.0;    // [m/s]
    double end_of_slip = 0.0;       // [s] stage (i) ends
    double settled = 0.0;           // [s] stage (iii) starts
    double slip_speed_final = 0.0;  // [m/s]
    double max_plastic_strain = 0.0, max_strain = 0.0;
    double energy_balance_error = 0.0;  // [1] |error| / work put in, at the end
  };

  struct RunResult
  {
    std::vector<IncrementRecord> increments;  // without the origin row
    bool complete = false;
    std::string message;  // why the run stopped early (empty if complete)
    unsigned long n_dofs = 0;
    unsigned long n_cells = 0;
    double symmetry_factor = 1.0;  // full-body force / modelled-part force
    double h_min = 0.0;            // [m] smallest cell diameter
    double wall_time = 0.0;        // [s]
    double setup_time = 0.0;       // [s] mesh, DoFs, static matrices
    unsigned int n_ranks = 1;
    std::vector<std::string> field_files;  // written VTU/PVTU/PVD (rank 0 lists them)
    YieldCheck yield_check;  // at the last converged increment (empty before the first)
    /// Adaptive refinement: one entry per mesh, the last the recorded curve's mesh; empty
    /// without mesh.adaptive_cycles.
    std::vector<AdaptiveCycle> adaptive_cycles;
    double adaptive_error = -1.0;  // [1] estimated relative error of F(δ_max); < 0: none
    std::string adaptive_error_method;
    double adaptive_order = 0.0;               // [1] q of F = F_inf + C N^-q (0: not extrapolated)
    double adaptive_extrapolated_force = 0.0;  // [N] F_inf (0: not extrapolated)
    /// [m] study impact: the expected peak penetration the adaptive meshes were marked at
    /// (the quasi-static studies mark at loading.delta_max); 0: no adaptive cycles
    double adaptive_marking_delta = 0.0;
    /// mesh.adaptive_target_error > 0: whether the estimate reached it (within the cycles)
    bool adaptive_target_reached = false;
    /// contact.sliding finite: how often the mortar search's new partners needed a new
    /// sparsity pattern, and how many increments were solved again with a new coupling
    unsigned int sliding_rebuilds = 0;
    unsigned int sliding_resolves = 0;
    /// Study impact: `increments` hold the quasi-static curve of the same mesh (the reference
    /// the dynamic path is compared with), these the time steps.
    std::vector<DynamicStepRecord> dynamic_steps;
    ImpactSummary impact;
    /// Study rolling: `increments` hold F(δ) per time step, these the time steps.
    std::vector<RollingStepRecord> rolling_steps;
    std::vector<StrainProfilePoint> strain_profile;
    RollingSummary rolling;
  };

  struct RunOptions
  {
    std::string output_dir;  // fields go to output_dir/fields; empty: no fields written
    bool write_fields = true;
    MPI_Comm comm = MPI_COMM_WORLD;
    /// Called on every rank after each converged increment (main() streams the CSV from it).
    std::function<void(const IncrementRecord &)> on_increment;
    /// Study impact: called on every rank after each converged time step.
    std::function<void(const DynamicStepRecord &)> on_dynamic_step;
    /// Study rolling: called on every rank after each converged time step.
    std::function<void(const RollingStepRecord &)> on_rolling_step;
    /// Study rolling: restart files (solve/rolling_restart.h). `write_dir`: the state written
    /// there after every `every` converged steps and the last (empty: none); `resume_dir`: the
    /// run continues from the state there (empty: from rest), its steps' records replayed
    /// through the callbacks above first.
    struct Restart
    {
      std::string write_dir;
      unsigned int every = 1;
      std::string resume_dir;
    } restart;
  };

  /// Runs one scene (no sweep). Throws InputError for scene problems found late; numerical
  /// failures are returned as an incomplete RunResult (what was reached is kept).
  RunResult run_scene(const FeScene &scene, const RunOptions &options);

  /// Initialises MPI, p4est and deal.II's thread settings (one thread per rank: the ranks share
  /// two cores) for the lifetime of the returned object. Call first in main().
  std::shared_ptr<void> make_runtime(int &argc, char **&argv);

  /// The rank a launcher (mpirun, or srun and other PMI launchers) started this process as,
  /// read from the environment, so before MPI starts; nullopt when no launcher started it.
  std::optional<int> launcher_rank();

  /// deal.II, Trilinos, p4est versions for the manifest.
  std::vector<std::pair<std::string, std::string>> fe_library_versions();
}  // namespace clearjoint::fe
