// The adaptive run's error estimate (fe_stage/solve/adaptive_estimate.h): exact on sequences of
// the assumed form with the rate p/d, larger for a faster rate, smaller by a known factor for a
// slower one, the last cycle's change (labelled: not extrapolated, not a bound) where the
// changes turn or grow, a target met only by an extrapolation — and on every adaptive sequence fe_stage measured and docs/benchmarks.md
// records (tests/data/fe/adaptive_sequences.txt), within a stated margin of the error that
// independent references give, and no more than a stated factor above it; the last cycle's
// change there on both sides of the error (the figures the pipeline and report quote).
#include "fe_stage/solve/adaptive_estimate.h"
#include "laws/own_error_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

using namespace clearjoint::fe;

namespace
{
  struct Cycle  // the fields estimate_adaptive_error reads from fe_model.h's AdaptiveCycle
  {
    unsigned long n_dofs = 0;
    double force = 0.0;
  };
  std::vector<Cycle> sequence(const std::vector<double> &dofs, const std::vector<double> &forces)
  {
    std::vector<Cycle> c(dofs.size());
    for (std::size_t k = 0; k < dofs.size(); ++k)
      {
        c[k].n_dofs = static_cast<unsigned long>(dofs[k]);
        c[k].force = forces[k];
      }
    return c;
  }
  const unsigned int Q2 = 2;  // fe_stage's default degree: the bound on q is 2/3
} // namespace

TEST(AdaptiveEstimate, RecoversTheLimitAndOrderOfAPowerLawSequence)
{
  // F = F_inf + C N^-q on unevenly growing meshes, as Kelly's refinement makes them, with the
  // rate 2/3 the estimate assumes (Q2 in 3D): the fit and the estimate are exact
  const double F_inf = 19540.0, C = 1.0e5, q = 2.0 / 3.0;
  const std::vector<double> N = {3588, 7869, 17874, 41115};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  // golden sections stop at 1e-12 in q; the fitted rate is reported, the tail (~84 N here)
  // uses 2/3 itself: F_inf to 1e-6 N leaves room for the round-off of the logs and powers
  EXPECT_NEAR(e.fitted_order, q, 1e-9);
  EXPECT_DOUBLE_EQ(e.order, q);
  EXPECT_EQ(e.n_meshes_fitted, 4u);
  EXPECT_NEAR(e.extrapolated_force, F_inf, 1e-6);
  EXPECT_NEAR(e.error, (F.back() - F_inf) / F_inf, 1e-10);
  EXPECT_TRUE(adaptive_target_met(e, 1.01 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.99 * e.error));
  EXPECT_FALSE(adaptive_target_met(e, 0.0));  // no target: never "met"
  EXPECT_NE(e.method.find("least squares over the last 4 meshes"), std::string::npos) << e.method;
}

TEST(AdaptiveEstimate, ARateAboveTheBoundIsCreditedOnlyUpToIt)
{
  // q = 1 > 2/3 (Q2 in 3D): the fit finds 1, the estimate uses 2/3 and so over-estimates, by
  // exactly ((N_k/N_{k-2}) - 1) / ((N_k/N_{k-2})^(2/3) - 1) for this exact power law
  const double F_inf = 22000.0, C = 2.0e6, q = 1.0;
  const std::vector<double> N = {1782, 3873, 9024, 21057};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  EXPECT_NEAR(e.fitted_order, q, 1e-9);  // as above
  EXPECT_DOUBLE_EQ(e.order, 2.0 / 3.0);
  const double ratio = N[3] / N[1];
  const double tail = (F[1] - F[3]) / (std::pow(ratio, 2.0 / 3.0) - 1.0);
  EXPECT_NEAR(e.error, tail / (F[3] - tail), 1e-12);  // the same formula: round-off only
  EXPECT_GT(e.error, (F[3] - F_inf) / F_inf);
  EXPECT_NE(e.method.find("q = 0.667 (p/d; least squares over the last 4 meshes: 1, not used)"),
            std::string::npos)
    << e.method;
  // Q1 elements: the bound is 1/3
  EXPECT_DOUBLE_EQ(estimate_adaptive_error(sequence(N, F), 1).order, 1.0 / 3.0);
}

TEST(AdaptiveEstimate, TheFitUsesTheLastFiveMeshes)
{
  // a wild first mesh (a change 100x the power law's) is left out once there are six meshes
  const double F_inf = 100.0, C = 50.0, q = 0.4;
  const std::vector<double> N = {1e3, 2e3, 4e3, 8e3, 16e3, 32e3};
  std::vector<double> F;
  for (const double n : N)
    F.push_back(F_inf + C * std::pow(n, -q));
  F[0] += 100.0 * (F[0] - F[1]);
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  EXPECT_EQ(e.n_meshes_fitted, 5u);
  EXPECT_NEAR(e.fitted_order, q, 1e-9);  // as in the first test: the wild mesh is not in it
  EXPECT_DOUBLE_EQ(e.order, 2.0 / 3.0);
}

TEST(AdaptiveEstimate, ASlowerFittedRateIsReportedNotExtrapolated)
{
  // Changes that barely shrink, as on the misalignment study's first deformable meshes (there
  // 447 N then 353 N at θ_max, 408 N then 349 N at 2.5°: fitted rates 0.28 and 0.09, and
  // the old estimate, which extrapolated at the fitted rate, said 63 % and 336 % for errors of
  // 3.5-4.5 % and 0.8-1.1 %). The tail is the one at p/d, whatever the fit says.
  const std::vector<double> N = {4680, 12105, 29154};
  const std::vector<double> F = {100.0, 90.0, 81.5};
  const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
  ASSERT_TRUE(e.extrapolated) << e.method;
  EXPECT_LT(e.fitted_order, 0.1);  // the three-mesh Richardson rate: 0.092
  EXPECT_DOUBLE_EQ(e.order, 2.0 / 3.0);
  const double tail = (F[0] - F[2]) / (std::pow(N[2] / N[0], 2.0 / 3.0) - 1.0);
  EXPECT_NEAR(e.error, tail / (F[2] - tail), 1e-12);  // 10.5 %, the last change 10.4 %
  EXPECT_NE(e.method.find(
              "q = 0.667 (p/d; least squares over the last 3 meshes: 0.0923, not used)"),
            std::string::npos)
    << e.method;

  // the price: a sequence that does converge steadily at q = 0.5 < 2/3 gets the tail at 2/3,
  // (R^0.5 - 1)/(R^(2/3) - 1) of its own (R = N_k/N_{k-2}) — an under-estimate by that factor
  const double F_inf = 19540.0, C = 1.0e5, q = 0.5;
  const std::vector<double> M = {3588, 7869, 17874, 41115};
  std::vector<double> G;
  for (const double n : M)
    G.push_back(F_inf + C * std::pow(n, -q));
  const AdaptiveEstimate slow = estimate_adaptive_error(sequence(M, G), Q2);
  ASSERT_TRUE(slow.extrapolated) << slow.method;
  EXPECT_NEAR(slow.fitted_order, q, 1e-9);
  const double R = M[3] / M[1];
  const double factor = (std::pow(R, q) - 1.0) / (std::pow(R, 2.0 / 3.0) - 1.0);  // 0.64
  const double true_tail = G[3] - F_inf;
  EXPECT_NEAR(slow.extrapolated_force, G[3] - factor * true_tail, 1e-6);
}

TEST(AdaptiveEstimate, FewMeshesOrNoLimitGiveTheLabelledLastChange)
{
  EXPECT_LT(estimate_adaptive_error(sequence({1000}, {100.0}), Q2).error, 0.0);
  // two meshes: the last change, labelled as such (not extrapolated, not a bound), which never
  // meets a target
  const AdaptiveEstimate two = estimate_adaptive_error(sequence({1000, 2000}, {110.0, 100.0}), Q2);
  EXPECT_FALSE(two.extrapolated);
  EXPECT_DOUBLE_EQ(two.error, 0.1);
  EXPECT_NE(two.method.find("change in the last cycle"), std::string::npos);
  EXPECT_NE(two.method.find("not a bound"), std::string::npos);
  EXPECT_EQ(two.method.find("lower bound"), std::string::npos);
  EXPECT_FALSE(adaptive_target_met(two, 0.5));
  // the differences grow (no limit of the form F_inf + C N^-q): the last change again
  const AdaptiveEstimate growing =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 108.0, 100.0}), Q2);
  EXPECT_FALSE(growing.extrapolated);
  EXPECT_DOUBLE_EQ(growing.error, 0.08);
  EXPECT_EQ(growing.method, two.method);
  // not monotone (the last step reverses): the last change
  const AdaptiveEstimate zigzag =
    estimate_adaptive_error(sequence({1000, 2000, 4000}, {110.0, 100.0, 101.0}), Q2);
  EXPECT_FALSE(zigzag.extrapolated);
  // a reversal among the fitted changes, not only in the last one: the last change
  EXPECT_FALSE(
    estimate_adaptive_error(sequence({1000, 2000, 4000, 8000}, {110.0, 112.0, 105.0, 103.0}), Q2)
      .extrapolated);
  // a mesh that did not grow (a refinement that added nothing): no extrapolation
  EXPECT_FALSE(
    estimate_adaptive_error(sequence({1000, 2000, 2000}, {110.0, 100.0, 99.0}), Q2).extrapolated);
}

namespace
{
  // A sequence fe_stage measured (F(δ_max) per adaptive mesh) and the interval in which
  // independent references put its limit: one block of tests/data/fe/adaptive_sequences.txt,
  // whose header describes the fields and each block names the docs section it comes from.
  struct Measured
  {
    std::string name, journal;
    std::vector<double> n_dofs;
    std::vector<double> forces;    // [N]
    double F_ref_low = 0.0, F_ref_high = 0.0;  // [N]
    std::size_t n_checked = 0;                 // prefixes of 2 .. n_checked meshes are checked
  };

  std::vector<Measured> read_measured_sequences()
  {
    const std::string path = std::string(CLEARJOINT_TEST_DATA_DIR) + "/fe/adaptive_sequences.txt";
    std::ifstream in(path);
    EXPECT_TRUE(in) << path;
    std::vector<Measured> out;
    Measured s;
    std::string line;
    while (std::getline(in, line))
      {
        std::istringstream words(line);
        std::string key;
        if (!(words >> key) || key[0] == '#')
          continue;
        std::string rest;
        std::getline(words >> std::ws, rest);
        std::istringstream values(rest);
        if (key == "sequence")
          {
            s = Measured();
            s.name = rest;
          }
        else if (key == "journal")
          s.journal = rest;
        else if (key == "reference")
          values >> s.F_ref_low >> s.F_ref_high;
        else if (key == "checked")
          values >> s.n_checked;
        else if (key == "mesh")
          {
            double n = 0.0, f = 0.0;
            values >> n >> f;
            s.n_dofs.push_back(n);
            s.forces.push_back(f);
          }
        else if (key == "end")
          out.push_back(s);
        else if (key != "source")
          ADD_FAILURE() << path << ": unknown key " << key;
      }
    return out;
  }

  /// The larger of the relative errors of F against the two ends of the reference interval.
  double error_against(const double F, const Measured &s)
  {
    return std::max(std::abs(F - s.F_ref_low) / s.F_ref_low,
                    std::abs(F - s.F_ref_high) / s.F_ref_high);
  }
}  // namespace

TEST(AdaptiveEstimate, TheRecordedSequencesAreReadWhole)
{
  const std::vector<Measured> all = read_measured_sequences();
  ASSERT_EQ(all.size(), 15u);  // the blocks of the data file (t_B = 6 and 8 mm since 2026-11-30)
  std::size_t n_rigid = 0, n_deformable = 0;
  for (const Measured &s : all)
    {
      EXPECT_EQ(s.n_dofs.size(), s.forces.size()) << s.name;
      EXPECT_GE(s.forces.size(), 4u) << s.name;
      EXPECT_LE(s.n_checked, s.forces.size()) << s.name;
      EXPECT_LE(s.F_ref_low, s.F_ref_high) << s.name;
      n_rigid += s.journal == "rigid" && s.n_checked > 0;
      n_deformable += s.journal == "deformable" && s.n_checked > 0;
    }
  EXPECT_EQ(n_rigid, 2u);  // the radial rigid journal with μ = 0.1 and the flanged bearing
  EXPECT_EQ(n_deformable, 12u);
}

// Issue 32 item 3: on every prefix of 3 or more meshes of every recorded sequence of both
// journals that the references do not rest on (tests/data/fe/adaptive_sequences.txt;
// docs/benchmarks.md "The adaptive error estimate before the sequence turns" has the table
// this prints), an extrapolated estimate is
//  - honest within a margin: at least 0.6 times the error against the far end of the
//    reference interval. The margin is what the sequences show no estimate from their first
//    meshes could know: t_B = 2 mm's fifth mesh, 0.31 % for 0.43-0.51 % (the sixth mesh's
//    change, 0.19 %, shrank less than the changes before it foretold), and t_B = 10 mm,
//    0.76-0.80 times (a steady rate of 0.57-0.59 there, below p/d);
//  - not far above it where the sequence's own rate is at least p/d: at most 2 times from four
//    meshes on (the largest measured 1.83), 4 times with three (3.65: the rate then rests on
//    two changes, the first from the base mesh);
//  - where the fitted rate is slower (meshes before the asymptotic range, whose next changes
//    nothing in the sequence foretells: the misalignment study's deformable journal turned
//    within two cycles after each), at most 1.5 times the last cycle's change: the tail of a
//    power law at p/d after a cycle that multiplies the DoFs by 2.2-2.6 (the recorded ones) is
//    1.1-1.5 times that change (1/(2.2^(2/3) - 1) = 1.45); measured 1.01-1.43. The estimate
//    before this check (the tail at the fitted rate) said 2.3-30 times the last change there:
//    13.6 % at θ_max on the standard preset's mesh for 1.4-2.3 %, 336 % at 2.5° on the fast
//    one's for 0.8-1.1 %.
// Lower bounds (the changes turn or grow) are printed, not checked: they claim only a floor.
TEST(AdaptiveEstimate, BracketsTheReferenceOnTheMeasuredSequences)
{
  std::size_t n_extrapolated = 0;
  std::vector<double> last_change_ratios;  // the last change / the far-end error, where used
  for (const Measured &s : read_measured_sequences())
    for (std::size_t m = 2; m <= s.n_checked; ++m)
      {
        const std::vector<double> N(s.n_dofs.begin(), s.n_dofs.begin() + m);
        const std::vector<double> F(s.forces.begin(), s.forces.begin() + m);
        const AdaptiveEstimate e = estimate_adaptive_error(sequence(N, F), Q2);
        const double near = std::min(std::abs(F.back() - s.F_ref_low) / s.F_ref_low,
                                     std::abs(F.back() - s.F_ref_high) / s.F_ref_high);
        const bool inside = s.F_ref_low <= F.back() && F.back() <= s.F_ref_high;
        const double far = error_against(F.back(), s);
        const double last_change = std::abs(F[m - 1] - F[m - 2]) / std::abs(F[m - 1]);
        std::printf("| %s | %zu | %.0f | %.3f-%.3f %% | %.3f %% | %.2f | %s |\n", s.name.c_str(), m,
                    N.back(), 100.0 * (inside ? 0.0 : near), 100.0 * far, 100.0 * e.error,
                    e.error / far, e.method.c_str());
        if (!e.extrapolated)
          {
            last_change_ratios.push_back(e.error / far);
            continue;
          }
        ++n_extrapolated;
        const std::string where = s.name + ", " + std::to_string(m) + " meshes";
        EXPECT_GE(e.error, 0.6 * far) << where;
        if (e.fitted_order >= e.order)
          EXPECT_LE(e.error, (m == 3 ? 4.0 : 2.0) * far) << where;
        else
          EXPECT_LE(e.error, 1.5 * last_change) << where;
      }
  // (25 since 2026-11-30: the sequences at t_B = 6 and 8 mm, estimated at 0.79-1.07 times
  // their far-end errors, added 6)
  EXPECT_EQ(n_extrapolated, 25u);
  // The rest are the last cycle's change, none checked away: not a bound either way — below the
  // error on 9, above it on 16, 0.05-29 times it, median 1.12 (the figures laws::last_change_record
  // quotes, checked below; bench/adaptive_estimate_table.py prints the same).
  ASSERT_EQ(last_change_ratios.size(), 25u);
  std::sort(last_change_ratios.begin(), last_change_ratios.end());
  EXPECT_EQ(std::count_if(last_change_ratios.begin(), last_change_ratios.end(),
                          [](const double r) { return r > 1.0; }),
            16);
  EXPECT_NEAR(last_change_ratios.front(), 0.05, 0.005);
  EXPECT_NEAR(last_change_ratios.back(), 29.0, 0.5);
  EXPECT_NEAR(last_change_ratios[12], 1.12, 0.005);  // the median of 25
  // The one place the words are typed (run_pipeline's log and summary, which the report quotes)
  // says what these sequences say.
  char record[96];
  std::snprintf(record, sizeof(record), "%.1g-%.2gx the error, median %.3g",
                last_change_ratios.front(), last_change_ratios.back(), last_change_ratios[12]);
  EXPECT_NE(std::string(clearjoint::laws::last_change_record).find(record), std::string::npos)
    << "laws::last_change_record is \"" << clearjoint::laws::last_change_record
    << "\"; the recorded sequences say " << record;
}
