#include "laws/law_range_error.h"

namespace clearjoint::laws
{
  LawRangeError::LawRangeError(const double delta, const double delta_min, const double delta_max)
    : NumericalError("contact law evaluated at delta = " + format_value(delta) + " m (" +
                     format_value(delta * 1e3) + " mm), outside its valid range [" +
                     format_value(delta_min) + ", " + format_value(delta_max) +
                     "] m; the scene's out_of_range policy is 'error' (use clamp or extend to "
                     "continue, or a law fitted over a wider range)")
    , delta_(delta)
  {}
} // namespace clearjoint::laws
