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
