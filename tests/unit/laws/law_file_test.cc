#include "common/error.h"
#include "common/strict_reader.h"
#include "laws/law_file.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <functional>

using namespace clearjoint;
using namespace clearjoint::laws;

namespace
{
  const std::string paper_law_path = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";

  std::string error_of(const nlohmann::json &j)
  {
    return test_support::input_error_of([&] { law_from_json(j, "law.json"); });
  }

  LawFile fitted_law()
  {
    LawFile l;
    l.law = {3.7e8, 1.02};
    l.delta_min = 0.0;
    l.delta_max = 5e-5;
    l.delta_ref = 5e-5;
    l.source_kind = "fit";
    l.source_description = "test";
    l.data_file = "/x/force_penetration.csv";
    l.data_sha256 = std::string(64, 'a');
    l.scene = {{"t_B", 0.004}};
    FitDiagnostics d;
    d.n_points = 3;
    d.weighting = "absolute";
    d.fit_delta_min = 1e-5;
    d.fit_delta_max = 5e-5;
    d.r_squared = 0.9999;
    d.K_ci95_low = 3.6e8, d.K_ci95_high = 3.8e8;
    d.n_ci95_low = 1.01, d.n_ci95_high = 1.03;
    d.correlation_K_n = 0.99;
    d.delta = {1e-5, 3e-5, 5e-5};
    d.force = {3000, 9000, 16000};
    d.residual = {1, -2, 1};
    d.solver_summary = "ok";
    l.diagnostics = d;
    return l;
  }
} // namespace

TEST(LawFile, PaperLawIsTheSpecsConversion)
{
  const LawFile l = read_law_file(paper_law_path);
  EXPECT_NEAR(l.law.K, 3.6595e8, 0.0001e8);  // SPEC §1, 5 digits
  EXPECT_DOUBLE_EQ(l.law.n, 1.0114);
  EXPECT_NEAR(l.F_ref(), 16344.0, 0.5);      // SPEC §1: 16 344 N at 0.05 mm
  EXPECT_DOUBLE_EQ(l.delta_max, 5e-5);
  EXPECT_EQ(l.source_kind, "paper");
  EXPECT_FALSE(l.diagnostics.has_value());
}

TEST(LawFile, RoundTripKeepsEveryField)
{
  test_support::ScratchDir dir("law_roundtrip");
  const LawFile a = fitted_law();
  write_law_file(dir.file("law.json"), a);
  const LawFile b = read_law_file(dir.file("law.json"));
  EXPECT_EQ(b.law.K, a.law.K);
  EXPECT_EQ(b.law.n, a.law.n);
  EXPECT_EQ(b.delta_max, a.delta_max);
  EXPECT_EQ(b.data_sha256, a.data_sha256);
  EXPECT_EQ(b.scene, a.scene);
  ASSERT_TRUE(b.diagnostics.has_value());
  EXPECT_EQ(b.diagnostics->residual, a.diagnostics->residual);
  EXPECT_EQ(b.diagnostics->n_ci95_high, a.diagnostics->n_ci95_high);
  EXPECT_EQ(to_json(b), to_json(a));
}

TEST(LawFile, ReaderRejectsUnknownKeys)
{
  auto j = to_json(fitted_law());
  j["comment"] = "hello";
  EXPECT_NE(error_of(j).find("'comment'"), std::string::npos) << error_of(j);
  j = to_json(fitted_law());
  j["law"]["K_mm"] = 1.0;
  EXPECT_NE(error_of(j).find("law.K_mm"), std::string::npos) << error_of(j);
}

TEST(LawFile, ReaderRejectsAWrongSchemaVersion)
{
  auto j = to_json(fitted_law());
  j["schema"] = "clearjoint.law/2";
  EXPECT_NE(error_of(j).find("clearjoint.law/2"), std::string::npos);
  j.erase("schema");
  EXPECT_NE(error_of(j).find("'schema'"), std::string::npos);
}

TEST(LawFile, ReaderRejectsMissingOrWrongUnits)
{
  auto j = to_json(fitted_law());
  j.erase("units");
  EXPECT_NE(error_of(j).find("'units'"), std::string::npos) << error_of(j);
  j = to_json(fitted_law());
  j["units"]["delta"] = "mm";
  const std::string m = error_of(j);
  EXPECT_NE(m.find("units.delta"), std::string::npos) << m;
  EXPECT_NE(m.find("'mm'"), std::string::npos) << m;
}

TEST(LawFile, ReaderRejectsNonPositiveK)
{
  for (const double K : {0.0, -3.6e8})
  {
    auto j = to_json(fitted_law());
    j["law"]["K"] = K;
    const std::string m = error_of(j);
    EXPECT_NE(m.find("law.K"), std::string::npos) << m;
    EXPECT_NE(m.find("(0, inf) N/m^n"), std::string::npos) << m;
  }
}

TEST(LawFile, ReaderRejectsInconsistentCopies)
{
  auto j = to_json(fitted_law());
  j["reference"]["F_ref"] = 1.0;  // edited by hand without changing K
  EXPECT_NE(error_of(j).find("reference.F_ref"), std::string::npos);
  j = to_json(fitted_law());
  j["mm_N"]["K"] = 338240.0;
  EXPECT_NE(error_of(j).find("mm_N.K"), std::string::npos);
}

TEST(LawFile, DiscretisationErrorRoundTripsAndIsOptional)
{
  test_support::ScratchDir dir("law_discretisation");
  LawFile a = fitted_law();
  a.discretisation_error = DiscretisationError{0.02, "preset standard: Richardson"};
  write_law_file(dir.file("law.json"), a);
  const LawFile b = read_law_file(dir.file("law.json"));
  ASSERT_TRUE(b.discretisation_error.has_value());
  EXPECT_EQ(b.discretisation_error->F_relative, 0.02);
  EXPECT_EQ(b.discretisation_error->description, "preset standard: Richardson");
  // Written as null when unknown, and a file from before the key existed still reads.
  auto j = to_json(fitted_law());
  EXPECT_TRUE(j.at("discretisation_error").is_null());
  EXPECT_FALSE(law_from_json(j, "law.json").discretisation_error.has_value());
  j.erase("discretisation_error");
  EXPECT_FALSE(law_from_json(j, "law.json").discretisation_error.has_value());
}

TEST(LawFile, ReaderRejectsABadDiscretisationError)
{
  LawFile a = fitted_law();
  a.discretisation_error = DiscretisationError{0.02, "x"};
  auto j = to_json(a);
  j["discretisation_error"]["F_relative"] = 1.5;  // 150 %: outside [0, 1)
  EXPECT_NE(error_of(j).find("discretisation_error.F_relative"), std::string::npos) << error_of(j);
  j = to_json(a);
  j["discretisation_error"]["unit"] = "%";
  EXPECT_NE(error_of(j).find("discretisation_error.unit"), std::string::npos) << error_of(j);
  j = to_json(a);
  j["discretisation_error"]["extra"] = 1;
  EXPECT_NE(error_of(j).find("discretisation_error.extra"), std::string::npos) << error_of(j);
}
