// The model as each time stepper sees it (issue 29: no stepper reaches into the model's members).
// A stepper owns its loop and its state; it is given the parts it works on — the scene, the DoF
// space, the assembler, the state u, the contact nodes, the journal frame — and, for what only
// the whole model can do (a contact solve, a material Newton iteration, the rollback of a failed
// attempt), one of the interfaces below, which Model implements:
//   - QuasiStaticProblem: the quasi-static push (solve/quasi_static_stepper.h);
//   - DynamicProblem:     the impact study's HHT-α stepper (solve/hht_stepper.h);
//   - SpinProblem:        the rolling study's spin stepper (solve/spin_stepper.h).
// Also here: the values those operations return (MaterialIteration: solve/material_newton.h).
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/solve/hht.h"
#include "fe_stage/solve/material_newton.h"

#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace clearjoint::fe::detail
{
  /// What a failed attempt of a step goes back to: the displacement and the contact nodes
  /// (active and stick sets, slip history, partners), and the count of finite sliding's
  /// pattern rebuilds (a rebuild since then: the restored state is paired again so that the
  /// pattern holds its partners). The one rollback of every stepper.
  struct Snapshot
  {
    TrilinosWrappers::MPI::Vector u;  // owned
    std::vector<ContactNode> nodes;
    unsigned int sliding_rebuilds = 0;
  };

  /// One converged state of the rolling bearing for a given journal spin (the torque
  /// balance's evaluation, Model::solve_rolling_state).
  struct RollingSolve
  {
    double torque_journal = 0.0;  // [N m] full body, on the journal about +z
    unsigned int newton_iterations = 0, contact_iterations = 0, linear_iterations = 0;
    unsigned int line_search_steps = 0;
    IncrementRecord record;
  };

  /// How the linearised state of a material Newton iteration moves with the deformable or rigid
  /// journal's turn ψ (the bordered spin iteration's column, solve/spin_stepper.cc): the
  /// iteration's contact solve repeated at ψ + d_psi — the same tangent, the same active and
  /// stick sets, from the same start — and the differences it makes.
  struct TurnSensitivity
  {
    double d_psi = 0.0;                // [rad] the turn it is taken over (set by the caller)
    TrilinosWrappers::MPI::Vector du;  // [m] u(ψ + d_psi) − u(ψ), owned
    double d_torque = 0.0;             // [N m] M(ψ + d_psi) − M(ψ), full body
    unsigned int linear_iterations = 0;
  };

  /// What the quasi-static push asks of the model.
  class QuasiStaticProblem
  {
  public:
    /// Zero displacement, no contact, every node sticking with no slip history.
    virtual void start_from_rest() = 0;
    virtual Snapshot save_state() const = 0;
    virtual void restore_state(const Snapshot &s) = 0;
    /// The obstacle at the push δ and the contact nodes' gaps at the current u (the
    /// predictor's active set).
    virtual void evaluate_contact_at(double delta) = 0;
    /// One contact solve to the push δ from the current state; throws StepFailure.
    virtual IncrementRecord solve_increment(double delta) = 0;
    /// The bodies are elastoplastic: a state is the material Newton iteration's, and a
    /// converged one is committed to the points' history.
    virtual bool elastoplastic() const = 0;
    virtual void commit_material() = 0;
    /// Finite sliding: the mortar search again at the deformed surfaces, slip counted from
    /// `u_start`; how far the coupling moved.
    virtual double pair_deformed_surfaces(const TrilinosWrappers::MPI::Vector &u_start) = 0;

  protected:
    ~QuasiStaticProblem() = default;
  };

  /// What the impact study's stepper asks of the model.
  class DynamicProblem
  {
  public:
    /// The assembled operator becomes c_m M + c_k K (the solver's AMG is built again).
    virtual void set_dynamic_operator(const MatrixCoefficients &c) = 0;
    /// Zero displacement, no contact, every node sticking with no slip history.
    virtual void start_from_rest() = 0;
    /// Each contact node's share of the step's known load (the friction rows read K u − b).
    virtual void set_contact_load_offsets() = 0;
    /// One contact solve to the push δ from the current state; throws StepFailure.
    virtual IncrementRecord solve_increment(double delta) = 0;
    virtual Snapshot save_state() const = 0;
    virtual void restore_state(const Snapshot &s) = 0;

  protected:
    ~DynamicProblem() = default;
  };

  /// What the rolling study's spin stepper asks of the model.
  class SpinProblem
  {
  public:
    virtual Snapshot save_state() const = 0;
    virtual void restore_state(const Snapshot &s) = 0;
    /// The journal is deformable and turns over the bore: its partners must be found again
    /// for each pose (pair_turned_journal).
    virtual bool journal_turns_deformable() const = 0;
    /// The bore nodes' partners found again for the journal's pose now, slip counted from
    /// `u_start` (the step's start).
    virtual void pair_turned_journal(const TrilinosWrappers::MPI::Vector &u_start) = 0;
    /// The converged elastoplastic state at the push δ for the spin in the journal frame, and
    /// the journal's torque there; throws StepFailure.
    virtual RollingSolve solve_rolling_state(double delta) = 0;
    /// One material Newton iteration (the coupled spin iteration's); with `sensitivity`, also
    /// its solve's dependence on the journal's turn (TurnSensitivity; the state is the
    /// iteration's own afterwards). Throws StepFailure.
    virtual MaterialIteration material_iteration(double delta, bool line_search,
                                                 TurnSensitivity *sensitivity) = 0;
    /// [N m] the contact's torque on the journal about its axis, full body (collective).
    virtual double journal_torque() const = 0;
    /// [m] the material Newton iteration's tolerance on its correction.
    virtual double material_tolerance() const = 0;

  protected:
    ~SpinProblem() = default;
  };
}  // namespace clearjoint::fe::detail
