// When the direct solver's kept LU factorization is still worth using as GMRES's
// preconditioner for a changed matrix, instead of factoring the new one (SystemSolver's direct
// mode, solve/linear_solver.h). Within a step the contact model's matrix changes at every
// active-set and material iteration, but by little: a few contact rows, the plastic tangent at
// the yielding points. A factorization of an earlier matrix is then a preconditioner that
// leaves GMRES a few iterations, each two triangular solves with the kept factors — on the
// rolling study's finest ring (83 k DoFs) a factorization cost ~2.9 s, most of the run.
//
// The rule counts in flops, so that the solver's path does not depend on timing: one
// factorization's flops (MUMPS's own count) against one GMRES iteration's (the factors'
// entries and the matrix's non-zeros, each used once: a multiply and an add), scaled by how
// much faster the dense kernels of a factorization run than the memory-bound triangular
// solves. Once the iterations spent with the kept factors reach that budget, the next changed
// matrix is factored again: the time lost to a stale preconditioner is bounded by about the
// time a factorization would have taken.
#pragma once

#include <cmath>

namespace clearjoint::fe
{
  class FactorizationReuse
  {
  public:
    /// A solve that needs more iterations than this is factored afresh instead: the kept
    /// factors are too far from the matrix.
    static constexpr unsigned int max_iterations_per_solve = 30;
    /// The factorization's dense kernels run this much faster per flop than an iteration's
    /// sparse ones (measured, docs/benchmarks.md "The kept factors as GMRES's preconditioner").
    static constexpr double dense_speedup = 15.0;

    /// A new factorization of `factorization_flops`, with `factor_entries` entries in its factors,
    /// of a matrix with `matrix_nonzeros`.
    void factored(const double factorization_flops, const double factor_entries,
                  const double matrix_nonzeros)
    {
      const double iteration_flops = 2.0 * (factor_entries + matrix_nonzeros);
      budget_ =
        iteration_flops > 0.0 ? factorization_flops / (dense_speedup * iteration_flops) : 0.0;
      spent_ = 0.0;
    }

    /// A GMRES solve preconditioned by the kept factors took `iterations`.
    void record(const unsigned int iterations) { spent_ += iterations; }

    /// A try fits into what is left of one factorization's cost: at least the iterations the
    /// forecast needs to judge it (the rolling study's coarsest ring, 2 745 DoFs, whose
    /// factorization costs a few iterations, is always factored).
    bool worth_reusing() const { return budget_ - spent_ >= min_steps_for_forecast; }

    /// Whether a solve whose residual fell from `initial` to `now` in `step` iterations would,
    /// at that mean rate, need more than `max_steps` to reach `tolerance`: the kept factors
    /// are too far from the matrix, and trying on costs more than it can save. Judged from
    /// `min_steps_for_forecast` iterations on (the first ones of GMRES are the least telling).
    static bool forecast_exceeds(const unsigned int step, const double initial, const double now,
                                 const double tolerance, const unsigned int max_steps)
    {
      if (step < min_steps_for_forecast || !(now > tolerance) || !(initial > now))
        return false;
      const double rate = std::pow(now / initial, 1.0 / step);
      return step + std::log(tolerance / now) / std::log(rate) > max_steps;
    }
    static constexpr unsigned int min_steps_for_forecast = 4;

    /// [iterations] one factorization's cost, and what the kept factors have taken.
    double budget() const { return budget_; }
    double spent() const { return spent_; }

  private:
    double budget_ = 0.0, spent_ = 0.0;
  };
}  // namespace clearjoint::fe
