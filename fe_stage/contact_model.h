// The FE contact model's remaining shared state and steps (deal.II, dim = 3). Internal: only
// fe_stage's own .cc files include this; everything else sees the deal.II-free façade
// fe_model.h. Its member functions are defined by concept across fe_stage/{contact,material,
// solve,results}/ (fe_stage/README.md maps each to its file). It composes the parts and runs the
// steppers, so it includes solve/; it sits outside core/, which includes nothing from solve/.
//
// The class is being dissolved into objects that own their state (issue 29, FE_DESIGN §4.1).
// Owners so far, each in its own header: the meshed bodies (Bodies, mesh/bodies.h), the DoF
// space and its fixed constraints (DofSpace, core/dof_space.h), the operator, its load, the
// elastic cache and each iteration's condensed system (Assembler, core/assembler.h), the
// iterate u and its nodal forces (State, core/state.h), the contact nodes and their active set
// (ContactProblem, contact/contact_problem.h), how they find their partners (ContactPairing,
// contact/contact_pairing.h), the linear solver and its AMG (SystemSolver,
// solve/linear_solver.h), the material law with its quadrature-point history (MaterialLaw,
// material/material_law.h), the steppers that own their loops and see the model only through
// QuasiStaticProblem, DynamicProblem and SpinProblem (the quasi-static push QuasiStaticStepper,
// HhtStepper, SpinStepper; solve/stepper_interfaces.h), their step-size policy
// (StepController, solve/step_controller.h) and root finder (solve/root_finder.h), HHT-α's
// coefficients and predictor (HhtAlpha, solve/hht.h), the per-node Coulomb law
// (contact/coulomb_ssn.h), the fields with their PVD records and the yield check
// (FieldOutput, results/field_output.h).
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
//     contact/contact_rows.cc. Partners: a rigid obstacle, node-to-node on common rays, or dual
//     mortar (and finite sliding). The converged solution does not depend on the
//     complementarity constants;
//   - quasi-static increments of δ, HHT-α time steps (impact), or the turning bearing's time
//     steps with the journal's spin from its torque balance (rolling).
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/contact/rigid_obstacle.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/scoped_timer.h"
#include "fe_stage/core/state.h"
#include "fe_stage/core/step_failure.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/results/field_output.h"
#include "fe_stage/solve/adaptive_estimate.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/linear_solver.h"
#include "fe_stage/solve/rolling_kinematics.h"
#include "fe_stage/solve/stepper_interfaces.h"
#include "fe_stage/study_plan.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  using namespace dealii;

  class HhtStepper;
  class QuasiStaticStepper;
  class SpinStepper;

  /// The steppers see the model only through QuasiStaticProblem, DynamicProblem and
  /// SpinProblem (solve/stepper_interfaces.h), and the material Newton iteration through
  /// MaterialProblem (solve/material_newton.h), besides the parts they are given.
  class ContactModel : private QuasiStaticProblem,
                       private DynamicProblem,
                       private SpinProblem,
                       private MaterialProblem
  {
  public:
    ContactModel(const FeScene &scene, const RunOptions &options);
    RunResult run();

  private:
    void make_block_grid();
    /// The pairing's contact nodes, their partners' ghosts and the contact cells
    /// (contact/contact_pattern.cc); searched between the surfaces displaced by
    /// `search_displacement` when given (ghosted; finite sliding's rebuild).
    void find_contact_nodes(const TrilinosWrappers::MPI::Vector *search_displacement = nullptr);
    /// contact.sliding finite: the mortar search again at the converged deformed surfaces
    /// (contact/sliding.cc); slip then counts from u_start. Returns how far the coupling moved.
    double follow_sliding(const TrilinosWrappers::MPI::Vector &u_start, bool rebuild = false);
    /// contact.sliding finite (scene.cc admits it only for two bodies paired by mortar)
    bool finite_sliding() const { return scene_.contact.sliding == Contact::Sliding::finite; }
    double pair_deformed_surfaces(const TrilinosWrappers::MPI::Vector &u_start) override
    {
      return follow_sliding(u_start);
    }
    unsigned int n_sliding_rebuilds_ = 0;  // follow_sliding: new sparsity patterns
    void make_matrices();
    /// The contact surface's DoFs, massless in an operator of this kind (the impact study's
    /// dynamic one with impact.mass = redistributed: Assembler::lump_and_redistribute); empty
    /// otherwise.
    std::set<types::global_dof_index> massless_dofs(Assembler::Operator kind) const;
    void compute_nodal_weights();
    void set_obstacle_position(double delta);
    void evaluate_contact_at(double delta) override
    {
      set_obstacle_position(delta);
      evaluate_contact(delta);
    }
    /// The quasi-static push's parts (QuasiStaticStepper::Parts).
    QuasiStaticStepper quasi_static_stepper();
    /// Everything that depends on the mesh: DoFs, constraints, contact nodes (searched as
    /// find_contact_nodes), matrices.
    void prepare_mesh(const TrilinosWrappers::MPI::Vector *search_displacement = nullptr);
    /// The run's mesh sizes and set-up time into `result` (every study, once its mesh is final).
    void record_mesh(RunResult &result) const;
    /// Study impact (solve/impact_stepping.cc): the static curve, then HHT-α time steps.
    RunResult run_impact();
    /// Its steps: the mesh, the journal's mass and the integrator's α, β, γ (returned);
    /// the static probe and the quasi-static reference curve with the contact period and Δt
    /// they set; the time steps to the separation or the end time, keeping the displacement at
    /// the peak force; the summary and the yield check at the peak. False: result.message says
    /// why, result.wall_time is set.
    HhtAlpha begin_impact(RunResult &result);
    bool compute_impact_reference(RunResult &result);
    bool march_impact(RunResult &result, HhtStepper &stepper, TrilinosWrappers::MPI::Vector &u_peak,
                      bool &have_peak);
    void finish_impact(RunResult &result, const HhtStepper &stepper,
                       const TrilinosWrappers::MPI::Vector *u_peak);
    /// [s] impact.end_time, or 4 T_c (twice a linear contact's duration).
    double impact_end_time(double contact_period) const;
    /// Switches the assembled operator to c_m M + c_k K and reassembles (the solver's AMG is
    /// built again).
    void set_dynamic_operator(const MatrixCoefficients &c) override;
    /// Study rolling (solve/rolling_stepping.cc): the bearing turning, the journal's spin from
    /// its torque balance, elastoplastic (core/plastic_assembly.cc).
    RunResult run_rolling();
    /// Its set-up before the first step and its end after the last (solve/rolling_stepping.cc).
    void begin_rolling(RunResult &result);
    void finish_rolling(RunResult &result, const SpinStepper &stepper,
                        const rolling::Motion &motion, const std::vector<double> &times,
                        const std::vector<double> &slips);
    void init_plasticity();
    /// The tangent and its load at the current displacement (Assembler::assemble_tangent),
    /// then the contact nodes' share of the load. Returns the number of yielding points.
    unsigned int assemble_plastic() override;
    bool elastoplastic() const override { return system_.kind() == Assembler::Operator::tangent; }
    struct PlasticEnergies
    {
      double plastic_work_step = 0.0;  // [J] full body
      double elastic_energy = 0.0;     // [J]
      double plastic_volume = 0.0;     // [m^3]
      double max_plastic_strain = 0.0, max_strain = 0.0;
      // the bearing's own (material 0): its balance in its frame
      double bearing_plastic_work_step = 0.0, bearing_elastic_energy = 0.0;  // [J]
    };
    PlasticEnergies commit_plasticity();
    std::vector<StrainProfilePoint> strain_profile(unsigned int body, double turn,
                                                   double half_angle) const;
    /// One material Newton iteration (SpinProblem: the coupled spin iteration's), and its
    /// tolerance: the iteration's own (MaterialNewton).
    MaterialIteration material_iteration(double delta, bool line_search) override
    {
      return newton_.iterate(delta, line_search);
    }
    double material_tolerance() const override { return newton_.tolerance(); }
    /// A converged state's trial states made the points' history.
    void commit_material() override;
    /// One state of the rolling bearing for a given journal spin (the torque-balance's g):
    /// Newton on the material around the active-set contact solve. Throws StepFailure.
    RollingSolve solve_rolling_state(double delta) override;
    /// [N m] the contact's torque on the journal about its axis, full body (collective).
    double journal_torque() const override;
    void refine_adaptively();
    /// The quasi-static study's adaptive cycles before its curve, and the sequence closed
    /// after it (solve/quasi_static_stepping.cc).
    bool run_adaptive_cycles(RunResult &result, QuasiStaticStepper &stepper,
                             bool &last_mesh_marked);
    void close_adaptive_sequence(RunResult &result, bool last_mesh_marked);
    /// One increment to `delta` from the current state; throws StepFailure.
    IncrementRecord solve_increment(double delta) override;
    // the parts of one active-set iteration (solve/contact_iteration.cc calls them in order)
    void build_contact_constraints(double delta);
    void assemble_system(double delta, double c);
    void record_forces(double delta, IncrementRecord &rec);
    void record_coulomb_check(IncrementRecord &rec) const;
    /// The boundary whose nodes carry the contact constraints: the bore (or the block's top),
    /// or the journal's surface when it is the mortar slave.
    types::boundary_id slave_surface_id() const { return slave_surface(plan_); }
    /// +1 when the slave is the bore (or the block), −1 when it is the journal: the force on
    /// the bearing is this times the force on the slave's nodes.
    double slave_sign() const { return slave_surface_id() == bid_journal_surface ? -1.0 : 1.0; }
    /// The rigid obstacle's gap at a reference point (deal.II types around RigidObstacle::gap).
    bool obstacle_gap(const Point<dim> &X, double delta, double &g0, Tensor<1, dim> &n) const
    {
      Vec3 normal;
      if (!obstacle_.gap({X[0], X[1], X[2]}, delta, g0, normal))
        return false;
      n = Tensor<1, dim>({normal[0], normal[1], normal[2]});
      return true;
    }
    void evaluate_contact(double delta);
    bool friction_cell_matrix(unsigned int k, FullMatrix<double> &M,
                              std::vector<types::global_dof_index> &ext) const;
    void friction_node_matrix(const ContactNode &cn, double c, double delta, FullMatrix<double> &M,
                              Vector<double> &rhs, std::vector<types::global_dof_index> &ext) const;
    /// Every study's start: zero displacement, no contact, every node sticking with no slip
    /// history and the obstacle's surface points unmoved.
    void start_from_rest() override;
    /// What a failed attempt goes back to (Snapshot, solve/stepper_interfaces.h).
    Snapshot save_state() const override
    {
      return {state_.u_owned(), contact_.nodes(), n_sliding_rebuilds_};
    }
    void restore_state(const Snapshot &s) override;
    /// [s] since the model was made (the runs' setup and wall times).
    double elapsed() const
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    /// Each contact node's share of the step's known load b (system_.load(): the traction is
    /// K u − b in the dynamic and elastoplastic solves), for the friction rows (collective).
    void set_contact_load_offsets() override;

    const FeScene &scene_;
    const StudyPlan plan_;  // what the scene's study sets up (study/*.cc)
    RunOptions options_;
    MPI_Comm comm_;
    const unsigned int rank_, n_ranks_;

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
    /// The bodies' law (make_material: J2 with its history for the rolling study, else
    /// linear elastic); material_->elastic() is the law of the static operator.
    std::unique_ptr<MaterialLaw> material_;

    bool journal_driven_ = true;             // false: a deformable journal is free
    AffineConstraints<double> constraints_;  // + contact lines of the active set
    /// The operator (stiffness, dynamic or elastoplastic tangent), its load, the contact
    /// cells' matrices, the elastic cache and each iteration's condensed system.
    Assembler system_;
    bool rolling_deformable_journal() const { return frame_.turning && plan_.deformable_partner; }
    bool journal_turns_deformable() const override { return rolling_deformable_journal(); }
    void pair_turned_journal(const TrilinosWrappers::MPI::Vector &u_start) override
    {
      follow_sliding(u_start);
    }
    /// Σ_p w_p Q u_p: the partners' displacement as the slave node sees it (ghosted v; Q the
    /// partners' turn now unless given).
    Tensor<1, dim> partner_displacement(const ContactNode &cn,
                                        const TrilinosWrappers::MPI::Vector &v,
                                        const Tensor<2, dim> *Q = nullptr) const
    {
      Tensor<1, dim> s;
      for (const auto &p : cn.partners)
        for (unsigned int c = 0; c < dim; ++c)
          s[c] += p.weight * v[p.dofs[c]];
      return (Q ? *Q : frame_.partner_rotation) * s;
    }
    /// The partner combinations' sparsity: per candidate node (by its x-DoF) the component of
    /// its normal line and its partners' x-DoFs, as make_matrices built the pattern for them
    /// (follow_sliding: whether new couplings fit it).
    struct PatternEntry
    {
      unsigned int component = 0;
      std::set<types::global_dof_index> partners;
    };
    std::map<types::global_dof_index, PatternEntry> pattern_partners_;
    State state_;  // u (owned and ghosted) and the nodal forces it leaves

    SystemSolver solver_;  // KLU or CG/GMRES with the AMG it owns
    /// The material Newton iteration of an elastoplastic state, with its line search and the
    /// tangent it leaves assembled.
    MaterialNewton newton_;

    /// The fields for ParaView, their PVD records and the yield check.
    FieldOutput fields_;
    std::chrono::steady_clock::time_point start_;
    double t_assemble_ = 0, t_solve_ = 0, t_evaluate_ = 0;
  };

}  // namespace clearjoint::fe::detail
