// The FE contact model (Model), the composition root of fe_stage (deal.II, dim = 3): it owns
// one of each part and runs no study itself. run() chooses the study's run once from the
// scene's plan — QuasiStaticRun (radial, misalignment, Hertz, patch), ImpactRun or RollingRun, each its own
// object in solve/*_run.{h,cc} — and the runs, the steppers and the material Newton iteration
// see the model only through the interfaces it implements for what needs several parts at
// once (the mesh and all that depends on it, a stepper over the parts, the rollback of a failed
// attempt, a rolling state, the material's commit): StudyModel (solve/study_model.h),
// QuasiStaticProblem, DynamicProblem, SpinProblem (solve/stepper_interfaces.h) and
// MaterialProblem (solve/material_newton.h); the contact pattern asks it, through
// MeshPreparation (contact/contact_pattern.h), to make everything that depends on the mesh
// again. Internal: only fe_stage's own .cc files include this; everything else sees the
// deal.II-free façade fe_model.h. Its own functions are in model.cc (fe_stage/README.md maps
// every file). It includes solve/; core/ includes nothing from solve/.
//
// The parts, each the one owner of its state (issue 29, FE_DESIGN §4.1): the meshed bodies
// (Bodies, mesh/bodies.h), the DoF space and its fixed constraints (DofSpace,
// core/dof_space.h), the operator, its load, the elastic cache and each iteration's condensed
// system (Assembler, core/assembler.h), the iterate u and its nodal forces (State,
// core/state.h), the contact nodes and their active set (ContactProblem,
// contact/contact_problem.h), how they find their partners (ContactPairing,
// contact/contact_pairing.h), the sparsity pattern they condense into with the couplings it
// was built for and finite sliding's rebuilds of it (ContactPattern, contact/contact_pattern.h),
// one increment's contact solve with its constraints (ContactSolve, solve/contact_solve.h), the
// linear solver and its AMG (SystemSolver, solve/linear_solver.h), the material law with its
// quadrature-point history on the mesh — its commits, energies and strain profile
// (MaterialState, material/material_state.h; the point law MaterialLaw,
// material/material_law.h) — and its Newton iteration (MaterialNewton,
// solve/material_newton.h), the fields with their PVD records and the yield check
// (FieldOutput, results/field_output.h). The steppers own their loops and state
// (QuasiStaticStepper, HhtStepper, SpinStepper), with one step-size policy (StepController,
// solve/step_controller.h), one root finder (solve/root_finder.h), HHT-α's coefficients and
// predictor (HhtAlpha, solve/hht.h) and the per-node Coulomb law (contact/coulomb_ssn.h).
//
// Method (docs/fe.md has the equations):
//   - small strain, or finite strain (material.kinematics: total Lagrangian, the J2 law in the
//     logarithmic strain space; core/finite_strain_assembly.cc); FE_Q(p)^3 on hexahedra with a
//     curved mapping MappingQ(max(2,p)) and cylindrical manifolds,
//     parallel::distributed::Triangulation, Trilinos matrices; linear elastic, or J2
//     elastoplastic with history (the rolling study and the patch test: the operator is then
//     the tangent, with the linearisation's load; core/assembler.h);
//   - contact enforced EXACTLY at the contact nodes by a primal–dual active set (as deal.II's
//     step-41/42): an active node gets the linearised non-penetration constraint as an
//     AffineConstraints line on its dominant displacement component; the contact force at a
//     node is λ = (K u − b)·n; Coulomb friction by the semi-smooth Newton rows of
//     solve/contact_rows.cc. Partners: a rigid obstacle, node-to-node on common rays, or dual
//     mortar (and finite sliding). The converged solution does not depend on the
//     complementarity constants;
//   - quasi-static increments of δ, HHT-α time steps (impact), or the turning bearing's time
//     steps with the journal's spin from its torque balance (rolling).
#pragma once

#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/contact/contact_pattern.h"
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/contact/rigid_obstacle.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dim.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/material/material_state.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/results/field_output.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/contact_solve.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/hht_stepper.h"
#include "fe_stage/solve/linear_solver.h"
#include "fe_stage/solve/material_newton.h"
#include "fe_stage/solve/quasi_static_stepper.h"
#include "fe_stage/solve/rolling_kinematics.h"
#include "fe_stage/solve/spin_stepper.h"
#include "fe_stage/solve/stepper_interfaces.h"
#include "fe_stage/solve/study_model.h"
#include "fe_stage/study_plan.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>

#include <chrono>
#include <memory>
#include <set>
#include <vector>

namespace clearjoint::fe::detail
{
  using namespace dealii;

  /// The steppers see the model only through QuasiStaticProblem, DynamicProblem and
  /// SpinProblem (solve/stepper_interfaces.h), the material Newton iteration through
  /// MaterialProblem (solve/material_newton.h), and the studies' runs through StudyModel
  /// (solve/study_model.h), besides the parts they are given.
  class Model : private QuasiStaticProblem,
                private DynamicProblem,
                private SpinProblem,
                private MaterialProblem,
                private StudyModel,
                private MeshPreparation
  {
  public:
    Model(const FeScene &scene, const RunOptions &options);
    /// The scene's study, chosen once from its plan: QuasiStaticRun, ImpactRun or
    /// RollingRun.
    RunResult run();

  private:
    // ---- the mesh and all that depends on it (model.cc)
    void build_mesh() override;
    void refine_mesh() override;
    void free_journal() override;
    /// Everything that depends on the mesh: DoFs, constraints, contact nodes and the pattern
    /// (ContactPattern, searched between the surfaces displaced by `search_displacement` when
    /// given), matrices, u, the solver's choice.
    void prepare_mesh(const TrilinosWrappers::MPI::Vector *search_displacement = nullptr) override;
    /// The contact surface's DoFs, massless in an operator of this kind (the impact study's
    /// dynamic one with impact.mass = redistributed: Assembler::lump_and_redistribute); empty
    /// otherwise.
    std::set<types::global_dof_index> massless_dofs(Assembler::Operator kind) const;
    /// The run's mesh sizes and set-up time into `result` (every study, once its mesh is final).
    void record_mesh(RunResult &result) const override;

    // ---- the contact pairing as the surfaces move (ContactPattern)
    double pair_deformed_surfaces(const TrilinosWrappers::MPI::Vector &u_start) override
    {
      return pattern_.follow_sliding(u_start);
    }
    void pair_turned_journal(const TrilinosWrappers::MPI::Vector &u_start) override
    {
      pattern_.follow_sliding(u_start);
    }
    bool journal_turns_deformable() const override { return plan_.journal_turns_deformable(); }
    unsigned int sliding_rebuilds() const override { return pattern_.rebuilds(); }
    std::string solver_summary() const override { return solver_.summary(); }

    // ---- the steppers over the model's parts, the start and the rollback (model.cc)
    QuasiStaticStepper quasi_static_stepper() override;
    HhtStepper hht_stepper(const HhtAlpha &hht, double dt_nominal, unsigned int max_cuts,
                           double m_J, double velocity, bool deformable_journal) override;
    SpinStepper spin_stepper(const rolling::Motion &motion, double t_end, unsigned int n_steps,
                             unsigned int max_cuts, double inertia) override;
    /// Every study's start: zero displacement, no contact, every node sticking with no slip
    /// history and the obstacle's surface points unmoved.
    void start_from_rest() override;
    /// What a failed attempt goes back to (Snapshot, solve/stepper_interfaces.h).
    Snapshot save_state() const override
    {
      return {state_.u_owned(), contact_.nodes(), pattern_.rebuilds()};
    }
    void restore_state(const Snapshot &s) override;
    /// The converged state into a restart file and back (StudyModel says what).
    void write_restart(RestartWriter &out) const override;
    void read_restart(RestartReader &in) override;
    /// Switches the assembled operator to c_m M + c_k K and reassembles (the solver's AMG is
    /// built again).
    void set_dynamic_operator(const MatrixCoefficients &c) override;

    // ---- the contact (ContactSolve)
    /// One increment to `delta` from the current state; throws StepFailure.
    IncrementRecord solve_increment(double delta) override
    {
      return contact_solve_.solve_increment(delta);
    }
    void evaluate_contact_at(double delta) override
    {
      contact_solve_.set_obstacle_position(delta);
      contact_solve_.evaluate_contact(delta);
    }
    /// Each contact node's share of the step's known load b.
    void set_contact_load_offsets() override { contact_solve_.set_contact_load_offsets(); }
    /// [N m] the contact's torque on the journal about its axis, full body (collective).
    double journal_torque() const override;

    // ---- the material (MaterialState, model.cc)
    /// The points' history sized for the mesh, then the operator the tangent.
    void init_plasticity() override;
    bool elastoplastic() const override { return system_.kind() == Assembler::Operator::tangent; }
    /// The tangent and its load at the current displacement (Assembler::assemble_tangent),
    /// then the contact nodes' share of the load. Returns the number of yielding points.
    unsigned int assemble_plastic() override;
    /// One material Newton iteration (SpinProblem: the coupled spin iteration's), and its
    /// tolerance: the iteration's own (MaterialNewton).
    MaterialIteration material_iteration(double delta, bool line_search,
                                         TurnSensitivity *sensitivity) override;
    /// The iteration's contact solve again at the journal's turn + s.d_psi (the sets kept),
    /// from `u_start`; the differences into `s`, then the solved state back as it was.
    void measure_turn_sensitivity(double delta, const TrilinosWrappers::MPI::Vector &u_start,
                                  TurnSensitivity &s);
    double material_tolerance() const override { return newton_.tolerance(); }
    /// One state of the rolling bearing for a given journal spin (the torque-balance's g):
    /// Newton on the material around the active-set contact solve. Throws StepFailure.
    RollingSolve solve_rolling_state(double delta) override;
    /// A converged state's trial states made the points' history (with the step's energies:
    /// commit_plasticity); the tangent assembled before no longer belongs to it.
    void commit_material() override
    {
      newton_.forget_tangent();
      material_.commit();
    }
    PlasticEnergies commit_plasticity() override
    {
      newton_.forget_tangent();
      return material_.commit_with_energies();
    }
    std::vector<StrainProfilePoint> strain_profile(unsigned int body, double turn,
                                                   double half_angle) const override
    {
      return material_.strain_profile(body, turn, half_angle);
    }

    /// [s] since the model was made (the runs' set-up and wall times).
    double elapsed() const override
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    // ---- the parts (in the order they are made)
    const FeScene &scene_;
    const StudyPlan plan_;  // what the scene's study sets up (study/*.cc)
    RunOptions options_;
    MPI_Comm comm_;

    Bodies bodies_;           // the mesh, its mapping, symmetry factor and h_min
    DofSpace dofs_;           // FE, DoFs, index sets, fixed constraints, loaded and support DoFs
    ContactProblem contact_;  // the contact nodes, slipping set, c_T, active-set update

    RigidObstacle obstacle_;
    /// The rolling study's journal as the contact sees it (the bearing's frame angle, the
    /// journal's centre and turn; identity elsewhere): set by the spin stepper.
    JournalFrame frame_;
    /// How the contact nodes find their partners (obstacle, common rays or mortar): reads
    /// the bodies, DoFs, contact problem, obstacle and frame above.
    std::unique_ptr<ContactPairing> pairing_;
    /// The bodies' law with its quadrature-point history (make_material: J2 with its history
    /// for material.model elastoplastic, else linear elastic): its commits, energies and strain
    /// profile; material_.law().elastic() is the law of the static operator.
    MaterialState material_;

    bool journal_driven_ = true;  // false: a deformable journal is free
    /// The operator (stiffness, dynamic or elastoplastic tangent), its load, the contact
    /// cells' matrices, the elastic cache and each iteration's condensed system.
    Assembler system_;
    State state_;  // u (owned and ghosted) and the nodal forces it leaves

    SystemSolver solver_;  // MUMPS or CG/GMRES with the AMG it owns
    /// The material Newton iteration of an elastoplastic state, with its line search and the
    /// tangent it leaves assembled.
    MaterialNewton newton_;
    /// The increment's contact solve: the active-set iteration, its constraints and times.
    ContactSolve contact_solve_;
    /// The contact nodes on the DoF space and the sparsity pattern every active set condenses
    /// into, with the couplings it was built for; finite sliding and its rebuilds.
    ContactPattern pattern_;
    /// The fields for ParaView, their PVD records and the yield check.
    FieldOutput fields_;
    std::chrono::steady_clock::time_point start_;
  };

}  // namespace clearjoint::fe::detail
