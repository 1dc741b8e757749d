// Extremes of the radial study on a coarse quarter model (seconds each), with the default
// end_faces journal unless stated: thin bearing, tiny and large pushes, μ = 0 and 0.5, a 1000x
// active-set constant. Each run must finish with finite
// forces that grow with δ, exact non-penetration and equilibrium, or stop with a message.
#include "fe_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  const std::string coarse =
    "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0}\n";

  void expect_sane(const RunResult &r, const FeScene &s)
  {
    ASSERT_TRUE(r.complete) << r.message;
    ASSERT_EQ(r.increments.size(), s.loading.n_increments);
    double previous = 0.0;
    for (const auto &i : r.increments)
      {
        EXPECT_TRUE(std::isfinite(i.force));
        EXPECT_GT(i.force, previous) << "F must grow with delta";
        previous = i.force;
        EXPECT_LT(i.max_penetration, 1e-9 * s.loading.delta_max);
        EXPECT_NEAR(i.force_support / i.force, 1.0, 1e-6);  // equilibrium, solver accuracy
        EXPECT_NEAR(i.force_load / i.force, 1.0, 1e-6);
        EXPECT_GT(i.n_active, 0u);
      }
    EXPECT_NEAR(r.increments.back().delta, s.loading.delta_max, 1e-15);
  }
} // namespace

TEST(FeExtremes, ThinBearingIsSofterThanDefault)
{
  const FeScene thin = scene(coarse + "contact: {mu: 0}\ngeometry: {t_B: 0.5e-3}\n"
                                      "loading: {n_increments: 4}\n");
  const FeScene normal = scene(coarse + "contact: {mu: 0}\nloading: {n_increments: 4}\n");
  const RunResult a = run(thin), b = run(normal);
  expect_sane(a, thin);
  expect_sane(b, normal);
  EXPECT_LT(a.increments.back().force, b.increments.back().force);
}

TEST(FeExtremes, TinyPushGivesSmallFiniteForce)
{
  const FeScene tiny = scene(coarse + "contact: {mu: 0}\nloading: {delta_max: 1.0e-7, n_increments: 4}\n");
  const FeScene normal = scene(coarse + "contact: {mu: 0}\nloading: {n_increments: 4}\n");
  const RunResult a = run(tiny), b = run(normal);
  expect_sane(a, tiny);
  expect_sane(b, normal);
  // The secant stiffness F/δ at 0.1 µm lies below the one at 50 µm (n ≥ 1: contact widens).
  EXPECT_LT(a.increments.back().force / 1e-7, b.increments.back().force / 0.05e-3);
}

TEST(FeExtremes, LargePushTenTimesTheStudy)
{
  // rigid journal: node-to-node pairing of two bodies assumes small sliding, which a push of
  // c_r (δ sin φ ≈ element size) would violate
  const FeScene s = scene(coarse + "contact: {mu: 0}\nloading: {journal: rigid, delta_max: 0.5e-3, n_increments: 5}\n");
  const RunResult r = run(s);
  expect_sane(r, s);
}

TEST(FeExtremes, FrictionCoefficientsZeroAndHalfRun)
{
  // Coulomb friction resists the slip between journal and bore that the push causes, so it
  // can only stiffen the joint: F(μ = 0.5) ≥ F(μ = 0), by a few percent at most (SPEC §2:
  // μ = 0.1 changes F by about 0.5 %).
  const FeScene a = scene(coarse + "contact: {mu: 0}\nloading: {n_increments: 3}\n");
  const FeScene b = scene(coarse + "contact: {mu: 0.5}\nloading: {n_increments: 3}\n");
  const RunResult ra = run(a), rb = run(b);
  expect_sane(ra, a);
  expect_sane(rb, b);
  ASSERT_EQ(ra.increments.size(), rb.increments.size());
  for (std::size_t i = 0; i < ra.increments.size(); ++i)
    {
      EXPECT_GT(rb.increments[i].force, ra.increments[i].force);
      EXPECT_LT(rb.increments[i].force, 1.1 * ra.increments[i].force);
    }
}

TEST(FeExtremes, ActiveSetConstantThousandTimesDefault)
{
  const FeScene a = scene(coarse + "contact: {mu: 0}\nloading: {n_increments: 3}\n");
  const FeScene b =
    scene(coarse + "contact: {mu: 0, active_set_scale: 1000}\nloading: {n_increments: 3}\n");
  const RunResult ra = run(a), rb = run(b);
  expect_sane(ra, a);
  expect_sane(rb, b);
  EXPECT_NEAR(rb.increments.back().force / ra.increments.back().force, 1.0, 1e-8);
}

TEST(FeExtremes, ActiveSetThatCannotSettleStopsLoudly)
{
  // One active-set iteration per increment cannot settle (the first solve only finds the
  // penetrating nodes); every cut fails too, so the run must stop incomplete with a message.
  const FeScene s =
    scene(coarse + "contact: {mu: 0, max_iterations: 1}\nloading: {n_increments: 2, max_cuts: 1}\n");
  const RunResult r = run(s);
  EXPECT_FALSE(r.complete);
  EXPECT_NE(r.message.find("active set"), std::string::npos) << r.message;
}
