// The fit_stage executable end to end: bad data and options give a clear message, exit code 1
// and no law file; good data give a law file and a manifest.
#include "common/strict_reader.h"
#include "laws/law_family.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace clearjoint;
namespace fs = std::filesystem;

namespace
{
  std::string good_csv()
  {
    std::string s = "# units: m,N,1\ndelta,force,n_iterations\n0,0,0\n";
    for (int i = 1; i <= 10; ++i)
      s += std::to_string(5e-6 * i) + "," + std::to_string(3.65952708e8 * std::pow(5e-6 * i, 1.0114)) +
           ",3\n";
    return s;
  }

  struct CommandRun
  {
    int exit_code;
    std::string output;
  };

  CommandRun fit(const test_support::ScratchDir &dir, const std::string &args)
  {
    const std::string log = dir.file("log.txt");
    const int rc = test_support::run_command(std::string(FIT_STAGE_EXE) + " --no-plots " + args, log);
    return {rc, test_support::read_text(log)};
  }
} // namespace

TEST(FitStageCommand, GoodDataWriteLawAndManifest)
{
  test_support::ScratchDir dir("fit_cli_good");
  test_support::write_text(dir.file("data.csv"), good_csv());
  const CommandRun r = fit(dir, dir.file("data.csv") + " --output " + dir.file("law.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto law = laws::read_law_file(dir.file("law.json"));
  EXPECT_NEAR(law.law.n, 1.0114, 1e-5);  // data written with 6 significant digits
  EXPECT_EQ(law.delta_min, 0.0) << "the origin row makes the law valid from 0";
  const auto m = read_json_file(dir.file("law.manifest.json"));
  EXPECT_EQ(m["status"], "complete");
  EXPECT_NE(r.output.find("N/mm^n"), std::string::npos) << "prints the mm/N form too";
}

TEST(FitStageCommand, BadDataExitWithInputErrorAndNoLawFile)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    {"delta,force\n0,0\n1e-5,3000\n2e-5,6000\n", "at least 3 points"},
    {"delta,force\n1e-5,3000\n-2e-5,6000\n3e-5,9000\n4e-5,12000\n", "column 'delta'"},
    {"delta,force\n1e-5,3000\n2e-5,-6000\n3e-5,9000\n4e-5,12000\n", "column 'force'"},
    {"delta,force\n1e-5,5000\n2e-5,5000\n3e-5,5000\n4e-5,5000\n", "constant"},
    {"delta,force\n1e-5,3000\n2e-5,nan\n3e-5,9000\n4e-5,12000\n", "finite"},
    {"delta,load\n1e-5,3000\n2e-5,6000\n3e-5,9000\n4e-5,12000\n", "column 'force'"},
    {"# units: mm,N\ndelta,force\n1e-2,3000\n2e-2,6000\n3e-2,9000\n", "unit"},
  };
  for (const auto &[csv, expected] : cases)
  {
    test_support::ScratchDir dir("fit_cli_bad");
    test_support::write_text(dir.file("data.csv"), csv);
    const CommandRun r = fit(dir, dir.file("data.csv") + " --output " + dir.file("law.json"));
    EXPECT_EQ(r.exit_code, 1) << csv << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in:\n"
                                                          << r.output;
    EXPECT_NE(r.output.find(dir.file("data.csv")), std::string::npos) << "names the file";
    EXPECT_FALSE(fs::exists(dir.file("law.json"))) << csv;
  }
}

TEST(FitStageCommand, BadOptionsAndMissingFile)
{
  test_support::ScratchDir dir("fit_cli_opts");
  test_support::write_text(dir.file("data.csv"), good_csv());
  const std::string base = dir.file("data.csv") + " --output " + dir.file("law.json");
  EXPECT_EQ(fit(dir, base + " --range 5e-5:1e-5").exit_code, 1);
  EXPECT_EQ(fit(dir, base + " --start -1,1").exit_code, 1);
  EXPECT_EQ(fit(dir, base + " --weighting squared").exit_code, 1);
  const CommandRun r = fit(dir, dir.file("nope.csv") + " --output " + dir.file("law.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("nope.csv"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("law.json")));
}

TEST(FitStageCommand, FamilyOverTheta)
{
  test_support::ScratchDir dir("fit_cli_family");
  test_support::write_text(dir.file("a.csv"), good_csv());
  std::string b = "delta,force\n0,0\n";
  for (int i = 1; i <= 10; ++i)
    b += std::to_string(4e-6 * i) + "," + std::to_string(2e9 * std::pow(4e-6 * i, 1.2)) + "\n";
  test_support::write_text(dir.file("b.csv"), b);
  const CommandRun r = fit(dir, "--family theta " + dir.file("b.csv") + "=0.02 " + dir.file("a.csv") +
                           "=0 --output " + dir.file("family.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto f = laws::read_law_family(dir.file("family.json"));
  EXPECT_EQ(f.unit(), "rad");
  ASSERT_EQ(f.members().size(), 2u);
  EXPECT_EQ(f.members()[0].value, 0.0) << "members sorted by value";
  EXPECT_DOUBLE_EQ(f.delta_ref(), 4e-5) << "common reference inside every member's range";
}

// Issue 15 item 6: the FE mesh's measured error of F goes into the law (and every member of a
// family); an impossible value is an input error naming the option, with no law written.
TEST(FitStageCommand, DiscretisationErrorIsRecordedAndChecked)
{
  test_support::ScratchDir dir("fit_cli_disc");
  test_support::write_text(dir.file("data.csv"), good_csv());
  const std::string base = dir.file("data.csv") + " --output " + dir.file("law.json");
  const CommandRun ok = fit(dir, base + " --discretisation-error 2.5 --discretisation-error-source 'level 1'");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const auto law = laws::read_law_file(dir.file("law.json"));
  ASSERT_TRUE(law.discretisation_error.has_value());
  EXPECT_EQ(law.discretisation_error->F_relative, 0.025);
  EXPECT_EQ(law.discretisation_error->description, "level 1");
  fs::remove(dir.file("law.json"));
  const CommandRun bad = fit(dir, base + " --discretisation-error 100");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("--discretisation-error"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir.file("law.json")));
  EXPECT_EQ(fit(dir, base + " --discretisation-error-source x").exit_code, 1)
    << "a source without a value";
  const CommandRun fam = fit(dir, "--family t_B " + dir.file("data.csv") + "=0.004 " +
                                    dir.file("data.csv") + "=0.006 --discretisation-error 4.8 --output " +
                                    dir.file("family.json"));
  ASSERT_EQ(fam.exit_code, 0) << fam.output;
  // a named family: members() refers into it (a temporary's would dangle in the range-for)
  const auto family = laws::read_law_family(dir.file("family.json"));
  for (const auto &m : family.members())
    EXPECT_EQ(m.law.discretisation_error->F_relative, 0.048);
}

// Issue 32 item 4: where no preset figure applies, the law's discretisation error is fe_stage's
// own estimate from the FE run's manifest (--discretisation-error-from), the largest of several
// for a family; a manifest without one, or both sources at once, is an input error naming it.
TEST(FitStageCommand, DiscretisationErrorFromTheFeRunsOwnEstimate)
{
  test_support::ScratchDir dir("fit_cli_own_estimate");
  test_support::write_text(dir.file("data.csv"), good_csv());
  const auto manifest = [&](const std::string &name, const std::string &adaptive) {
    test_support::write_text(dir.file(name),
                             "{\"schema\": \"clearjoint.manifest/1\", \"extra\": {" + adaptive + "}}");
    return dir.file(name);
  };
  const std::string a = manifest(
    "a.json", "\"adaptive\": {\"estimated_error_F_max\": {\"value\": 0.0085, \"unit\": \"1\", "
              "\"method\": \"last two cycles extrapolated\"}, \"cycles\": [{}, {}, {}]}");
  const std::string b = manifest(
    "b.json", "\"adaptive\": {\"estimated_error_F_max\": {\"value\": 0.033, \"unit\": \"1\", "
              "\"method\": \"change in the last cycle (not extrapolated; not a bound)\"}}");
  const std::string none = manifest("none.json", "\"mesh\": {}");
  const std::string base = dir.file("data.csv") + " --output " + dir.file("law.json");

  const CommandRun one = fit(dir, base + " --discretisation-error-from " + a);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto law = laws::read_law_file(dir.file("law.json"));
  ASSERT_TRUE(law.discretisation_error.has_value());
  EXPECT_EQ(law.discretisation_error->F_relative, 0.0085);
  EXPECT_NE(law.discretisation_error->description.find("own estimate, 0.85 % (extrapolated)"),
            std::string::npos)
    << law.discretisation_error->description;
  EXPECT_NE(law.discretisation_error->description.find(a), std::string::npos);

  const CommandRun fam = fit(dir, "--family t_B " + dir.file("data.csv") + "=0.004 " +
                                    dir.file("data.csv") + "=0.006 --output " +
                                    dir.file("family.json") + " --discretisation-error-from " + a +
                                    " --discretisation-error-from " + b);
  ASSERT_EQ(fam.exit_code, 0) << fam.output;
  const auto family = laws::read_law_family(dir.file("family.json"));
  for (const auto &m : family.members())
  {
    EXPECT_EQ(m.law.discretisation_error->F_relative, 0.033) << "the largest";
    EXPECT_NE(m.law.discretisation_error->description.find("~3.3 % (the change in the last cycle"),
              std::string::npos)
      << m.law.discretisation_error->description;
    EXPECT_NE(m.law.discretisation_error->description.find("the largest of 2 cases"),
              std::string::npos);
  }

  fs::remove(dir.file("law.json"));
  const CommandRun missing = fit(dir, base + " --discretisation-error-from " + none);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("extra.adaptive.estimated_error_F_max"), std::string::npos)
    << missing.output;
  EXPECT_NE(missing.output.find("none.json"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir.file("law.json")));
  const CommandRun both =
    fit(dir, base + " --discretisation-error 2 --discretisation-error-from " + a);
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.output.find("--discretisation-error-from"), std::string::npos) << both.output;
  // --check before the FE runs: a manifest not written yet is skipped
  EXPECT_EQ(fit(dir, base + " --check --discretisation-error-from " + dir.file("later.json"))
              .exit_code,
            0);
}
