// The direct solve of the contact model's systems: MUMPS (a multifrontal LU, through Trilinos'
// Amesos) that keeps its factorization while the matrix keeps its values. Within one step the
// condensed system often repeats: the impact study's journal iterations solve the same
// operator with the same active set at a new position of the journal (measured: 157 of 329
// solves of the standard preset's impact case repeat the matrix of the solve before), and
// only the right-hand side changes. A Krylov method pays its full cost for each; here such a
// solve is two triangular solves. The symbolic analysis (ordering) is kept while the matrix
// object and its sparsity pattern stay (the model's pattern is fixed per mesh: it holds every
// candidate's contact line), the numeric factorization while the values stay too; whether
// they did is decided by comparing the values with a copy of the factored ones, on every
// rank together.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <mpi.h>

#include <memory>
#include <vector>

class Amesos_BaseSolver;
class Epetra_CrsMatrix;
class Epetra_LinearProblem;

namespace clearjoint::fe::detail
{
  class DirectSolver
  {
  public:
    DirectSolver();
    ~DirectSolver();

    /// x = A⁻¹ b. Factors A unless it is the matrix of the last factorization with the same
    /// values. Throws StepFailure with MUMPS's reason (a singular matrix, too little memory).
    void solve(const dealii::TrilinosWrappers::SparseMatrix &A,
               dealii::TrilinosWrappers::MPI::Vector &x,
               const dealii::TrilinosWrappers::MPI::Vector &b);

    /// The matrix's sparsity pattern changed (a new mesh or operator): analyse it again.
    void invalidate();

    /// Whether the kept factorization is of A's matrix object with its pattern (collective).
    bool holds_pattern_of(const dealii::TrilinosWrappers::SparseMatrix &A) const;
    /// Whether A's values are the factored ones (collective).
    bool holds_values_of(const dealii::TrilinosWrappers::SparseMatrix &A) const;
    /// Analyses A's pattern (MUMPS's ordering and symbolic factorization) unless the kept
    /// analysis is of it; returns MUMPS's estimate of the memory the factorization will need
    /// in core, all ranks together [bytes] (collective). Throws StepFailure with MUMPS's reason.
    double analyse(const dealii::TrilinosWrappers::SparseMatrix &A);
    /// Factors A, analysing its pattern first unless the kept analysis is of it. Throws
    /// StepFailure with MUMPS's reason.
    void factor(const dealii::TrilinosWrappers::SparseMatrix &A);
    /// x = M⁻¹ b with M the matrix of the kept factorization (two triangular solves; A's
    /// values may have moved on since: a stale factorization preconditions a Krylov method).
    void apply(dealii::TrilinosWrappers::MPI::Vector &x,
               const dealii::TrilinosWrappers::MPI::Vector &b) const;
    /// [flops] MUMPS's count for the last factorization, and the entries of its factors
    /// (summed over the ranks): what one factorization and one apply() cost.
    double factorization_flops() const { return factorization_flops_; }
    double factor_entries() const { return factor_entries_; }

    /// Numeric factorizations, and solves that reused the last one.
    unsigned int n_factorizations() const { return n_factorizations_; }
    unsigned int n_reuses() const { return n_reuses_; }

  private:
    void keep_values(const Epetra_CrsMatrix &A);

    std::unique_ptr<Epetra_LinearProblem> problem_;
    std::unique_ptr<Amesos_BaseSolver> solver_;
    const Epetra_CrsMatrix *analysed_ = nullptr;  // the matrix the symbolic analysis is of
    std::size_t analysed_nonzeros_ = 0;           // its pattern's size on this rank
    double estimated_memory_ = 0.0;               // [bytes] the analysis's estimate, all ranks
    bool factored_ = false;
    double factorization_flops_ = 0.0, factor_entries_ = 0.0;
    std::vector<double> factored_values_;  // this rank's rows, in storage order
    unsigned int n_factorizations_ = 0;
    unsigned int n_reuses_ = 0;
  };
}  // namespace clearjoint::fe::detail
