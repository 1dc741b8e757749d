// The material Newton iteration of an elastoplastic state (the rolling study's states and the
// elastoplastic quasi-static push): the tangent and its load at the current displacement, the
// active-set contact solve of the linearised problem, until the correction is negligible; with
// Crisfield's line search on the energy along each step (solver.line_search). It owns the
// tangent the line search leaves assembled at the point it accepts; what only the model can do
// — assemble the tangent (small or finite kinematics), hand the contact nodes their share of
// the load, solve the contact problem — it asks of a MaterialProblem.
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/scene.h"

#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>

namespace clearjoint::fe::detail
{
  /// One material Newton iteration from the current u.
  struct MaterialIteration
  {
    IncrementRecord record;
    double correction = 0.0;  // [m] max-norm of the Newton step (its full length)
    unsigned int n_plastic_points = 0;
    double step_length = 1.0;            // [1] the fraction of the Newton step taken
    unsigned int line_search_steps = 0;  // trial points rejected
  };

  /// A converged elastoplastic state: its last contact solve and what it cost.
  struct MaterialSolve
  {
    IncrementRecord record;  // of the last contact solve
    unsigned int newton_iterations = 0, contact_iterations = 0, linear_iterations = 0;
    unsigned int line_search_steps = 0;
  };

  /// What the iteration asks of the model.
  class MaterialProblem
  {
  public:
    /// The tangent and its load at the current u, then the contact nodes' share of the load;
    /// returns the number of yielding quadrature points.
    virtual unsigned int assemble_plastic() = 0;
    /// The contact nodes' share of the load as it is (the nodes may have been paired again).
    virtual void set_contact_load_offsets() = 0;
    /// The active-set contact solve to the push δ from the current u; throws StepFailure.
    virtual IncrementRecord solve_increment(double delta) = 0;

  protected:
    ~MaterialProblem() = default;
  };

  class MaterialNewton
  {
  public:
    /// The model's parts the iteration reads (the state u it moves).
    struct Parts
    {
      const FeScene &scene;
      const DofSpace &dofs;
      const Assembler &system;
      State &state;
      const ContactProblem &contact;
      MPI_Comm comm;
    };

    MaterialNewton(MaterialProblem &problem, const Parts &parts);

    /// [m] Converged when the correction is below 1e-7 of the push (δ_max = 1 mm: 0.1 nm), far
    /// below the discretisation error; quadratic convergence reaches it in a few iterations
    /// once the plastic zone and the active set have settled.
    double tolerance() const { return 1e-7 * parts_.scene.loading.delta_max; }

    /// One iteration from the current u: the tangent, its load and the active-set contact
    /// solve at the push δ; how far u moved [m]. `line_search` (an iteration after a step's
    /// first, whose start already meets the step's prescribed motion): the step is shortened
    /// where it overshoots the energy's minimum along it. Throws StepFailure.
    /// `after_solve` (when given) runs after the contact solve, before the line search, with
    /// the iteration's start; it must leave the state as it found it.
    MaterialIteration
    iterate(double delta, bool line_search,
            const std::function<void(const TrilinosWrappers::MPI::Vector &u_start)> &after_solve =
              {});

    /// Iterations until the correction is below tolerance(), at most max_it; the line search
    /// from the second on when solver.line_search. Throws StepFailure when it diverges (the
    /// correction grew three iterations running) or runs out of iterations.
    MaterialSolve solve(double delta, unsigned int max_it);

    /// The assembled tangent no longer belongs to u: the history was committed or restored,
    /// or the matrices were made again.
    void forget_tangent() { tangent_current_ = false; }

  private:
    /// [N] the out-of-balance force r = K u − b at the current u with the tangent and load
    /// assembled there, the hanging DoFs' shares on their masters, zero on the constrained
    /// DoFs (supports, symmetry, push) and on the contact nodes' and their partners' (their
    /// balance holds the contact forces, which only a contact solve gives). Collective.
    TrilinosWrappers::MPI::Vector interior_forces() const;
    /// The line search along the Newton step `step` from `u_start`, g0 = step · r(u_start) < 0;
    /// leaves u at the point it accepts.
    void search_line(MaterialIteration &it, double g0, const TrilinosWrappers::MPI::Vector &u_start,
                     const TrilinosWrappers::MPI::Vector &step);

    MaterialProblem &problem_;
    const Parts parts_;
    const unsigned int rank_;
    /// The line search leaves the tangent assembled at the point it accepts: the next
    /// iteration starts from it instead of assembling again, if u is still that point and
    /// forget_tangent() was not called since.
    bool tangent_current_ = false;
    TrilinosWrappers::MPI::Vector u_at_tangent_;
    unsigned int n_plastic_at_tangent_ = 0;
  };
}  // namespace clearjoint::fe::detail
