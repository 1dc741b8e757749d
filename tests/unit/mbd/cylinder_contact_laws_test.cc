// Each contact law against its closed form over a sweep of δ (SPEC §4, STYLE.md tests).
#include "mbd_stage/cylinder_contact_laws.h"

#include "common/error.h"
#include "common/units.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;
using namespace clearjoint::mbd;

namespace
{
  // The paper's joint (Table 4 as read in SPEC §4): steel on steel.
  const double R_B = 0.010, R_J = 0.0095, L = 0.018, E = 207e9, nu = 0.3;
  const double E_star = effective_modulus(E, nu, E, nu);
}

TEST(CylinderContactLaws, EffectiveModulus)
{
  EXPECT_NEAR(E_star, E / (2 * (1 - nu * nu)), 1e-3);  // Pa; same material: E/(2(1−ν²))
}

TEST(CylinderContactLaws, HertzAgainstClosedForm)
{
  const laws::PowerLaw h = hertz_cylinder_law(R_B, R_J, E_star);
  const double K = 4.0 / 3.0 * E_star * std::sqrt(R_B * R_J / (R_B - R_J));
  EXPECT_DOUBLE_EQ(h.n, 1.5);
  EXPECT_NEAR(h.K / K, 1.0, 1e-15);
  for (double d = 1e-9; d < 1e-4; d *= 1.7)
    EXPECT_NEAR(h.force(d) / (K * std::pow(d, 1.5)), 1.0, 1e-14);
}

TEST(CylinderContactLaws, PereiraAgainstHandEvaluationInMillimetres)
{
  const PereiraParameters p;  // a = 0.965, b = 0.0965
  const laws::PowerLaw law = pereira_law(R_B, R_J, L, E_star, p);
  const double dR = 0.5, Y = 0.0151 * dR + 1.151, n = Y * std::pow(dR, -0.005);
  EXPECT_NEAR(law.n, n, 1e-15);
  const double E_mm = E_star / 1e6;  // N/mm²
  for (double d_mm = 1e-5; d_mm < 0.1; d_mm *= 2.3)
  {
    const double F_mm = (p.a * dR + p.b) * 18.0 * E_mm * std::pow(d_mm, n) / dR;  // N
    // 1e-12: K is converted mm→m through 1000^n; only rounding differs.
    EXPECT_NEAR(law.force(d_mm * 1e-3) / F_mm, 1.0, 1e-12);
  }
  // Y(ΔR) is continuous where Pereira's two fits meet (ΔR = 0.34955 mm): to 1e-4, the
  // precision of the published coefficients.
  EXPECT_NEAR(pereira_Y(0.34955 - 1e-12), pereira_Y(0.34955), 1e-4);
  EXPECT_THROW(pereira_Y(20.0), InputError);
}

TEST(CylinderContactLaws, JohnsonInversionRoundTripsOverTheWholeBranch)
{
  const JohnsonLaw j(R_B - R_J, L, E_star);
  EXPECT_NEAR(j.peak_delta(), 4 * (R_B - R_J) / std::exp(2.0), 1e-18);
  EXPECT_NEAR(j.peak_force(), 4 * units::pi * L * E_star * (R_B - R_J) / std::exp(2.0), 1e-6);
  // The closed form δ(F) has its maximum at F_peak.
  EXPECT_NEAR(j.penetration(j.peak_force()), j.peak_delta(), 1e-15);
  double F_prev = 0.0;
  for (double d = 1e-12; d < j.peak_delta(); d *= 1.3)
  {
    const double F = j.force(d);
    ASSERT_TRUE(std::isfinite(F));
    EXPECT_GT(F, F_prev);  // monotone on the branch through the origin
    F_prev = F;
    // Round trip: δ(F(δ)) = δ to 1e-12 relative (Newton to machine precision).
    EXPECT_NEAR(j.penetration(F) / d, 1.0, 1e-12) << "delta = " << d;
  }
  bool beyond = false;
  EXPECT_DOUBLE_EQ(j.force(2 * j.peak_delta(), &beyond), j.peak_force());
  EXPECT_TRUE(beyond);
  EXPECT_EQ(j.force(-1e-6), 0.0);
}

TEST(CylinderContactLaws, JohnsonEnergyIsTheIntegralOfTheForce)
{
  const JohnsonLaw j(R_B - R_J, L, E_star);
  for (double d = 1e-8; d < 0.9 * j.peak_delta(); d *= 3.0)
  {
    const double h = 1e-4 * d;  // central difference, relative error ~1e-8
    const double dE = (j.energy(d + h) - j.energy(d - h)) / (2 * h);
    EXPECT_NEAR(dE / j.force(d), 1.0, 1e-6) << "delta = " << d;
  }
}
