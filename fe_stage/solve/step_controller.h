// The one step-size policy of fe_stage's steppers (the quasi-static push's increments of δ, the
// impact study's Δt, the rolling study's Δt), after the shape of Chrono's timestepper step
// control (SetStepControl, SetMinStepSize): a step that fails is tried again at half the size —
// at most `max_cuts` times per step, and never below the floor, the nominal size halved
// max_cuts times (the size carries over between steps, so the cuts of one step alone would not
// bound it). After a step that needed cuts the next one starts at its size, which doubles back
// toward the nominal once `grow_after` steps in a row converged without a cut (Abaqus/Standard's
// automatic incrementation grows the same way). No deal.II; unit-tested in
// tests/unit/fe/step_controller_test.cc.
#pragma once

#include <limits>
#include <string>

namespace clearjoint::fe
{
  class StepController
  {
  public:
    /// nominal > 0 [the stepped variable's unit]; grow_after ≥ 1 steps.
    StepController(double nominal, unsigned int max_cuts, unsigned int grow_after);

    /// Starts a step: the attempt's size is the carried size, shortened to `remaining` (a
    /// target or an end time reached exactly). Returns it.
    double begin_step(double remaining = std::numeric_limits<double>::infinity());
    /// The size of the attempt in progress.
    double size() const { return size_; }
    /// Cuts of the step in progress.
    unsigned int cuts() const { return cuts_; }
    /// After a failed attempt: halves the size and returns true, or returns false (the size
    /// unchanged) when the step has had max_cuts cuts or half the size is below the floor.
    bool cut();
    /// Whether half the attempt's size is below the floor.
    bool at_floor() const { return 0.5 * size_ < floor_; }
    /// For the message of a refused cut: what the floor refused (empty when it was the number
    /// of cuts), e.g. " (a shorter step than the nominal 0.01 s halved 6 times,
    /// loading.max_cuts, is not tried)"; `unit` of the stepped variable.
    std::string floor_note(const std::string &unit) const;
    /// After the step converged: the size the next step starts at.
    void accept();

    /// The size the next step starts at (before begin_step's `remaining`).
    double next_size() const { return carried_; }
    /// What carries from one step to the next (a restart file keeps it): the next step's
    /// size and the steps converged without a cut since it last changed.
    struct Carried
    {
      double size = 0.0;
      unsigned int easy_steps = 0;
    };
    Carried carried() const { return {carried_, easy_steps_}; }
    /// Throws std::invalid_argument for a size that is not in (0, nominal].
    void restore(const Carried &c);
    double nominal() const { return nominal_; }
    double floor() const { return floor_; }
    unsigned int max_cuts() const { return max_cuts_; }

  private:
    double nominal_, floor_;
    unsigned int max_cuts_, grow_after_;
    double carried_;               // the next step's size before `remaining`
    double size_;                  // the attempt's
    unsigned int cuts_ = 0;        // of the step in progress
    unsigned int easy_steps_ = 0;  // converged without a cut since the size last changed
  };
}  // namespace clearjoint::fe
