#include "common/error.h"
#include "laws/law_family.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;
using namespace clearjoint::laws;

namespace
{
  LawFile law(double K, double n)
  {
    LawFile l;
    l.law = {K, n};
    l.delta_max = 5e-5;
    l.delta_ref = 5e-5;
    l.source_kind = "fit";
    l.source_description = "test";
    return l;
  }

  LawFamily theta_family(RangePolicy policy)
  {
    return LawFamily("theta", "rad", 5e-5,
                     {{0.0, law(3.7e8, 1.01)}, {0.02, law(1.0e9, 1.2)}, {0.04, law(2e9, 1.4)}},
                     policy);
  }
} // namespace

TEST(LawFamily, MembersAreReproducedExactly)
{
  const auto f = theta_family(RangePolicy::error);
  for (const auto &m : f.members())
  {
    const PowerLaw p = f.at(m.value);
    EXPECT_NEAR(p.n, m.law.law.n, 1e-14);
    EXPECT_NEAR(p.force(5e-5), m.law.law.force(5e-5), 1e-10 * m.law.law.force(5e-5));
  }
}

TEST(LawFamily, InterpolatesLogFrefAndNLinearly)
{
  const auto f = theta_family(RangePolicy::error);
  const double Fa = 3.7e8 * std::pow(5e-5, 1.01), Fb = 1.0e9 * std::pow(5e-5, 1.2);
  const PowerLaw p = f.at(0.005);  // a quarter of the way from 0 to 0.02
  EXPECT_NEAR(p.n, 0.75 * 1.01 + 0.25 * 1.2, 1e-14);
  EXPECT_NEAR(p.force(5e-5), std::exp(0.75 * std::log(Fa) + 0.25 * std::log(Fb)),
              1e-10 * Fa);
}

TEST(LawFamily, ParameterPolicies)
{
  EXPECT_THROW(theta_family(RangePolicy::error).at(0.05), InputError);
  const auto c = theta_family(RangePolicy::clamp);
  EXPECT_NEAR(c.at(0.05).n, 1.4, 1e-14);
  EXPECT_NEAR(c.at(-0.01).n, 1.01, 1e-14);
  EXPECT_EQ(c.n_parameter_out_of_range(), 2u);
  const auto e = theta_family(RangePolicy::extend);
  EXPECT_NEAR(e.at(0.05).n, 1.5, 1e-12);  // slope 0.2/0.02 rad continued for 0.01 rad
}

TEST(LawFamily, FileRoundTripAndStrictReading)
{
  test_support::ScratchDir dir("family_roundtrip");
  const auto f = theta_family(RangePolicy::clamp);
  write_law_family(dir.file("f.json"), f);
  EXPECT_EQ(peek_schema(dir.file("f.json")), law_family_schema);
  const auto g = read_law_family(dir.file("f.json"));
  EXPECT_EQ(to_json(g), to_json(f));
  auto j = to_json(f);
  j["members"][1]["weight"] = 1;
  EXPECT_THROW(law_family_from_json(j, "f.json"), InputError);
  j = to_json(f);
  j["members"][1]["value"] = 0.0;  // not strictly increasing
  EXPECT_THROW(law_family_from_json(j, "f.json"), InputError);
}
