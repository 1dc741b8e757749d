// The direct solver (fe_stage/solve/direct_solver.h): MUMPS solves exactly, keeps its
// factorization while the matrix repeats its values (a new right-hand side costs no new
// factorization), factors again when one value changes, and a singular system is a StepFailure
// with a reason, not a crash or a wrong answer.
#include "fe_stage/core/step_failure.h"
#include "fe_stage/solve/direct_solver.h"

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace clearjoint::fe::detail;
using namespace dealii;

namespace
{
  constexpr unsigned int n = 40;

  /// A tridiagonal, diagonally dominant matrix (a 1D Laplacian with a varying shift).
  void make_matrix(TrilinosWrappers::SparseMatrix &A)
  {
    const IndexSet all = complete_index_set(n);
    DynamicSparsityPattern dsp(n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(i + 1, n - 1); ++j)
        dsp.add(i, j);
    A.reinit(all, all, dsp, MPI_COMM_SELF);
    for (unsigned int i = 0; i < n; ++i)
      {
        A.set(i, i, 2.0 + 0.01 * i);
        if (i > 0)
          A.set(i, i - 1, -1.0);
        if (i + 1 < n)
          A.set(i, i + 1, -1.0);
      }
    A.compress(VectorOperation::insert);
  }

  /// |A x − b| / |b|
  double relative_residual(const TrilinosWrappers::SparseMatrix &A,
                           const TrilinosWrappers::MPI::Vector &x,
                           const TrilinosWrappers::MPI::Vector &b)
  {
    TrilinosWrappers::MPI::Vector r(b);
    A.vmult(r, x);
    r -= b;
    return r.l2_norm() / b.l2_norm();
  }
}  // namespace

TEST(DirectSolver, ReusesItsFactorizationWhileTheMatrixRepeats)
{
  const IndexSet all = complete_index_set(n);
  TrilinosWrappers::SparseMatrix A;
  make_matrix(A);
  TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(all, MPI_COMM_SELF);
  for (unsigned int i = 0; i < n; ++i)
    b(i) = std::sin(1.0 + i);
  b.compress(VectorOperation::insert);

  DirectSolver solver;
  solver.solve(A, x, b);
  // 1e-12: an LU of a well-conditioned 40 × 40 system (condition number < 1e3) leaves
  // round-off only
  EXPECT_LT(relative_residual(A, x, b), 1e-12);
  EXPECT_EQ(solver.n_factorizations(), 1u);
  EXPECT_EQ(solver.n_reuses(), 0u);

  // the same matrix, another right-hand side: the factorization is reused
  b *= -3.0;
  b(7) += 1.0;
  b.compress(VectorOperation::insert);
  solver.solve(A, x, b);
  EXPECT_LT(relative_residual(A, x, b), 1e-12);
  EXPECT_EQ(solver.n_factorizations(), 1u);
  EXPECT_EQ(solver.n_reuses(), 1u);

  // one value changed: factored again, and the solution is the new matrix's
  A.set(5, 5, 7.0);
  A.compress(VectorOperation::insert);
  solver.solve(A, x, b);
  EXPECT_LT(relative_residual(A, x, b), 1e-12);
  EXPECT_EQ(solver.n_factorizations(), 2u);
  EXPECT_EQ(solver.n_reuses(), 1u);

  // after invalidate() (a new pattern), analysed and factored again
  solver.invalidate();
  solver.solve(A, x, b);
  EXPECT_LT(relative_residual(A, x, b), 1e-12);
  EXPECT_EQ(solver.n_factorizations(), 3u);
}

TEST(DirectSolver, ASingularSystemIsAStepFailure)
{
  const IndexSet all = complete_index_set(n);
  TrilinosWrappers::SparseMatrix A;
  make_matrix(A);
  // row 10 all zeros (its entries stay in the pattern): singular
  A.set(10, 9, 0.0);
  A.set(10, 10, 0.0);
  A.set(10, 11, 0.0);
  A.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(all, MPI_COMM_SELF);
  b = 1.0;
  DirectSolver solver;
  try
    {
      solver.solve(A, x, b);
      FAIL() << "a singular system was solved";
    }
  catch (const StepFailure &f)
    {
      EXPECT_NE(f.reason.find("MUMPS"), std::string::npos) << f.reason;
    }
}

// The analysis alone (the iterative solver's fallback asks for it before it factors), on a 2D
// Laplacian of 120 × 120 nodes (14 400 rows, five-point stencil): MUMPS's estimate of the
// factorization's memory is at least its matrix's entries (8 bytes each; the factors fill in far
// beyond them: nested dissection's O(n log n)) and well below a gigabyte (measured ~10 MB; MUMPS
// counts whole megabytes, so a tiny matrix reads 0); the analysis is kept, so that the
// factorization after it and a second request analyse nothing again; the solve is exact.
TEST(DirectSolver, AnalysesOnceAndEstimatesTheFactorizationsMemory)
{
  constexpr unsigned int side = 120, rows = side * side;
  const IndexSet all = complete_index_set(rows);
  DynamicSparsityPattern dsp(rows);
  const auto at = [&](unsigned int i, unsigned int j) { return i * side + j; };
  for (unsigned int i = 0; i < side; ++i)
    for (unsigned int j = 0; j < side; ++j)
      {
        dsp.add(at(i, j), at(i, j));
        if (i > 0)
          dsp.add(at(i, j), at(i - 1, j));
        if (i + 1 < side)
          dsp.add(at(i, j), at(i + 1, j));
        if (j > 0)
          dsp.add(at(i, j), at(i, j - 1));
        if (j + 1 < side)
          dsp.add(at(i, j), at(i, j + 1));
      }
  TrilinosWrappers::SparseMatrix A;
  A.reinit(all, all, dsp, MPI_COMM_SELF);
  for (unsigned int r = 0; r < rows; ++r)
    for (auto it = dsp.begin(r); it != dsp.end(r); ++it)
      A.set(r, it->column(), it->column() == r ? 4.01 : -1.0);
  A.compress(VectorOperation::insert);

  DirectSolver solver;
  const double memory = solver.analyse(A);
  EXPECT_GE(memory, 8.0 * dsp.n_nonzero_elements());
  EXPECT_LT(memory, 1e9);
  EXPECT_EQ(solver.analyse(A), memory);
  EXPECT_EQ(solver.n_factorizations(), 0u);
  TrilinosWrappers::MPI::Vector x(all, MPI_COMM_SELF), b(all, MPI_COMM_SELF);
  for (unsigned int r = 0; r < rows; ++r)
    b[r] = 1.0 + 1e-4 * r;
  solver.solve(A, x, b);
  EXPECT_EQ(solver.n_factorizations(), 1u);
  EXPECT_LT(relative_residual(A, x, b), 1e-12);
  std::printf("MUMPS's memory estimate for %u rows: %.3g bytes\n", rows, memory);
}
