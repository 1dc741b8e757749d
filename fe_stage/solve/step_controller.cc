#include "fe_stage/solve/step_controller.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clearjoint::fe
{
  StepController::StepController(const double nominal, const unsigned int max_cuts,
                                 const unsigned int grow_after)
    : nominal_(nominal)
    , floor_(std::ldexp(nominal, -static_cast<int>(std::min(max_cuts, 1000u))))
    , max_cuts_(max_cuts)
    , grow_after_(grow_after)
    , carried_(nominal)
    , size_(nominal)
  {
    // (the scene validator owns the user-facing checks of the sizes and of loading.max_cuts)
    if (!(std::isfinite(nominal) && nominal > 0.0))
      throw std::invalid_argument("StepController: the nominal step must be finite and > 0");
    if (grow_after == 0)
      throw std::invalid_argument("StepController: grow_after must be >= 1");
  }

  double StepController::begin_step(const double remaining)
  {
    cuts_ = 0;
    size_ = std::min(carried_, remaining);
    return size_;
  }

  bool StepController::cut()
  {
    if (cuts_ >= max_cuts_ || at_floor())
      return false;
    ++cuts_;
    size_ *= 0.5;
    return true;
  }

  std::string StepController::floor_note(const std::string &unit) const
  {
    if (!at_floor())
      return "";
    return " (a shorter step than the nominal " + format_value(nominal_) + " " + unit + " halved " +
           std::to_string(max_cuts_) + " times, loading.max_cuts, is not tried)";
  }

  void StepController::restore(const Carried &c)
  {
    if (!(c.size > 0.0 && c.size <= nominal_))
      throw std::invalid_argument("StepController: a carried size must be in (0, nominal]");
    carried_ = c.size;
    easy_steps_ = c.easy_steps;
  }

  void StepController::accept()
  {
    if (cuts_ > 0)
      {
        carried_ = size_;
        easy_steps_ = 0;
      }
    else if (carried_ < nominal_ && ++easy_steps_ >= grow_after_)
      {
        carried_ = std::min(nominal_, 2.0 * carried_);
        easy_steps_ = 0;
      }
  }
}  // namespace clearjoint::fe
