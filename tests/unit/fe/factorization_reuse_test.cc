// When the direct solver's kept factors still precondition GMRES for a changed matrix
// (fe_stage/solve/factorization_reuse.h): a budget of iterations from MUMPS's flop counts, and
// the forecast that gives up on a try early.
#include "fe_stage/solve/factorization_reuse.h"

#include <gtest/gtest.h>

using clearjoint::fe::FactorizationReuse;

namespace
{
  // The rolling study's 14 k-DoF ring as MUMPS counted it: 4.70e9 flops a factorization,
  // 9.68e6 entries in the factors, 2.92e6 non-zeros in the matrix.
  constexpr double flops = 4.70e9, entries = 9.68e6, nonzeros = 2.92e6;
}  // namespace

TEST(FactorizationReuse, NothingFactoredIsNothingToReuse)
{
  FactorizationReuse r;
  EXPECT_FALSE(r.worth_reusing());
}

TEST(FactorizationReuse, TheBudgetIsTheFactorizationsFlopsInIterations)
{
  FactorizationReuse r;
  r.factored(flops, entries, nonzeros);
  // an iteration: each factor entry and matrix non-zero once, a multiply and an add
  const double expected = flops / (FactorizationReuse::dense_speedup * 2.0 * (entries + nonzeros));
  EXPECT_DOUBLE_EQ(r.budget(), expected);
  EXPECT_GT(r.budget(), 5.0);  // (12.4 with the measured speed-up: several solves' worth)
  EXPECT_TRUE(r.worth_reusing());
}

TEST(FactorizationReuse, SpentIterationsExhaustTheBudgetAndANewFactorizationRenewsIt)
{
  FactorizationReuse r;
  r.factored(flops, entries, nonzeros);
  // a try fits while the forecast's first iterations do
  const double room = FactorizationReuse::min_steps_for_forecast;
  const auto fits = static_cast<unsigned int>(r.budget() - room);
  r.record(fits);
  EXPECT_TRUE(r.worth_reusing());
  r.record(1);
  EXPECT_FALSE(r.worth_reusing());
  r.factored(flops, entries, nonzeros);
  EXPECT_DOUBLE_EQ(r.spent(), 0.0);
  EXPECT_TRUE(r.worth_reusing());
}

TEST(FactorizationReuse, ATinySystemIsAlwaysFactoredAfresh)
{
  // a factorization as cheap as a few applies: no room for a try the forecast could judge
  FactorizationReuse r;
  r.factored(1.0e7, 1.0e5, 5.0e4);  // 2.2 iterations
  EXPECT_LT(r.budget(), FactorizationReuse::min_steps_for_forecast);
  EXPECT_GT(r.budget(), 1.0);
  EXPECT_FALSE(r.worth_reusing());
}

TEST(FactorizationReuse, TheForecastGivesUpOnASlowTryAndLetsAFastOneRun)
{
  const unsigned int max = 30;
  const double tolerance = 1e-10;
  // 4 iterations, 1e-2 per iteration: 10 in all, within 30
  EXPECT_FALSE(FactorizationReuse::forecast_exceeds(4, 1.0, 1e-8, tolerance, max));
  // 4 iterations, a factor 10 in all: ~40 needed
  EXPECT_TRUE(FactorizationReuse::forecast_exceeds(4, 1.0, 1e-1, tolerance, max));
  // no reduction at all gives no rate: not judged here (the iteration limit ends such a try)
  EXPECT_FALSE(FactorizationReuse::forecast_exceeds(4, 1.0, 1.0, tolerance, max));
  // too early to judge, however slow
  EXPECT_FALSE(FactorizationReuse::forecast_exceeds(3, 1.0, 0.99, tolerance, max));
  // already within tolerance: nothing to forecast
  EXPECT_FALSE(FactorizationReuse::forecast_exceeds(8, 1.0, 1e-11, tolerance, max));
}
