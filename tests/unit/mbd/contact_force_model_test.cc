// Contact-force models with each damping term against F = F_el(δ)·[1 + χ(c_e)·δ̇/δ̇⁻] over a
// sweep of δ and δ̇ (SPEC §4), the δ̇⁻ floor, and the law-range policy counters.
#include "mbd_stage/contact_force_model.h"

#include "laws/law_range_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace clearjoint;
using namespace clearjoint::mbd;

TEST(ContactForceModel, EveryDampingTermAgainstItsClosedForm)
{
  const laws::PowerLaw law{3.6595e8, 1.0114};  // the paper's law in SI
  const double c_e = 0.9, v_imp = 0.4;         // 1, m/s
  struct Case
  {
    laws::DampingModel m;
    double chi;
  };
  const Case cases[] = {
    {laws::DampingModel::none, 0.0},
    {laws::DampingModel::lankarani_nikravesh, 3 * (1 - c_e * c_e) / 4},
    {laws::DampingModel::hunt_crossley, 3 * (1 - c_e) / 2},
    {laws::DampingModel::flores, 8 * (1 - c_e) / (5 * c_e)},
    {laws::DampingModel::gonthier, (1 - c_e * c_e) / c_e},
  };
  for (const Case &c : cases)
  {
    ContactForceModel m = ContactForceModel::power_law("fe", law);
    m.set_damping(c.m, c_e, 1e-3);
    EXPECT_NEAR(m.chi(), c.chi, 1e-15);
    for (double d = 1e-8; d < 1e-4; d *= 2.1)
      for (double dd = -v_imp; dd <= v_imp; dd += 0.05)
      {
        const ContactForce f = m.force(d, dd, v_imp);
        const double ref = std::max(0.0, law.K * std::pow(d, law.n) * (1 + c.chi * dd / v_imp));
        EXPECT_NEAR(f.total, ref, 1e-12 * ref + 1e-12);
        EXPECT_NEAR(f.elastic, law.K * std::pow(d, law.n), 1e-12 * f.elastic);
        EXPECT_GE(f.total, 0.0);  // never pulls
      }
  }
}

TEST(ContactForceModel, ImpactVelocityFloorBoundsTheDampingRatio)
{
  ContactForceModel m = ContactForceModel::power_law("hertz", {1e10, 1.5});
  m.set_damping(laws::DampingModel::lankarani_nikravesh, 0.5, 1e-3);
  // A grazing impact (δ̇⁻ = 1e-9 m/s) uses the floor 1e-3 m/s.
  EXPECT_DOUBLE_EQ(m.impact_velocity(1e-9), 1e-3);
  EXPECT_DOUBLE_EQ(m.impact_velocity(0.2), 0.2);
  const double d = 1e-6, F_el = 1e10 * std::pow(d, 1.5);
  EXPECT_NEAR(m.force(d, 1e-3, 1e-9).total, F_el * (1 + m.chi()), 1e-9 * F_el);
}

TEST(ContactForceModel, LawFileRangePolicyIsAppliedAndAcceptedStatesAreCounted)
{
  laws::LawFile lf;
  lf.law = {3.6595e8, 1.0114};
  lf.delta_min = 0.0;
  lf.delta_max = 5e-5;
  lf.delta_ref = 5e-5;
  const ContactForceModel extend = ContactForceModel::law_file("fe", lf, laws::RangePolicy::extend);
  EXPECT_NEAR(extend.elastic_force(1e-4), lf.law.force(1e-4), 1e-6);
  // A force evaluation is a trial stage: it never counts; an accepted state does.
  EXPECT_EQ(extend.n_out_of_range(), 0u);
  extend.observe_accepted(4e-5);
  EXPECT_EQ(extend.n_out_of_range(), 0u);
  extend.observe_accepted(1e-4);
  EXPECT_EQ(extend.n_out_of_range(), 1u);
  EXPECT_DOUBLE_EQ(extend.max_delta_accepted(), 1e-4);
  const ContactForceModel clamp = ContactForceModel::law_file("fe", lf, laws::RangePolicy::clamp);
  EXPECT_NEAR(clamp.elastic_force(1e-4), lf.law.force(5e-5), 1e-6);
  clamp.observe_accepted(1e-4);
  EXPECT_EQ(clamp.n_out_of_range(), 1u);
  // "error": a trial stage beyond the range is evaluated on the extrapolated law (the step
  // may still be rejected); an accepted state beyond it stops the run.
  const ContactForceModel error = ContactForceModel::law_file("fe", lf, laws::RangePolicy::error);
  EXPECT_NEAR(error.elastic_force(1e-4), lf.law.force(1e-4), 1e-6);
  EXPECT_NO_THROW(error.observe_accepted(4e-5));
  EXPECT_THROW(error.observe_accepted(1e-4), laws::LawRangeError);
}

TEST(ContactForceModel, JohnsonBeyondPeakIsHeldAndAcceptedStatesAreCounted)
{
  const JohnsonLaw j(5e-4, 0.018, 1.137e11);
  const ContactForceModel clamp = ContactForceModel::johnson("j", j, laws::RangePolicy::clamp);
  EXPECT_DOUBLE_EQ(clamp.elastic_force(2 * j.peak_delta()), j.peak_force());
  EXPECT_EQ(clamp.n_out_of_range(), 0u);
  clamp.observe_accepted(2 * j.peak_delta());
  EXPECT_EQ(clamp.n_out_of_range(), 1u);
  const ContactForceModel err = ContactForceModel::johnson("j", j, laws::RangePolicy::error);
  EXPECT_DOUBLE_EQ(err.elastic_force(2 * j.peak_delta()), j.peak_force());
  EXPECT_NO_THROW(err.observe_accepted(0.5 * j.peak_delta()));
  EXPECT_THROW(err.observe_accepted(2 * j.peak_delta()), laws::LawRangeError);
}

TEST(ContactForceModel, LawFamilyIsEvaluatedAtTheCurrentTilt)
{
  // Two members at θ = 0 and θ = 2° (rad); the family interpolates ln F_ref and n linearly.
  const auto member = [](const double theta, const double K, const double n) {
    laws::LawFile lf;
    lf.law = {K, n};
    lf.delta_min = 0.0;
    lf.delta_max = 5e-5;
    lf.delta_ref = 5e-5;
    return laws::LawFamilyMember{theta, lf};
  };
  const double t2 = 2.0 * 3.14159265358979 / 180.0;
  const laws::LawFamily fam("theta", "rad", 5e-5,
                            {member(0.0, 3.6595e8, 1.0114), member(t2, 1.0e8, 1.05)},
                            laws::RangePolicy::clamp);
  const ContactForceModel m = ContactForceModel::law_family("fam", fam, laws::RangePolicy::extend);
  const double d_ref = 5e-5;
  const double F0 = 3.6595e8 * std::pow(d_ref, 1.0114), F2 = 1.0e8 * std::pow(d_ref, 1.05);
  // At the members: their own laws.
  EXPECT_NEAR(m.elastic_force(2e-5, 0.0), 3.6595e8 * std::pow(2e-5, 1.0114), 1e-9 * F0);
  EXPECT_NEAR(m.elastic_force(d_ref, t2), F2, 1e-9 * F2);
  // Half way: F_ref = √(F0·F2) (log-linear), n the mean.
  const double n_mid = 0.5 * (1.0114 + 1.05), F_mid = std::sqrt(F0 * F2);
  EXPECT_NEAR(m.elastic_force(d_ref, 0.5 * t2), F_mid, 1e-9 * F_mid);
  EXPECT_NEAR(m.elastic_force(1e-5, 0.5 * t2), F_mid * std::pow(1e-5 / d_ref, n_mid), 1e-9 * F_mid);
  // Beyond δ_max under "extend": evaluated; counted once an accepted state is there.
  m.elastic_force(1e-4, 0.5 * t2);
  EXPECT_EQ(m.n_out_of_range(), 0u);
  m.observe_accepted(1e-4, 0.5 * t2);
  EXPECT_EQ(m.n_out_of_range(), 1u);
}
