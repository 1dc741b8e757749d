// NIST StRD "DanWood" (y = b1·x^b2, the form of F = K·δ^n): certified values to ≥ 6 significant
// digits in b1, b2 and ≥ 3 in their standard deviations, from our default start (log–log fit)
// and from both NIST starting points (SPEC §3).
#include "common/csv.h"
#include "fit_stage/power_law_fitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

using namespace clearjoint;
using namespace clearjoint::fit;

namespace
{
  // Certified values, copied from the comment lines of tests/data/nist_danwood.txt.
  constexpr double b1 = 7.6886226176E-01, b1_sd = 1.8281973860E-02;
  constexpr double b2 = 3.8604055871E+00, b2_sd = 5.1726610913E-02;
  constexpr double rss = 4.3173084083E-03, residual_sd = 3.2853114039E-02;

  // "k significant digits" = relative error below 0.5·10^(1−k).
  double digits(int k) { return 0.5 * std::pow(10.0, 1 - k); }

  void check(const std::optional<std::pair<double, double>> &start)
  {
    const CsvTable t = read_csv(std::string(CLEARJOINT_TEST_DATA_DIR) + "/nist_danwood.txt");
    ASSERT_EQ(t.rows.size(), 5u) << "the first data row is read as the header";
    // The file has no header line (its column names are in a comment): rebuild all 6 rows.
    std::vector<double> x = {std::stod(t.columns[0])}, y = {std::stod(t.columns[1])};
    for (const auto &r : t.rows)
      x.push_back(r[0]), y.push_back(r[1]);
    FitOptions o;
    o.start = start;
    o.source = "nist_danwood.txt";
    const FitResult r = fit_power_law(x, y, o);
    const auto &d = r.diagnostics;
    EXPECT_NEAR(r.law.K, b1, digits(6) * b1);
    EXPECT_NEAR(r.law.n, b2, digits(6) * b2);
    EXPECT_NEAR(d.K_std_error, b1_sd, digits(3) * b1_sd);
    EXPECT_NEAR(d.n_std_error, b2_sd, digits(3) * b2_sd);
    EXPECT_NEAR(d.sum_squared_residuals, rss, digits(6) * rss);
    EXPECT_NEAR(d.residual_std, residual_sd, digits(6) * residual_sd);
    // What we actually reach, for the record: 9+ digits in every run we saw.
    EXPECT_NEAR(r.law.K, b1, digits(9) * b1);
    EXPECT_NEAR(r.law.n, b2, digits(9) * b2);
  }
} // namespace

TEST(NistDanWood, FromTheDefaultLogLogStart) { check(std::nullopt); }
TEST(NistDanWood, FromNistStart1) { check(std::make_pair(1.0, 5.0)); }
TEST(NistDanWood, FromNistStart2) { check(std::make_pair(0.7, 4.0)); }
