// The quasi-static studies' stepper: the push δ from rest through a list of targets (the
// radial, misalignment, Hertz and patch studies' curves, their adaptive cycles' marking pushes,
// and the impact study's static probe and reference curve). It owns its loop and its state —
// the last two converged displacements, from which it predicts the next, and the count of
// finite sliding's extra solves — and asks the model, through QuasiStaticProblem
// (solve/stepper_interfaces.h), for what only the whole model can do: a contact solve, the
// contact's evaluation at a predicted state, the rollback of a failed attempt.
//
// One increment to δ: the displacement extrapolated linearly in δ from the last two converged
// states, with every node it penetrates activated; the converged state at δ (a contact solve,
// or the material Newton iteration of an elastoplastic body); with finite sliding the mortar
// search again at the converged surfaces until the coupling stops moving; the material's
// history committed and the friction's slip counted from here. An attempt that fails is
// restored and halved (solve/step_controller.h, loading.max_cuts).
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/scene.h"
#include "fe_stage/solve/material_newton.h"
#include "fe_stage/solve/stepper_interfaces.h"

#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  class QuasiStaticStepper
  {
  public:
    /// The model's parts the stepper works on: it sets u for the predictor, activates the
    /// nodes the prediction penetrates, and runs the material Newton iteration of an
    /// elastoplastic body.
    struct Parts
    {
      const FeScene &scene;
      const DofSpace &dofs;
      State &state;
      ContactProblem &contact;
      MaterialNewton &newton;
      MPI_Comm comm;
      /// contact.sliding finite: the search again after each converged increment
      bool finite_sliding = false;
    };

    QuasiStaticStepper(QuasiStaticProblem &problem, const Parts &parts);

    /// Pushes from δ = 0 (the model at rest) through `targets` (increasing, the last δ_max):
    /// each target reached from the last converged state, and halved on failure up to
    /// loading.max_cuts times (one controller per target: the increments to a target never
    /// grow back). `on_converged(k, record)` is called for target k = 1, 2, … Returns false
    /// with `message` set when an increment fails for good.
    bool push_through(const std::vector<double> &targets, std::string &message,
                      const std::function<void(unsigned int, IncrementRecord &)> &on_converged);

    /// contact.sliding finite: the mortar search again after each converged increment (as the
    /// model's contact pattern says).
    bool finite_sliding() const { return parts_.finite_sliding; }
    /// Increments solved again with a new coupling by finite sliding, over every push so far.
    unsigned int sliding_resolves() const { return n_sliding_resolves_; }

  private:
    /// The displacement extrapolated linearly in δ to `try_delta` from the last two converged
    /// states, and every node the prediction penetrates activated (the active set then mostly
    /// settles in one or two iterations).
    void predict(double try_delta, double delta_done, double delta_previous,
                 const TrilinosWrappers::MPI::Vector &u_previous);
    /// The converged state at δ from the current one; throws StepFailure.
    IncrementRecord solve_state(double delta, const TrilinosWrappers::MPI::Vector &u_start);
    /// Finite sliding: the mortar search again at the converged surfaces, and the increment
    /// solved again with the new coupling (slip counted from the increment's start `u_start`)
    /// until the coupling stops moving. Throws StepFailure when it still moves after 10.
    IncrementRecord settle_sliding(double delta, const TrilinosWrappers::MPI::Vector &u_start,
                                   IncrementRecord rec);

    QuasiStaticProblem &problem_;
    Parts parts_;
    const unsigned int rank_;
    unsigned int n_sliding_resolves_ = 0;
  };
}  // namespace clearjoint::fe::detail
