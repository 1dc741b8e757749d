// Whether a contact solve's stick/slip iteration still makes progress. The iteration
// (solve/contact_iteration.cc) decides each node's stick, slip or open state and linearises
// Coulomb's slip law; friction's constant c_T steers its path, not its converged state
// (docs/fe.md). Too stiff a c_T makes it cycle: on the rolling study's deformable journal the
// slip law's residual alternated between 319 and 326 N for ten iterations with the sets
// unchanged, or rose from 480 to 3 200 N over twelve iterations of nodes flipping between
// stick, slip and open, until a softening after 12 iterations lowered c_T. This says so after
// two iterations, so that c_T is lowered then (docs/benchmarks.md "The direct solver without
// scaling, and the stick/slip iteration's cycles").
#pragma once

#include <limits>

namespace clearjoint::fe
{
  class StickSlipProgress
  {
  public:
    /// The slip law's residual [N] after an iteration, and whether it is within the solve's
    /// tolerance. True when the iteration cycles: unsettled, and two iterations in a row have
    /// not halved the best residual since the start or the last restart().
    bool record(const double slip_residual, const bool settled)
    {
      if (slip_residual <= 0.5 * best_)
        {
          best_ = slip_residual;
          without_progress_ = 0;
        }
      else
        ++without_progress_;
      return !settled && without_progress_ >= 2;
    }

    /// c_T was changed: the iterations from here are judged afresh.
    void restart()
    {
      best_ = std::numeric_limits<double>::infinity();
      without_progress_ = 0;
    }

  private:
    double best_ = std::numeric_limits<double>::infinity();  // [N]
    unsigned int without_progress_ = 0;
  };
}  // namespace clearjoint::fe
