// MUMPS through Amesos, keeping the factorization while the matrix keeps its values.
#include "fe_stage/solve/direct_solver.h"

#include "fe_stage/core/step_failure.h"
#include "fe_stage/solve/mumps_statistics.h"

#include <deal.II/base/mpi.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <array>
#include <string>

namespace clearjoint::fe::detail
{
  DirectSolver::DirectSolver() = default;
  DirectSolver::~DirectSolver() = default;

  void DirectSolver::invalidate()
  {
    solver_.reset();
    problem_.reset();
    analysed_ = nullptr;
    analysed_nonzeros_ = 0;
    estimated_memory_ = 0.0;
    factored_ = false;
    factored_values_.clear();
  }

  bool DirectSolver::holds_pattern_of(const dealii::TrilinosWrappers::SparseMatrix &A) const
  {
    // the analysis belongs to one matrix object and its pattern: a reallocated or re-patterned
    // matrix is analysed again (every rank holds the same matrix object's part, so the test
    // agrees across ranks except for the pattern's size, hence the collective minimum)
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    const bool held = &matrix == analysed_ && factored_ &&
                      std::size_t(matrix.NumMyNonzeros()) == factored_values_.size();
    return dealii::Utilities::MPI::min(held ? 1 : 0, A.get_mpi_communicator()) == 1;
  }

  bool DirectSolver::holds_values_of(const dealii::TrilinosWrappers::SparseMatrix &A) const
  {
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    bool same = std::size_t(matrix.NumMyNonzeros()) == factored_values_.size();
    std::size_t k = 0;
    for (int row = 0; same && row < matrix.NumMyRows(); ++row)
      {
        int n = 0;
        double *values = nullptr;
        matrix.ExtractMyRowView(row, n, values);
        same = std::equal(values, values + n, factored_values_.begin() + k);
        k += n;
      }
    // one rank's change refactors on all (MUMPS factors collectively)
    return dealii::Utilities::MPI::min(same ? 1 : 0, A.get_mpi_communicator()) == 1;
  }

  void DirectSolver::keep_values(const Epetra_CrsMatrix &A)
  {
    factored_values_.resize(A.NumMyNonzeros());
    std::size_t k = 0;
    for (int row = 0; row < A.NumMyRows(); ++row)
      {
        int n = 0;
        double *values = nullptr;
        A.ExtractMyRowView(row, n, values);
        std::copy(values, values + n, factored_values_.begin() + k);
        k += n;
      }
  }

  namespace
  {
    void check(const int status, const char *what)
    {
      if (status != 0)
        throw StepFailure{std::string("direct solver (MUMPS through Amesos): ") + what +
                          " failed, status " + std::to_string(status) +
                          " (a singular system, or too little memory)"};
    }
  }  // namespace

  double DirectSolver::analyse(const dealii::TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    const bool held = &matrix == analysed_ &&
                      std::size_t(matrix.NumMyNonzeros()) == analysed_nonzeros_;
    if (dealii::Utilities::MPI::min(held ? 1 : 0, A.get_mpi_communicator()) == 1)
      return estimated_memory_;
    invalidate();
    problem_ = std::make_unique<Epetra_LinearProblem>();
    problem_->SetOperator(const_cast<Epetra_CrsMatrix *>(&matrix));
    Amesos factory;
    solver_.reset(factory.Create("Amesos_Mumps", *problem_));
    if (!solver_)
      throw StepFailure{"direct solver: Trilinos' Amesos has no MUMPS"};
    // No scaling (ICNTL(8) = 0). MUMPS's automatic choice, an iterative simultaneous
    // row/column scaling, cost 15 % of the rolling study's run (perf, the paper's case on
    // the coarsest ring: ~1 600 factorizations of 2.7 k DoFs each); without it the results
    // agree to the solvers' tolerances (bench/fe_unchanged.py: forces within 2e-10 of their
    // largest, a reduced rolling case's tangential force within 3e-7; docs/benchmarks.md
    // "The direct solver without scaling, and the stick/slip iteration's cycles"): the
    // assembled FE operators are well scaled, and the threshold pivoting stays on.
    Teuchos::ParameterList parameters;
    parameters.sublist("mumps").set("ICNTL(8)", 0);
    check(solver_->SetParameters(parameters), "setting the parameters");
    check(solver_->SymbolicFactorization(), "the symbolic analysis");
    analysed_ = &matrix;
    analysed_nonzeros_ = matrix.NumMyNonzeros();
    // (certain on MUMPS's host, rank 0, as the counts below)
    estimated_memory_ = dealii::Utilities::MPI::broadcast(
      A.get_mpi_communicator(), 1e6 * mumps_statistics(*solver_).estimated_memory_mb, 0);
    return estimated_memory_;
  }

  void DirectSolver::factor(const dealii::TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    analyse(A);
    check(solver_->NumericFactorization(), "the factorization");
    keep_values(matrix);
    factored_ = true;
    ++n_factorizations_;
    // MUMPS's global counts are certain on its host, rank 0; every rank takes them from there,
    // so that the ranks' choices between reusing the factors and factoring agree (a rank that
    // factors while another runs GMRES deadlocks the collectives; a two-rank run did)
    const MumpsStatistics statistics = mumps_statistics(*solver_);
    const std::array<double, 2> counts = dealii::Utilities::MPI::broadcast(
      A.get_mpi_communicator(),
      std::array<double, 2>{statistics.factorization_flops, statistics.factor_entries}, 0);
    factorization_flops_ = counts[0];
    factor_entries_ = counts[1];
  }

  void DirectSolver::apply(dealii::TrilinosWrappers::MPI::Vector &x,
                           const dealii::TrilinosWrappers::MPI::Vector &b) const
  {
    problem_->SetLHS(&x.trilinos_vector());
    problem_->SetRHS(const_cast<Epetra_MultiVector *>(
      static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
    check(solver_->Solve(), "the solve");
  }

  void DirectSolver::solve(const dealii::TrilinosWrappers::SparseMatrix &A,
                           dealii::TrilinosWrappers::MPI::Vector &x,
                           const dealii::TrilinosWrappers::MPI::Vector &b)
  {
    if (holds_pattern_of(A) && holds_values_of(A))
      ++n_reuses_;
    else
      factor(A);
    apply(x, b);
  }
}  // namespace clearjoint::fe::detail
