#include "common/units.h"

#include <gtest/gtest.h>

using namespace clearjoint;

// SPEC §1: F = 338240·δ^1.0114 (mm, N) is K = 3.6595e8 N/m^1.0114 in SI; 16 344 N at 0.05 mm.
TEST(Units, PaperLawConversion)
{
  const double K = units::power_law_K_mm_to_SI(338240.0, 1.0114);
  EXPECT_NEAR(K, 3.6595e8, 0.0001e8);  // SPEC quotes 5 significant digits
  EXPECT_NEAR(K * std::pow(0.05 * units::mm, 1.0114), 16344.0, 0.5);  // SPEC rounds to 1 N
  EXPECT_NEAR(338240.0 * std::pow(0.05, 1.0114), K * std::pow(0.05e-3, 1.0114), 1e-9 * 16344);
  EXPECT_DOUBLE_EQ(units::power_law_K_SI_to_mm(K, 1.0114), 338240.0);
}

TEST(Units, Angles)
{
  EXPECT_DOUBLE_EQ(units::to_deg(units::pi), 180.0);
  EXPECT_DOUBLE_EQ(90 * units::deg, units::pi / 2);
}
