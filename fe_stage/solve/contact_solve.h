// One increment's contact solve: the primal–dual active set (as deal.II's step-41/42), with
// Coulomb friction by semi-smooth Newton rows, iterated to convergence at a push δ — and what
// each iteration needs: the rigid obstacle's (or the turning journal's) position and gaps, the
// constraint lines of the active nodes, the system with the contact cells and friction rows,
// the linear solve, the evaluation of every node's force, gap and slip, and the increment's
// forces and checks. It owns the iteration's constraints (the fixed ones at δ plus the active
// set's lines) and the time it spends; it works on the parts it is given (the contact nodes,
// the assembler, u) and keeps nothing else between increments.
//
// Files: solve/contact_iteration.cc (the iteration and its system), solve/contact_rows.cc
// (obstacle, nodal areas, constraint and friction rows), results/reactions.cc (evaluation,
// forces, Coulomb check).
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/contact/contact_pattern.h"
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/contact/rigid_obstacle.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/scoped_timer.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/linear_solver.h"
#include "fe_stage/study_plan.h"

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace clearjoint::fe::detail
{
  class ContactSolve : public ContactEvaluation
  {
  public:
    /// The parts the solve works on: it moves the obstacle (and the turning journal's
    /// partners' frame), sets the DoFs' push, writes the contact nodes' state, assembles and
    /// solves into u.
    struct Parts
    {
      const FeScene &scene;
      const StudyPlan &plan;
      const Bodies &bodies;
      DofSpace &dofs;
      ContactProblem &contact;
      RigidObstacle &obstacle;
      JournalFrame &frame;
      Assembler &system;
      State &state;
      SystemSolver &solver;
      MPI_Comm comm;
    };

    explicit ContactSolve(const Parts &parts);

    /// One increment to `delta` from the current state: active-set iterations until no node
    /// changes and the slip law holds, then the increment's forces and checks. Throws
    /// StepFailure.
    IncrementRecord solve_increment(double delta);

    /// The last increment's linear solve again with the contact nodes' active and stick sets
    /// (and slip directions) kept, the obstacle placed anew at δ for the journal's frame now,
    /// linearised about the current u; the solve starts from `guess`. Writes u and the nodes'
    /// forces, gaps and slips; returns the linear solver's iterations. Throws StepFailure.
    unsigned int solve_with_sets_kept(double delta, const TrilinosWrappers::MPI::Vector &guess);

    /// The rigid obstacle at δ: each node's gap g0, normal n and the displacement of the
    /// obstacle's surface point facing it (solve/contact_rows.cc says how for each study).
    void set_obstacle_position(double delta) override;
    /// λ = (K u)·n, ĝ and the relative displacement of every node at the current u.
    void evaluate_contact(double delta) override;
    /// Nodal areas w_i = ∫ φ_i dA over the contact surface (once per mesh).
    void compute_nodal_weights();
    /// Each contact node's share of the step's known load b (the friction rows read the
    /// traction K u − b in the dynamic and elastoplastic solves). Collective.
    void set_contact_load_offsets();

    /// The time in the contact assembly (another assembly, the elastoplastic tangent's, adds
    /// to it through assembly_timer()), the linear solves and the evaluation [s].
    [[nodiscard]] ScopedTimer assembly_timer() { return ScopedTimer(t_assemble_); }
    double assembly_time() const { return t_assemble_; }
    double solve_time() const { return t_solve_; }
    double evaluation_time() const { return t_evaluate_; }

  private:
    /// c [N/m], the active set's complementarity constant: contact.active_set_scale E h_min
    double complementarity_constant() const
    {
      return scene_.contact.active_set_scale * scene_.material.E * bodies_.h_min();
    }
    // the parts of one active-set iteration, in order
    void build_contact_constraints(double delta);
    void assemble_system(double delta, double c);
    void record_forces(double delta, IncrementRecord &rec);
    void record_coulomb_check(IncrementRecord &rec) const;
    bool friction_cell_matrix(unsigned int k, FullMatrix<double> &M,
                              std::vector<types::global_dof_index> &ext) const;
    void friction_node_matrix(const ContactNode &cn, double c, double delta, FullMatrix<double> &M,
                              Vector<double> &rhs, std::vector<types::global_dof_index> &ext) const;
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

    // the parts (Parts), by the names the solve's files use
    const FeScene &scene_;
    const StudyPlan &plan_;
    const Bodies &bodies_;
    DofSpace &dofs_;
    ContactProblem &contact_;
    RigidObstacle &obstacle_;
    JournalFrame &frame_;
    Assembler &system_;
    State &state_;
    SystemSolver &solver_;
    MPI_Comm comm_;
    unsigned int rank_;
    bool check_friction_rows_;  // the debug check of the slip law's rows (-v on any rank)

    AffineConstraints<double> constraints_;  // the fixed ones at δ + the active set's lines
    double t_assemble_ = 0, t_solve_ = 0, t_evaluate_ = 0;
  };
}  // namespace clearjoint::fe::detail
