// A load step that did not converge (linear solver, active set, non-finite force, penetration):
// the stepping catches it, restores the last converged state and cuts the step.
#pragma once

#include <string>

namespace clearjoint::fe::detail
{
  struct StepFailure
  {
    std::string reason;
  };
}  // namespace clearjoint::fe::detail
