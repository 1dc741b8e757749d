// When the AMG preconditioner has gone stale and is worth building again (SystemSolver,
// solve/linear_solver.h). An active-set contact solve changes the matrix at every iteration
// (rows of active nodes, friction's slip directions), and an AMG built for an earlier matrix
// converges ever more slowly: on the standard thickness case at t_B = 8 mm (102 k DoFs) its
// solves took 593 iterations in the first increment against 281 with a fresh AMG at every
// solve, and a fresh AMG for every solve halved the run's iterations but spent 40 % of the solve
// time in setups (docs/benchmarks.md "The AMG rebuilt when stale").
//
// The rule weighs the two, in iterations so that the solver's path does not depend on timing:
// each solve's iterations per decade of residual reduction, against those of the first solve
// after the build, give the iterations the staleness cost; once they add up to more than one
// build costs (rebuild_after_lost_iterations), the next solve builds a fresh AMG: the time
// lost to staleness is bounded by about the time spent in builds.
#pragma once

#include <algorithm>
#include <cmath>

namespace clearjoint::fe
{
  class AmgStaleness
  {
  public:
    /// About one AMG build's cost in Krylov iterations with it: ML's setup for FE_Q(2)^3 with
    /// aggregation threshold 0 took 0.91 s on 102 k DoFs where an iteration took 63 ms (14
    /// iterations; both scale with the matrix's non-zeros). Not tuned further.
    static constexpr double rebuild_after_lost_iterations = 10.0;

    /// A fresh AMG: the next solve sets the rate it is judged by.
    void built()
    {
      fresh_rate_ = 0.0;
      lost_ = 0.0;
    }

    /// A Krylov solve with the current AMG took `iterations` from the residual
    /// `initial_residual` to `final_residual`. A solve that did not reduce it (a zero
    /// right-hand side, a start already within tolerance) says nothing about the AMG.
    void record(const unsigned int iterations, const double initial_residual,
                const double final_residual)
    {
      if (iterations == 0 || !(final_residual > 0.0) || !(initial_residual > final_residual))
        return;
      const double decades = std::log10(initial_residual / final_residual);
      const double rate = iterations / decades;  // iterations per decade
      if (fresh_rate_ == 0.0)
        fresh_rate_ = rate;
      else
        lost_ += std::max(0.0, iterations - fresh_rate_ * decades);
    }

    /// The iterations lost to staleness since the build exceed one build's cost.
    bool stale() const { return lost_ > rebuild_after_lost_iterations; }

    /// Within a solve: after `iterations` that brought the residual from `initial_residual` to
    /// `residual`, the iterations lost so far (this solve's and the earlier ones') exceed one
    /// build's cost, so that going on with this AMG costs more than a fresh one from here. A
    /// solve whose matrix moved far from the AMG's (the first contact rows after a solve
    /// without them: 194 iterations where 35 are usual, docs/benchmarks.md "Where a standard
    /// sweep case spends its time") is then stopped and continued from its iterate with a
    /// fresh AMG, instead of being judged only after it. Never before the rate is set.
    bool stale_within(const unsigned int iterations, const double initial_residual,
                      const double residual) const
    {
      if (fresh_rate_ == 0.0 || !(initial_residual > 0.0) || !(residual > 0.0))
        return false;
      const double decades = std::max(0.0, std::log10(initial_residual / residual));
      const double lost_now = std::max(0.0, iterations - fresh_rate_ * decades);
      return lost_ + lost_now > rebuild_after_lost_iterations;
    }

    /// [iterations] lost to staleness since the build.
    double lost_iterations() const { return lost_; }

  private:
    double fresh_rate_ = 0.0;  // iterations per decade of the first solve after the build
    double lost_ = 0.0;
  };
}  // namespace clearjoint::fe
