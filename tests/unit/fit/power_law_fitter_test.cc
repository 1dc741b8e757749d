#include "common/error.h"
#include "fit_stage/power_law_fitter.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace clearjoint;
using namespace clearjoint::fit;

namespace
{
  // The paper's law in SI (SPEC §1) sampled at 10 increments up to 0.05 mm, with the origin.
  void paper_data(std::vector<double> &d, std::vector<double> &f, double noise = 0.0,
                  unsigned seed = 1)
  {
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double K = 3.65952708e8, n = 1.0114;
    d = {0.0};
    f = {0.0};
    for (int i = 1; i <= 10; ++i)
    {
      d.push_back(5e-6 * i);
      f.push_back(K * std::pow(d.back(), n) * (1 + noise * gauss(rng)));
    }
  }

  std::string message_of(const std::vector<double> &d, const std::vector<double> &f,
                         const FitOptions &o = {})
  {
    return test_support::input_error_of([&] { fit_power_law(d, f, o); });
  }
} // namespace

TEST(PowerLawFitter, ExactDataGiveExactParameters)
{
  std::vector<double> d, f;
  paper_data(d, f);
  for (const auto w : {Weighting::absolute, Weighting::relative})
  {
    FitOptions o;
    o.weighting = w;
    const FitResult r = fit_power_law(d, f, o);
    // Noise-free data: only round-off remains (Ceres tolerances 1e-14..1e-15).
    EXPECT_NEAR(r.law.K, 3.65952708e8, 1e-8 * 3.65952708e8);
    EXPECT_NEAR(r.law.n, 1.0114, 1e-10);
    EXPECT_NEAR(r.diagnostics.r_squared, 1.0, 1e-12);
    EXPECT_LT(r.diagnostics.max_relative_residual, 1e-9);
    EXPECT_EQ(r.n_origin_rows_skipped, 1u);
    EXPECT_EQ(r.diagnostics.n_points, 10u);
  }
}

// With 0.5 % Gaussian noise, the 95 % intervals must contain the true values in about 95 % of
// repetitions: over 40 seeds we require ≥ 32 hits (P(fewer | p=0.95) < 1e-3 by the binomial).
TEST(PowerLawFitter, NoisyDataConfidenceIntervalsCoverTheTruth)
{
  int hits_n = 0, hits_K = 0;
  for (unsigned seed = 1; seed <= 40; ++seed)
  {
    std::vector<double> d, f;
    paper_data(d, f, 0.005, seed);
    FitOptions o;
    o.weighting = Weighting::relative;  // the noise is relative
    const FitResult r = fit_power_law(d, f, o);
    hits_n += r.diagnostics.n_ci95_low <= 1.0114 && 1.0114 <= r.diagnostics.n_ci95_high;
    hits_K += r.diagnostics.K_ci95_low <= 3.65952708e8 && 3.65952708e8 <= r.diagnostics.K_ci95_high;
    EXPECT_GT(r.diagnostics.correlation_K_n, 0.9) << "K and n are strongly correlated (SPEC §3)";
  }
  EXPECT_GE(hits_n, 32);
  EXPECT_GE(hits_K, 32);
}

TEST(PowerLawFitter, RangeSelectsPoints)
{
  std::vector<double> d, f;
  paper_data(d, f);
  FitOptions o;
  o.range_min = 0.99e-5;  // margins: 6·5e-6 is 3.0000000000000004e-5 in doubles
  o.range_max = 3.01e-5;
  const FitResult r = fit_power_law(d, f, o);
  EXPECT_EQ(r.diagnostics.n_points, 5u);
  EXPECT_DOUBLE_EQ(r.diagnostics.fit_delta_min, 2 * 5e-6);
  EXPECT_DOUBLE_EQ(r.diagnostics.fit_delta_max, 6 * 5e-6);
}

TEST(PowerLawFitter, BadDataIsRejectedWithAClearMessage)
{
  std::vector<double> d, f;
  paper_data(d, f);
  EXPECT_NE(message_of({0, 1e-5, 2e-5}, {0, 1, 2}).find("at least 3 points"), std::string::npos);
  auto d2 = d, f2 = f;
  d2[3] = -1e-6;
  EXPECT_NE(message_of(d2, f).find("row 4, column 'delta'"), std::string::npos);
  f2[5] = -1.0;
  EXPECT_NE(message_of(d, f2).find("row 6, column 'force'"), std::string::npos);
  std::vector<double> constant(d.size(), 100.0);
  constant[0] = 0.0;
  d2 = d;
  d2[0] = 1e-7;  // no origin row: the constant-F rows are all data
  EXPECT_NE(message_of(d2, std::vector<double>(d.size(), 100.0)).find("constant"),
            std::string::npos);
  f2 = f;
  f2[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of(d, f2).find("finite"), std::string::npos);
}
