// The FE stage's scene (schema clearjoint.fe/1): every parameter of SPEC §2 with its default and
// unit, read strictly (unknown keys, wrong types and out-of-range values are InputErrors naming
// the file, key path, value and valid range). Plain C++: no deal.II here, so tests and other
// tools can include it cheaply.
//
// All lengths are in metres, moduli in pascals, densities in kg/m³ (SI in every file, SPEC §1).
#pragma once

#include "fe_stage/material/hardening_table.h"
#include "fe_stage/solve/hht.h"
#include "geometry/joint_geometry.h"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::fe
{
  /// What is simulated. `radial` is the paper's §2.2/§3.1 study, `misalignment` its §3.3 study
  /// (journal tilted by θ in the y–z plane); `hertz` and `patch` are the verification problems
  /// of SPEC §2 (a rigid sphere / a rigid flat pressed onto an elastic block).
  /// `impact` is the paper's §3.2 study: the journal launched into the bearing, implicit
  /// dynamics (Hilber–Hughes–Taylor α).
  /// `rolling` is its §3.4 study: both bodies' steel elastoplastic, the bearing turning at ω_B,
  /// the journal pushed radially and spun by friction alone (docs/fe.md "Rolling study").
  enum class Study
  {
    radial,
    misalignment,
    hertz,
    patch,
    impact,
    rolling
  };

  /// The studies that model the joint (bearing and journal), not a verification block.
  inline bool is_joint_study(Study s)
  {
    return s == Study::radial || s == Study::misalignment || s == Study::impact ||
           s == Study::rolling;
  }

  /// How the journal is loaded (SPEC §2): `end_faces` (default) drives u_y = −δ on the journal's
  /// end face(s); `axis_line` drives only the journal's axis (the paper's choice; drifts with
  /// mesh size); `core` moves the journal's inner core r ≤ R_J/2 rigidly, u = (0, −δ, 0), the
  /// outer part deformable; `rigid` replaces the journal by a rigid cylinder (only the bearing
  /// is meshed).
  enum class JournalLoading
  {
    end_faces,
    axis_line,
    core,
    rigid
  };

  enum class LinearSolver
  {
    automatic,
    cg_amg,
    direct
  };

  struct Geometry
  {
    double R_B = 10.0e-3;  // [m] bearing inner radius
    double t_B = 4.0e-3;   // [m] bearing wall thickness (outer radius R_B + t_B)
    double L_B = 20.0e-3;  // [m] bearing length
    double c_r = 0.5e-3;   // [m] radial clearance, R_J = R_B - c_r (paper Eq. 1)
    double c_a = 1.0e-3;   // [m] axial clearance, L_J = L_B - 2 c_a (paper Eq. 2)

    /// Optional Gmsh MSH 2.2 mesh of the joint (physical groups bearing, journal,
    /// bearing_fixed, journal_loaded, bearing_contact, journal_contact; docs/geometry.md). Empty:
    /// the mesh is generated from the numbers above (which still describe the joint).
    std::string mesh;

    double R_J() const { return R_B - c_r; }        // [m] journal radius
    double L_J() const { return L_B - 2.0 * c_a; }  // [m] journal length
  };

  /// Misalignment study (paper §3.3): tilt of the journal's axis in the y–z plane.
  struct Misalignment
  {
    double theta_deg = 1.0;  // [deg] in [0, θ_max] (θ_max from paper Eq. 3)
  };

  struct Material
  {
    double E = 207.0e9;   // [Pa] Young's modulus
    double nu = 0.3;      // [1] Poisson's ratio
    double rho = 7800.0;  // [kg/m³] density (kept for the dynamic studies; unused when static)
    /// [Pa] the yield check's limit: the model stays linear elastic, the run reports where von
    /// Mises exceeds this (SPEC §2's hardening table starts at 168.2 MPa, the paper's steel).
    double yield_stress = 168.2e6;
    /// The constitutive law: `elastic` (every study but rolling) or `elastoplastic` (von Mises
    /// with isotropic hardening from `hardening`, radial return with the consistent tangent;
    /// the rolling study's default and only choice).
    enum class Model
    {
      elastic,
      elastoplastic
    } model = Model::elastic;
    /// The kinematics: `small` (ε = sym ∇u about the reference configuration) or `finite`
    /// (total Lagrangian: F = I + ∇u, first Piola stress and geometric stiffness, the J2 law
    /// lifted to the logarithmic strain space, material/finite_j2.h). Finite needs
    /// model elastoplastic (the patch test and the rolling study).
    enum class Kinematics
    {
      small,
      finite
    } kinematics = Kinematics::small;
    /// (ε_p [-], σ_y [Pa]) points, linear between them (material/hardening_table.h); empty:
    /// SPEC §2's default table 168.2 + 280.25·ε_p MPa at ε_p = 0, 0.1, …, 1.0.
    std::vector<std::array<double, 2>> hardening;
  };

  struct Contact
  {
    double mu = 0.1;  // [1] Coulomb friction coefficient (SPEC §2 default)
    /// [1] scale of the active-set complementarity constant c = scale · E · h_min. The converged
    /// solution does not depend on it (non-penetration is exact at the contact nodes); it only
    /// steers how the active set is guessed between iterations.
    double active_set_scale = 1.0;
    /// [1] friction's complementarity constant c_T = tangential_scale · c (stick where
    /// |t − c_T s_T| ≤ μ(λ − c ĝ)); like c it leaves the converged solution unchanged and only
    /// steers the semi-smooth Newton path (docs/fe.md says how the default was chosen).
    double tangential_scale = 1.0;
    unsigned int max_iterations = 100;  // active-set iterations per increment before a cut
                                        // (frictionless: 1–5; Coulomb friction: up to ~45)
    /// How a deformable journal's surface is paired with the bore: node_to_node on the
    /// generated meshes' common rays, or dual mortar (any two meshes). automatic: mortar (the
    /// joint with a deformable journal, generated or Gmsh, and the verification blocks).
    enum class Pairing
    {
      automatic,
      node_to_node,
      mortar
    } pairing = Pairing::automatic;
    /// Which joint surface is the mortar slave (carries the constraints): the bore, or the
    /// journal's surface (then the journal must be driven at its core, so that no surface
    /// node is driven). automatic: the journal for the tilted journal of the misalignment
    /// study (its rim bears on the bore), the bore otherwise.
    enum class MortarSlave
    {
      automatic,
      bore,
      journal
    } mortar_slave = MortarSlave::automatic;
    /// small: the mortar coupling of two deformable bodies is found once, in the reference
    /// configuration (fine while the surfaces slide much less than a contact cell); finite: it
    /// is found again at the deformed surfaces after every converged increment (Abaqus's
    /// small/finite sliding).
    enum class Sliding
    {
      small,
      finite
    } sliding = Sliding::small;
  };

  struct Loading
  {
    JournalLoading journal = JournalLoading::end_faces;
    double delta_max = 0.05e-3;  // [m] final push beyond first touch
    unsigned int n_increments = 10;
    unsigned int max_cuts = 3;  // an increment that fails is halved at most this many times
    /// [m] core loading, study radial: the journal placed this far along +z off the axial
    /// centre at δ = 0, and the core moved this much more along +z over the push (in
    /// proportion to δ, reached at δ_max). The journal must stay within the bore:
    /// |axial_offset|, |axial_offset + axial_slide| ≤ c_a.
    double axial_offset = 0.0;
    double axial_slide = 0.0;
  };

  struct Mesh
  {
    unsigned int degree = 2;              // polynomial degree of the elements (1 or 2)
    unsigned int n_circumferential = 24;  // coarse cells over 180°
    unsigned int n_radial = 0;            // coarse cells through t_B; 0: one per 2 mm (at least 1)
    unsigned int n_axial = 6;             // coarse cells over the half length L_B/2
    unsigned int global_refinements = 0;
    unsigned int contact_refinements = 1;  // extra refinements inside the contact window
    double contact_window_deg = 40.0;      // [deg] half-angle of the refined zone about the bottom
    /// Adaptive refinement: this many cycles of (curve, Kelly indicator, refine the
    /// adaptive_fraction of the cells with the largest indicators) before the recorded curve;
    /// 0: off. A deformable journal then pairs by dual mortar.
    unsigned int adaptive_cycles = 0;
    double adaptive_fraction = 0.2;  // [1] of the active cells refined per cycle, (0, 1)
    /// Increments of the push on each marking mesh (the cycles before the recorded curve,
    /// which keeps loading.n_increments). Only F(δ_max) and the solution at δ_max are used
    /// there, and they hardly depend on the path: with μ = 0.1, 1 to 20 increments give
    /// F(δ_max) within 5e-6 (docs/fe.md); frictionless contact is path-independent.
    unsigned int adaptive_increments = 2;
    /// [1] > 0: refine until the estimated relative error of F(δ_max) is at most this (an
    /// extrapolation from three or more meshes, solve/adaptive_estimate.h), adaptive_cycles
    /// then being the most cycles allowed; 0: exactly adaptive_cycles cycles.
    double adaptive_target_error = 0.0;
  };

  struct Solver
  {
    LinearSolver linear = LinearSolver::automatic;
    double tolerance = 1.0e-10;  // [1] relative residual of the linear solve
    unsigned int max_linear_iterations = 2000;
    /// `automatic`: direct (MUMPS) below this. Measured on 2026-11-29 (docs/benchmarks.md "The
    /// direct solver"): 1.4–1.5× less CPU than the AMG at 7 k and 11 k DoFs, the same at 22 k.
    unsigned int direct_below_dofs = 20000;
    /// Material Newton iterations per increment at most (an elastoplastic quasi-static study;
    /// the rolling study has rolling.max_newton_iterations per evaluation of its torque).
    unsigned int max_newton_iterations = 25;
    /// The material Newton iteration (elastoplastic: the rolling study, the plastic patch
    /// test) shortens a step that overshoots the minimum of the bodies' energy along it
    /// (Crisfield's line search; solve/material_newton.cc). false: full Newton steps.
    bool line_search = true;
  };

  /// Verification block (study hertz / patch): a block [0,W]×[−H,0]×[0,W] (quarter model).
  struct Verification
  {
    double sphere_radius = 10.0e-3;  // [m] hertz: radius of the rigid sphere
    double block_width = 20.0e-3;    // [m] W
    double block_height = 20.0e-3;   // [m] H
    unsigned int n_cells = 4;        // coarse cells per edge
    unsigned int contact_refinements = 4;
    double refine_radius = 1.0e-3;  // [m] hertz: cells within this distance get refined
    /// The body pressed onto the block: `rigid` (a rigid sphere / flat, step-42's obstacle) or
    /// `deformable` (same material, meshed independently, coupled by dual mortar): for hertz
    /// a body [0,W]×[0,H_i]×[0,W] whose bottom is the Hertz profile y = r²/2R (saturating far
    /// from the contact), for patch a second block; its top face is pushed down by δ.
    bool deformable_indenter = false;
    unsigned int indenter_n_cells = 3;  // coarse cells per edge of the indenter (≠ n_cells:
                                        // non-matching meshes)
    double indenter_height = 20.0e-3;   // [m] H_i
  };

  /// Impact study (paper §3.2): the journal (full-body mass ρ π R_J² L_J; rigid, or with
  /// loading.journal end_faces / axis_line deformable and free) starts at first
  /// touch with `velocity` toward the bearing (−y) — equivalent to the paper's coaxial start, as
  /// the free flight across the clearance changes nothing (no gravity, bearing at rest) — and
  /// the run follows it through the deepest penetration until it leaves the bearing.
  struct Impact
  {
    double velocity = 0.10;  // [m/s] speed at first touch, (0, 100)
    /// Abaqus/Standard's dynamic application (solve/hht.h): the operator and its α, β, γ —
    /// transient_fidelity (HHT, α = −0.05), moderate_dissipation (HHT, α = 1 − √2 = −0.41421,
    /// the paper's and the default) or quasi_static (backward Euler)
    DynamicApplication application = HhtAlpha::default_application;
    /// [1] HHT α in [−1/2, 0] overriding the application's (β, γ follow from it), as Abaqus's
    /// *DYNAMIC, ALPHA=; not with quasi_static. Empty: the application's.
    std::optional<double> alpha;
    /// Δt = T_c / steps_per_period, T_c = 2π √(m_J/k_c) the period of the journal's mass on
    /// the contact's secant stiffness k_c at the expected δ_max (measured by a static push on
    /// the same mesh): ≥ 10, the Δt/T ≤ 1/10.
    unsigned int steps_per_period = 40;
    double time_step = 0.0;  // [s] > 0: this Δt instead (0: from steps_per_period)
    double end_time = 0.0;   // [s] > 0: run to this time (past the separation: the bearing's
                             //   free vibration); 0: stop once the journal has left, at the
                             //   latest at 4 T_c (twice a linear contact's duration)
    /// [kg] > 0: the rigid journal's mass instead of ρ π R_J² L_J (0: that) — e.g. the mass
    /// that meets the bearing in a mechanism, the pin with the links it carries. Not with a
    /// deformable journal (loading.journal end_faces, axis_line): its mass is its mesh's
    /// (ρ and the geometry), and no density scaling is offered.
    double journal_mass = 0.0;
    unsigned int max_steps = 5000;  // time steps at most (a bound on the loop)
    unsigned int field_stride = 5;  // VTU fields every this many steps (and the last)
    /// The mass matrix: `redistributed` (row-sum lumped, the contact surface's nodes massless,
    /// their mass moved to their cells' other nodes: the contact force converges with Δt),
    /// `lumped` (row-sum), `consistent` (both oscillate at the contact: docs/fe.md).
    enum class Mass
    {
      redistributed,
      lumped,
      consistent
    } mass = Mass::redistributed;
  };

  /// Rolling study (paper §3.4): the bearing turns about its axis (+z) at omega_B; the rigid
  /// journal's axis is pushed radially (−y in the fixed frame) from first touch to
  /// loading.delta_max along a linear ramp reaching it at ramp_time, then held to end_time;
  /// the journal turns freely about its axis, driven by friction only (spin inertia included).
  /// The bearing is computed in its co-rotating frame (docs/fe.md).
  struct Rolling
  {
    double omega_B = 12.56;     // [rad/s] the bearing's spin, (0, 1e4)
    double ramp_time = 0.25;    // [s] the push reaches δ_max at this time, > 0
    double end_time = 0.0;      // [s] ≥ ramp_time: run to this time (0: ramp_time)
    unsigned int n_steps = 40;  // time steps over end_time (≥ 4)
    /// The bearing's support, turning with it: `outer_surface` (its whole outer surface, a
    /// bearing pressed into a rotating housing) or `upper_half` (the outer surface's nodes at
    /// y ≥ 0 at t = 0, the radial study's support: for comparisons at small ω_B).
    enum class Support
    {
      outer_surface,
      upper_half
    } support = Support::outer_surface;
    /// [kg m²] > 0: the journal's spin inertia about its axis instead of ½ m R_J² with
    /// m = ρ π R_J² L_J (0: that)
    double journal_inertia = 0.0;
    /// How a step finds the journal's spin γ̇ (solve/spin_stepper.h): `bordered` (γ̇ an unknown
    /// of each material Newton iteration beside the displacements: its torque-balance row and
    /// the displacements' dependence on the journal's turn, one Newton system), `coupled` (γ̇
    /// updated in each material Newton iteration by a secant on the balance), both one
    /// nonlinear solve a step with the root finder where that fails, or `nested` (a root
    /// finder on γ̇ around whole material solves).
    enum class SpinSolver
    {
      bordered,
      coupled,
      nested
    } spin_solver = SpinSolver::bordered;
    unsigned int max_spin_iterations = 60;    // torque-balance iterations per step at most
    unsigned int max_newton_iterations = 25;  // material Newton iterations per solve at most
    unsigned int field_stride = 10;           // VTU fields every this many steps (and the last)
  };

  struct Output
  {
    bool fields = true;  // write VTU/PVTU + PVD fields
  };

  struct FeScene
  {
    Study study = Study::radial;
    Geometry geometry;
    Material material;
    Contact contact;
    Loading loading;
    Mesh mesh;
    Solver solver;
    Verification verification;
    Misalignment misalignment;
    Output output;
    Impact impact;
    Rolling rolling;
    bool full_model = false;        // false: the symmetry planes the scene allows (quarter model)
    std::vector<double> sweep_t_B;  // [m] if non-empty, one run per value, one folder each
    std::vector<double> sweep_theta_deg;  // [deg] the same for the misalignment angle
    std::vector<double> sweep_velocity;   // [m/s] the same for the impact velocity
    /// [kg] the same for the impact study's rigid journal mass (impact.journal_mass; `own` in
    /// the file: ρ π R_J² L_J); with sweep_velocity, one case per pair (every velocity at
    /// every mass)
    std::vector<double> sweep_journal_mass;
    std::string source_file;  // for messages and the manifest
  };

  /// Reads and validates a scene file (YAML or JSON). Throws InputError.
  FeScene read_scene(const std::string &path);
  /// Same from already-parsed JSON (tests); `source` names it in messages.
  FeScene scene_from_json(const nlohmann::json &j, const std::string &source);
  /// Checks the combined constraints (geometry possible, etc.). Throws InputError.
  void validate_scene(const FeScene &scene);
  /// geometry.mesh: readable and checked (groups, hexahedra, no inverted cells), a rigid
  /// journal, the bore radius equal to R_B, the whole length for the misalignment study.
  /// Part of validate_scene, so a bad mesh stops the run before any output. Throws InputError.
  void check_mesh_against_scene(const FeScene &scene);

  /// [kg] the impact study's rigid journal mass: impact.journal_mass, or ρ π R_J² L_J.
  double rigid_journal_mass(const FeScene &scene);
  /// Whether the scene has a sweep block (one run per value or pair of values).
  bool has_sweep(const FeScene &scene);
  /// [kg m²] the rolling study's journal spin inertia: rolling.journal_inertia, or ½ m R_J²
  /// with m = ρ π R_J² L_J (the full journal).
  double rolling_journal_inertia(const FeScene &scene);
  /// The material's hardening table (checked; InputError names `key_path`).
  HardeningTable hardening_table(const Material &m, const std::string &file,
                                 const std::string &key_path = "material.hardening");
  /// [s] the rolling study's end time: rolling.end_time, or ramp_time.
  double rolling_end_time(const FeScene &scene);

  /// The joint's dimensions for the geometry library (θ_max, tilt checks).
  geometry::JointGeometry joint_geometry(const Geometry &g);
  /// θ_max of paper Eq. 3 in degrees; InputError at `key` if the geometry has none.
  double theta_max_deg(const Geometry &g, const std::string &file, const std::string &key);

  /// The annotated default scene (YAML text with units), what --print-defaults prints.
  std::string default_scene_yaml();
  /// The scene as JSON (for manifests).
  nlohmann::json scene_to_json(const FeScene &scene);

  std::string to_string(Study s);
  std::string to_string(JournalLoading l);
  std::string to_string(Contact::Pairing p);
  std::string to_string(Contact::MortarSlave s);
  std::string to_string(Contact::Sliding s);
}  // namespace clearjoint::fe
