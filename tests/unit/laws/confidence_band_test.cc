#include "common/error.h"
#include "laws/confidence_band.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;
using namespace clearjoint::laws;

namespace
{
  LawFile fitted()
  {
    LawFile l;
    l.law = {3.7e8, 1.02};
    l.delta_max = l.delta_ref = 5e-5;
    l.source_kind = "fit";
    FitDiagnostics d;
    d.K_std_error = 2e7;
    d.n_std_error = 0.005;
    d.correlation_K_n = 0.995;
    const double t = 2.306;  // t(0.975, 8)
    d.n_ci95_low = 1.02 - t * 0.005;
    d.n_ci95_high = 1.02 + t * 0.005;
    l.diagnostics = d;
    return l;
  }
} // namespace

TEST(ConfidenceBand, RidgeAndAcrossVariants)
{
  const auto band = confidence_band_laws(fitted(), "law.json");
  ASSERT_EQ(band.size(), 4u);
  const double t = 2.306, dn = t * 0.005;
  EXPECT_NEAR(band[0].law.law.n, 1.02 - dn, 1e-12);  // n_low: the end of n's interval
  EXPECT_NEAR(band[1].law.law.n, 1.02 + dn, 1e-12);
  // Along the ridge K follows its conditional mean: slope ρ·σ_K/σ_n.
  EXPECT_NEAR(band[1].law.law.K - 3.7e8, 0.995 * 2e7 / 0.005 * dn, 1e-6 * 3.7e8);
  // Across the ridge: K ± t·σ_K·√(1 − ρ²) at n̂.
  EXPECT_NEAR(band[3].law.law.K - 3.7e8, t * 2e7 * std::sqrt(1 - 0.995 * 0.995), 1e-6 * 3.7e8);
  EXPECT_EQ(band[2].law.law.n, 1.02);
  for (const auto &b : band)
  {
    EXPECT_EQ(b.law.source_kind, "confidence_band");
    EXPECT_FALSE(b.law.diagnostics.has_value());
  }
}

TEST(ConfidenceBand, NeedsAFittedLaw)
{
  LawFile paper = fitted();
  paper.diagnostics.reset();
  EXPECT_THROW(confidence_band_laws(paper, "paper.json"), InputError);
}

TEST(ConfidenceBand, NoMeshVariantsWithoutAMeasuredDiscretisationError)
{
  for (const auto &b : confidence_band_laws(fitted(), "law.json"))
    EXPECT_EQ(b.source, "regression") << b.name;
}

TEST(ConfidenceBand, MeshVariantsScaleTheLawByTheMeasuredError)
{
  LawFile l = fitted();
  l.discretisation_error = DiscretisationError{0.02, "preset standard"};
  const auto band = confidence_band_laws(l, "law.json");
  ASSERT_EQ(band.size(), 6u);
  EXPECT_EQ(band[4].name, "mesh_low");
  EXPECT_EQ(band[5].name, "mesh_high");
  for (int i : {4, 5})
  {
    EXPECT_EQ(band[i].source, "discretisation");
    EXPECT_EQ(band[i].law.law.n, 1.02);  // the measured error is of F only: n is kept
    EXPECT_EQ(band[i].law.source_kind, "confidence_band");
  }
  // F(δ_ref) moves by exactly ∓2 % (1e-12: round-off of one multiplication).
  EXPECT_NEAR(band[4].law.F_ref() / l.F_ref(), 0.98, 1e-12);
  EXPECT_NEAR(band[5].law.F_ref() / l.F_ref(), 1.02, 1e-12);
}
