#include "common/error.h"
#include "laws/law_range_error.h"
#include "laws/power_law.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::laws;

namespace
{
  const PowerLaw paper{3.65952708e8, 1.0114};  // SPEC §1, N/m^1.0114
}

TEST(PowerLaw, ZeroWithoutPenetration)
{
  EXPECT_EQ(paper.force(0.0), 0.0);
  EXPECT_EQ(paper.force(-1e-6), 0.0);
  EXPECT_EQ(paper.stiffness(-1e-6), 0.0);
  EXPECT_EQ(paper.energy(-1e-6), 0.0);
}

// The analytic slope against central differences over four decades of δ.
TEST(PowerLaw, StiffnessMatchesFiniteDifferences)
{
  for (const double n : {0.8, 1.0114, 1.5, 2.2})
  {
    const PowerLaw law{1e9, n};
    for (double d = 1e-8; d < 1e-4; d *= 3.7)
    {
      const double h = 1e-6 * d;
      const double fd = (law.force(d + h) - law.force(d - h)) / (2 * h);
      // Central differences with h = 1e-6·δ: truncation ~h², rounding ~1e-16/1e-6 = 1e-10.
      EXPECT_NEAR(law.stiffness(d), fd, 1e-8 * std::abs(fd)) << "n=" << n << " d=" << d;
    }
  }
}

// Energy is the integral of force: compare with Simpson's rule.
TEST(PowerLaw, EnergyIsTheIntegralOfForce)
{
  const PowerLaw law{3.6e8, 1.3};
  const double D = 5e-5;
  const int N = 2000;
  double s = law.force(0) + law.force(D);
  for (int i = 1; i < N; ++i)
    s += (i % 2 ? 4 : 2) * law.force(D * i / N);
  const double simpson = s * D / (3 * N);
  // Simpson on δ^1.3 (a non-smooth derivative at 0) converges ~N^-2.3: 1e-7 is ample at N=2000.
  EXPECT_NEAR(law.energy(D), simpson, 1e-7 * simpson);
}

TEST(BoundedPowerLaw, PoliciesOutsideTheRange)
{
  const double dmax = 5e-5;
  const BoundedPowerLaw err(paper, 0.0, dmax, RangePolicy::error);
  EXPECT_NO_THROW(err.force(dmax));
  EXPECT_THROW(err.force(1.01 * dmax), LawRangeError);
  EXPECT_EQ(err.counter().n_above, 1u);

  const BoundedPowerLaw clamp(paper, 0.0, dmax, RangePolicy::clamp);
  EXPECT_DOUBLE_EQ(clamp.force(2 * dmax), paper.force(dmax));
  EXPECT_EQ(clamp.stiffness(2 * dmax), 0.0);
  EXPECT_DOUBLE_EQ(clamp.energy(2 * dmax), paper.energy(dmax) + paper.force(dmax) * dmax);
  EXPECT_EQ(clamp.counter().n_above, 3u);
  EXPECT_DOUBLE_EQ(clamp.counter().max_delta_seen, 2 * dmax);

  const BoundedPowerLaw extend(paper, 0.0, dmax, RangePolicy::extend);
  EXPECT_DOUBLE_EQ(extend.force(2 * dmax), paper.force(2 * dmax));
  EXPECT_EQ(extend.counter().n_above, 1u);
  extend.reset_counter();
  EXPECT_EQ(extend.counter().n_above, 0u);
}

TEST(BoundedPowerLaw, ClampBelowTheRangeIsAContinuousChord)
{
  const double dmin = 1e-6, dmax = 5e-5;
  const BoundedPowerLaw clamp(paper, dmin, dmax, RangePolicy::clamp);
  EXPECT_DOUBLE_EQ(clamp.force(0.5 * dmin), 0.5 * paper.force(dmin));
  EXPECT_NEAR(clamp.force(dmin * (1 - 1e-12)), paper.force(dmin), 1e-9 * paper.force(dmin));
  EXPECT_EQ(clamp.counter().n_below, 2u);
}

TEST(BoundedPowerLaw, RejectsNonPhysicalLaws)
{
  EXPECT_THROW(BoundedPowerLaw(PowerLaw{0.0, 1.0}, 0, 1e-4, RangePolicy::error),
               clearjoint::InputError);
  EXPECT_THROW(BoundedPowerLaw(PowerLaw{1.0, -1.0}, 0, 1e-4, RangePolicy::error),
               clearjoint::InputError);
  EXPECT_THROW(BoundedPowerLaw(PowerLaw{1.0, 1.0}, 1e-4, 1e-4, RangePolicy::error),
               clearjoint::InputError);
  EXPECT_THROW(parse_range_policy("wrap"), clearjoint::InputError);
}
