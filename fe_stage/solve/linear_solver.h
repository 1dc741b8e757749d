// The linear solver (SystemSolver) of the contact model's systems: MUMPS below a size
// (DirectSolver, solve/direct_solver.h: it keeps its factorization while the matrix repeats,
// and for a changed matrix of the same pattern the kept factors precondition GMRES while that
// costs less than a new factorization, solve/factorization_reuse.h), else CG
// (GMRES where friction makes the operator non-symmetric) preconditioned by ML's AMG on the six
// rigid-body modes. It owns the AMG and decides when to rebuild it: once per new operator pattern or mesh
// (invalidate()), again when a solve fails with the reused one, and when the iterations its
// staleness has cost since its build outweigh a new build (solve/amg_staleness.h). A Krylov
// solve that fails even with a fresh AMG is solved by MUMPS where the system is small enough.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/solve/amg_staleness.h"
#include "fe_stage/solve/direct_solver.h"
#include "fe_stage/solve/factorization_reuse.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_MultiVector.h>

#include <memory>
#include <string>

namespace clearjoint::fe::detail
{
  using namespace dealii;

  class SystemSolver
  {
  public:
    /// What it solves with: MUMPS (`direct`), else the Krylov method within `max_iterations`.
    void configure(bool direct, unsigned int max_iterations);
    bool direct() const { return direct_; }

    /// The operator changed its pattern or the mesh changed: the AMG is built again at the
    /// next solve.
    void invalidate()
    {
      amg_.reset();
      direct_solver_.invalidate();
    }

    /// Solves A x = b to `relative_tolerance` × |b| (x: the start, then the solution); returns
    /// the Krylov iterations (1 for the direct solver). `dofs` and `mapping` give the rigid-body modes when
    /// the AMG is (re)built. Throws StepFailure with the reason.
    unsigned int solve(const TrilinosWrappers::SparseMatrix &A, bool nonsymmetric,
                       const DoFHandler<dim> &dofs, const Mapping<dim> &mapping,
                       TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &b,
                       double relative_tolerance);

    /// What the solves cost, for the run's summary: the AMG's builds, or MUMPS's
    /// factorizations and reuses.
    std::string summary() const;

  private:
    /// The direct mode's solve: the kept factorization for the same matrix; for a changed one
    /// of the same pattern, GMRES preconditioned by it (to the residual `tolerance`) while
    /// that is cheaper than factoring again (FactorizationReuse); else a new factorization.
    unsigned int solve_direct(const TrilinosWrappers::SparseMatrix &A,
                              TrilinosWrappers::MPI::Vector &x,
                              const TrilinosWrappers::MPI::Vector &b, double tolerance);
    void build_amg(const TrilinosWrappers::SparseMatrix &A, const DoFHandler<dim> &dofs,
                   const Mapping<dim> &mapping);

    bool direct_ = false;
    unsigned int max_iterations_ = 1000;
    DirectSolver direct_solver_;
    FactorizationReuse reuse_;  // when the kept factorization still pays as a preconditioner
    // the direct mode's solves: of the factored matrix itself; of a changed one by GMRES on
    // the kept factors; such tries that gave up
    unsigned int n_same_matrix_solves_ = 0, n_gmres_on_kept_factors_ = 0,
                 n_factorization_reuse_failures_ = 0;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_;
    std::unique_ptr<Epetra_MultiVector> null_space_;  // the AMG reads it: kept alive with it
    AmgStaleness staleness_;                          // when the AMG is worth building again
    unsigned int n_stale_stops_ = 0;                  // solves stopped, continued with a fresh AMG
    unsigned int n_amg_builds_ = 0;
    double t_amg_ = 0.0;
    unsigned int n_direct_fallbacks_ = 0;
    /// A failed Krylov solve is solved by MUMPS instead where this many times MUMPS's estimate
    /// of its factorization's memory (after its analysis) is free on the machine; else the
    /// step fails and is cut. The margin covers MUMPS's own relaxation of the estimate
    /// (ICNTL(14), 20 % by default) and what the run allocates besides.
    static constexpr double direct_fallback_memory_margin = 1.5;
  };
}  // namespace clearjoint::fe::detail
