#include "common/error.h"
#include "laws/damping.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint::laws;

// Each hysteresis factor against its closed form (SPEC §4) over a sweep of c_e.
TEST(Damping, HysteresisFactorsMatchTheirClosedForms)
{
  for (int i = 2; i <= 20; ++i)
  {
    const double ce = 0.05 * i;
    EXPECT_DOUBLE_EQ(hysteresis_factor(DampingModel::none, ce), 0.0);
    EXPECT_DOUBLE_EQ(hysteresis_factor(DampingModel::lankarani_nikravesh, ce),
                     0.75 * (1 - ce * ce));
    EXPECT_DOUBLE_EQ(hysteresis_factor(DampingModel::hunt_crossley, ce), 1.5 * (1 - ce));
    EXPECT_DOUBLE_EQ(hysteresis_factor(DampingModel::flores, ce), 1.6 * (1 - ce) / ce);
    EXPECT_DOUBLE_EQ(hysteresis_factor(DampingModel::gonthier, ce), (1 - ce * ce) / ce);
  }
  // Perfectly elastic impacts dissipate nothing in every model.
  for (const auto &name : damping_model_names())
    EXPECT_EQ(hysteresis_factor(parse_damping_model(name), 1.0), 0.0) << name;
}

TEST(Damping, PaperValueAtRestitution09)
{
  // The paper's F = 338240·δ^1.0114·[1 + 3(1 − c_e²)/4 · δ̇/δ̇⁻] with c_e = 0.9: χ = 0.1425.
  EXPECT_NEAR(hysteresis_factor(DampingModel::lankarani_nikravesh, 0.9), 0.1425, 1e-15);
}

TEST(Damping, DampedForceOverASweepOfRates)
{
  const double F_el = 1000.0, v0 = 0.3, chi = 0.75 * (1 - 0.81);
  for (double v = -v0; v <= v0; v += 0.01)
  {
    const double expected = std::max(0.0, F_el * (1 + chi * v / v0));
    EXPECT_NEAR(damped_force(F_el, chi, v, v0), expected, 1e-12 * F_el);
    EXPECT_NEAR(damping_force(F_el, chi, v, v0), F_el * chi * v / v0, 1e-12 * F_el);
  }
}

TEST(Damping, NeverPullsUnderStrongDamping)
{
  const double chi = hysteresis_factor(DampingModel::flores, 0.1);  // 14.4
  EXPECT_EQ(damped_force(100.0, chi, -0.5, 1.0), 0.0);
}

TEST(Damping, BadInputs)
{
  EXPECT_THROW(hysteresis_factor(DampingModel::flores, 0.0), clearjoint::InputError);
  EXPECT_THROW(hysteresis_factor(DampingModel::flores, 1.1), clearjoint::InputError);
  EXPECT_THROW(parse_damping_model("hertz"), clearjoint::InputError);
  EXPECT_THROW(damped_force(1.0, 0.5, 0.1, 0.0), clearjoint::NumericalError);
  EXPECT_EQ(to_string(parse_damping_model("gonthier")), "gonthier");
}
