// The single impact of issue 12 item 4 (mbd_stage/single_impact.h) against the closed forms of
// the undamped power-law impact, and the damped models' restitution and its inverse (the c_e
// that reproduces a given restitution).
#include "common/csv.h"
#include "common/error.h"
#include "laws/law_file.h"
#include "mbd_stage/single_impact.h"

#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include <signal.h>
#include <unistd.h>

using namespace clearjoint;
using namespace clearjoint::mbd;

namespace
{
  // the journal of the default joint on the fitted t_B = 4 mm law (order of magnitude)
  SingleImpact journal(const double n, const laws::DampingModel d = laws::DampingModel::none,
                       const double ce = 1.0)
  {
    SingleImpact s;
    s.mass = 0.0398;
    s.velocity = 0.1;
    s.law = {3.7e8 * std::pow(1e-6, 1.0 - n), n};  // F(1 µm) = 370 N for every n
    s.damping = d;
    s.restitution = ce;
    return s;
  }
} // namespace

// Undamped: δ_max, the contact duration (π √(m/K) for n = 1, the Γ-function form for any n)
// and restitution 1, to the RK4 step's accuracy (h = t_c/20000: the local error h⁵ gives ~1e-12
// relative over the impact; 1e-8 leaves room for the kink of δ^n at δ = 0).
TEST(SingleImpact, UndampedImpactMatchesTheClosedForms)
{
  for (const double n : {1.0, 1.06, 1.5})
    {
      const SingleImpact s = journal(n);
      const SingleImpactResult r = simulate_single_impact(s);
      const double dmax = undamped_delta_max(s.mass, s.velocity, s.law);
      const double tc = undamped_contact_duration(s.mass, s.velocity, s.law);
      EXPECT_NEAR(r.delta_max / dmax, 1.0, 1e-8) << "n = " << n;
      EXPECT_NEAR(r.contact_duration / tc, 1.0, 1e-8) << "n = " << n;
      EXPECT_NEAR(r.restitution, 1.0, 1e-8) << "n = " << n;
      EXPECT_NEAR(r.peak_force / s.law.force(dmax), 1.0, 1e-8) << "n = " << n;
      // the peak is at half the contact (a symmetric undamped impact)
      EXPECT_NEAR(r.time_of_peak / (0.5 * tc), 1.0, 1e-3) << "n = " << n;
    }
  const SingleImpact lin = journal(1.0);
  EXPECT_NEAR(undamped_contact_duration(lin.mass, lin.velocity, lin.law),
              M_PI * std::sqrt(lin.mass / lin.law.K), 1e-12 * M_PI * std::sqrt(lin.mass / lin.law.K));
  // Hertz (n = 3/2): t_c = 2.9432 δ_max/v (Johnson, Contact Mechanics, Eq. 11.24)
  const SingleImpact hz = journal(1.5);
  EXPECT_NEAR(undamped_contact_duration(hz.mass, hz.velocity, hz.law) /
                (undamped_delta_max(hz.mass, hz.velocity, hz.law) / hz.velocity),
              2.9432, 1e-4);
}

// Damped: the restitution falls below 1, less for c_e near 1; the model's own target c_e is
// roughly reproduced (Lankarani–Nikravesh derives χ for c_e near 1; Flores for any c_e). The
// measured mismatches are printed, not asserted beyond a loose band.
TEST(SingleImpact, DampedModelsReturnRoughlyTheirRestitution)
{
  using D = laws::DampingModel;
  for (const D d : {D::lankarani_nikravesh, D::hunt_crossley, D::flores, D::gonthier})
    for (const double ce : {0.95, 0.8, 0.6})
      {
        const SingleImpactResult r = simulate_single_impact(journal(1.06, d, ce));
        EXPECT_LT(r.restitution, 1.0);
        EXPECT_GT(r.restitution, 0.0);
        // 0.25: the models differ by design away from c_e = 1 (Flores 2011, Fig. 7)
        EXPECT_NEAR(r.restitution, ce, 0.25) << laws::to_string(d) << " c_e = " << ce;
        std::printf("%-20s c_e %.2f -> restitution %.4f\n", laws::to_string(d).c_str(), ce,
                    r.restitution);
      }
  // for c_e = 0.95 every model is within 0.03 of it (the models agree near elastic impacts)
  for (const D d : {D::lankarani_nikravesh, D::hunt_crossley, D::flores, D::gonthier})
    EXPECT_NEAR(simulate_single_impact(journal(1.06, d, 0.95)).restitution, 0.95, 0.03);
}

// The restitution of the power law with δ̇/δ̇⁻ damping does not depend on v (the impact is
// self-similar in v), so the fitted c_e does not either.
TEST(SingleImpact, RestitutionDoesNotDependOnTheVelocity)
{
  SingleImpact s = journal(1.06, laws::DampingModel::flores, 0.8);
  const double e1 = simulate_single_impact(s).restitution;
  s.velocity = 0.2;
  const double e2 = simulate_single_impact(s).restitution;
  EXPECT_NEAR(e1, e2, 1e-9);
}

// The inverse: simulate with c_e, fit c_e back from the restitution (round trip); an
// unreachable restitution names the model and its limit.
TEST(SingleImpact, FittedCoefficientReproducesTheRestitution)
{
  using D = laws::DampingModel;
  for (const D d : {D::lankarani_nikravesh, D::hunt_crossley, D::flores, D::gonthier})
    {
      const double ce = 0.9;
      const double e = simulate_single_impact(journal(1.06, d, ce)).restitution;
      const double fitted = fit_restitution_coefficient(journal(1.06, d), e);
      // 1e-7: the bisection resolves c_e to 1e-15; the restitution's own integration error
      // (~1e-10) divided by de/dc_e (~0.5–1) is what limits it
      EXPECT_NEAR(fitted, ce, 1e-7) << laws::to_string(d);
    }
  const std::string m = test_support::input_error_of(
    [&] { fit_restitution_coefficient(journal(1.06, D::lankarani_nikravesh), 0.1); });
  EXPECT_NE(m.find("lankarani_nikravesh"), std::string::npos) << "LN cannot reach 0.1: " << m;
  EXPECT_THROW(fit_restitution_coefficient(journal(1.06, D::flores), 1.5), InputError);
  EXPECT_THROW(fit_restitution_coefficient(journal(1.06, D::none), 0.9), InputError);
  SingleImpact bad = journal(1.06);
  bad.mass = 0.0;
  EXPECT_THROW(simulate_single_impact(bad), InputError);
  bad = journal(1.06);
  bad.velocity = -0.1;
  EXPECT_THROW(simulate_single_impact(bad), InputError);
}

// impact_compare end to end on a made-up FE sweep (two velocities): the tables are written with
// one row per velocity, the fitted c_e of every damping model returns the FE restitution, and
// bad input (a missing column, a bad --restitution) exits 1 and writes nothing.
TEST(ImpactCompare, WritesTheComparisonAndRejectsBadInput)
{
  test_support::ScratchDir dir("impact_compare");
  const std::string sweep = dir.file("sweep.csv");
  test_support::write_text(sweep,
                           "# units: m/s,N,m,s,1,kg\n"
                           "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,"
                           "restitution,journal_mass_kg\n"
                           "0.05,240.7,4.9e-07,3.37e-05,0.9754,0.0398\n"
                           "0.1,481.4,9.8e-07,3.37e-05,0.9754,0.0398\n# status: complete\n");
  const std::string law = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  const std::string exe = IMPACT_COMPARE_EXE;
  const std::string out = dir.file("out");
  ASSERT_EQ(test_support::run_command(exe + " --law " + law + " --fe-sweep " + sweep +
                                        " --output " + out + " --no-plots",
                                      dir.file("log.txt")),
            0)
    << test_support::read_text(dir.file("log.txt"));
  const CsvTable fits = read_csv(out + "/restitution_fit.csv");
  ASSERT_EQ(fits.rows.size(), 2u);
  for (const char *m : {"lankarani_nikravesh", "hunt_crossley", "flores", "gonthier"})
    {
      const double ce = fits.column(std::string("c_e_") + m)[1];
      ASSERT_GT(ce, 0.0) << m;
      SingleImpact s{0.0398, 0.1, laws::read_law_file(law).law, laws::parse_damping_model(m), ce};
      // the fitted c_e gives back the FE restitution (bisection to 1e-15 in c_e)
      EXPECT_NEAR(simulate_single_impact(s).restitution, 0.9754, 1e-9) << m;
    }
  const CsvTable table = read_csv(out + "/impact_comparison.csv");
  EXPECT_EQ(table.rows.size(), 2u);
  EXPECT_NEAR(table.column("none_restitution")[0], 1.0, 1e-8);
  EXPECT_TRUE(std::filesystem::exists(out + "/manifest.json"));

  // a sweep without the restitution column, and a bad --restitution: exit 1, nothing written
  const std::string bad = dir.file("bad.csv");
  test_support::write_text(bad, "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,"
                                "journal_mass_kg\n0.1,481.4,9.8e-07,3.37e-05,0.0398\n");
  const std::string out2 = dir.file("out2");
  EXPECT_EQ(test_support::run_command(exe + " --law " + law + " --fe-sweep " + bad +
                                        " --output " + out2, dir.file("log2.txt")),
            1);
  EXPECT_NE(test_support::read_text(dir.file("log2.txt")).find("restitution"), std::string::npos);
  EXPECT_EQ(test_support::run_command(exe + " --law " + law + " --fe-sweep " + sweep +
                                        " --output " + out2 + " --restitution 1.5",
                                      dir.file("log3.txt")),
            1);
  EXPECT_FALSE(std::filesystem::exists(out2));
}

namespace
{
  /// A stand-in for fe_stage's impact sweep folder: impact_sweep.csv, its manifest listing the
  /// case folders, and per case its manifest (v, journal mass) and quasi-static curve F = K δ^n.
  void write_impact_sweep(const std::string &dir, const std::vector<double> &restitution,
                          const double K, const double n, const double dt_fraction)
  {
    const std::vector<std::pair<double, double>> cases = {{0.1, 0.0398}, {0.1, 1.0}};
    std::filesystem::create_directories(dir);
    std::string table = "# units: m/s,N,m,s,1,kg,s,s\n"
                        "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,restitution,"
                        "journal_mass_kg,time_step_s,contact_period_s\n";
    std::string outputs;
    for (std::size_t i = 0; i < cases.size(); ++i)
      {
        const auto [v, m] = cases[i];
        const std::string folder = dir + "/m_" + std::to_string(i) + "kg_v_0.1mps";
        std::filesystem::create_directories(folder);
        std::string curve = "# units: m,N\ndelta,force\n0,0\n";
        for (int k = 1; k <= 10; ++k)
          {
            const double d = 2.0e-6 * k * (1.0 + 4.0 * i);
            curve += std::to_string(d) + "," + std::to_string(K * std::pow(d, n)) + "\n";
          }
        test_support::write_text(folder + "/force_penetration.csv", curve + "# status: complete\n");
        test_support::write_text(folder + "/manifest.json",
                                 "{\"extra\": {\"n_dofs\": 8600, \"impact\": {\"velocity_in\": "
                                 "{\"value\": " + std::to_string(v) + "}, \"journal_mass\": "
                                 "{\"value\": " + std::to_string(m) + "}}}}\n");
        outputs += std::string(i ? "," : "") + "{\"path\": \"/moved/away/" +
                   std::filesystem::path(folder).filename().string() + "/manifest.json\"}";
        const double T = 2.0 * M_PI * std::sqrt(m / K);
        table += std::to_string(v) + ",100,1e-06,3e-05," + std::to_string(restitution[i]) + "," +
                 std::to_string(m) + "," + std::to_string(T * dt_fraction) + "," +
                 std::to_string(T) + "\n";
      }
    test_support::write_text(dir + "/impact_sweep.csv", table + "# status: complete\n");
    test_support::write_text(dir + "/manifest.json", "{\"outputs\": [" + outputs +
                                                       ", {\"path\": \"" + dir +
                                                       "/impact_sweep.csv\"}]}\n");
  }
}  // namespace

// Like for like (issue 31 item 4): with the sweep's case folders beside it, each case's own
// quasi-static curve is fitted (a power law here: K and n come back) and its single impacts use
// it; a given --law is set beside; a second sweep at another dt gives the error bars (the
// largest difference of the FE restitution and of each fitted c_e to the main sweep's), and a
// level without one of the cases is an input error.
TEST(ImpactCompare, FitsEachCasesOwnCurveAndGivesErrorBarsFromTheLevels)
{
  test_support::ScratchDir dir("impact_compare_own");
  const double K = 4.0e8 * std::pow(1e-6, -0.05), n = 1.05;  // ~400 N at 1 µm
  write_impact_sweep(dir.file("main"), {0.96, 0.99}, K, n, 1.0 / 40);
  write_impact_sweep(dir.file("fine"), {0.95, 0.985}, K, n, 1.0 / 80);
  const std::string law = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  const std::string out = dir.file("out");
  ASSERT_EQ(test_support::run_command(std::string(IMPACT_COMPARE_EXE) + " --law " + law +
                                        " --fe-sweep " + dir.file("main/impact_sweep.csv") +
                                        " --fe-sweep-level " + dir.file("fine/impact_sweep.csv") +
                                        " --no-plots --output " + out,
                                      dir.file("log.txt")),
            0)
    << test_support::read_text(dir.file("log.txt"));
  const CsvTable t = read_csv(out + "/impact_comparison.csv");
  ASSERT_EQ(t.rows.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i)
    {
      // the exact power law comes back from the fit (to the curve's 6 printed digits)
      EXPECT_NEAR(t.column("law_K")[i] / K, 1.0, 1e-4);
      EXPECT_NEAR(t.column("law_n")[i], n, 1e-5);
      EXPECT_EQ(t.column("law_own")[i], 1.0);
    }
  EXPECT_TRUE(t.has_column("given_law_peak_force_error"));  // the paper's law set beside
  const CsvTable f = read_csv(out + "/restitution_fit.csv");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_NEAR(f.column("fe_restitution_error_bar")[0], 0.01, 1e-9);
  EXPECT_NEAR(f.column("fe_restitution_error_bar")[1], 0.005, 1e-9);
  // the fitted c_e moves with the restitution it reproduces: a bar of the same order
  const double bar = f.column("c_e_flores_error_bar")[0];
  EXPECT_GT(bar, 0.002);
  EXPECT_LT(bar, 0.05);
  // and it is the distance to the c_e that the finer level's restitution gives on the same law
  SingleImpact s{0.0398, 0.1, laws::PowerLaw{K, n}, laws::DampingModel::flores, 1.0};
  EXPECT_NEAR(bar,
              std::abs(fit_restitution_coefficient(s, 0.95) - fit_restitution_coefficient(s, 0.96)),
              1e-4);
  const std::string manifest = test_support::read_text(out + "/manifest.json");
  EXPECT_NE(manifest.find("own_quasi_static_curve"), std::string::npos);
  EXPECT_NE(manifest.find("spread over dt and mesh levels"), std::string::npos);

  // a level that lacks a case (a table alone, on the given law): exit 1, naming the level
  std::filesystem::remove(dir.file("fine/manifest.json"));
  test_support::write_text(dir.file("fine/impact_sweep.csv"),
                           "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,restitution,"
                           "journal_mass_kg\n0.2,100,1e-06,3e-05,0.95,0.0398\n"
                           "0.2,100,1e-06,3e-05,0.95,1\n# status: complete\n");
  EXPECT_EQ(test_support::run_command(std::string(IMPACT_COMPARE_EXE) + " --law " + law +
                                        " --fe-sweep " + dir.file("main/impact_sweep.csv") +
                                        " --fe-sweep-level " +
                                        dir.file("fine/impact_sweep.csv") + " --no-plots --output " +
                                        dir.file("out2"),
                                      dir.file("log2.txt")),
            1);
  EXPECT_NE(test_support::read_text(dir.file("log2.txt")).find("fine/impact_sweep.csv"),
            std::string::npos)
    << test_support::read_text(dir.file("log2.txt"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("out2")));
}

// An --output that cannot be made (a file in the way) is an input error naming --output, for
// impact_compare and mbd_stage alike (impact_compare used to end in "unexpected failure", 2).
TEST(ImpactCompare, AnOutputFolderThatCannotBeMadeIsAnInputError)
{
  test_support::ScratchDir dir("impact_compare_output");
  const std::string sweep = dir.file("sweep.csv");
  test_support::write_text(sweep,
                           "# units: m/s,N,m,s,1,kg\n"
                           "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,"
                           "restitution,journal_mass_kg\n"
                           "0.1,481.4,9.8e-07,3.37e-05,0.9754,0.0398\n# status: complete\n");
  test_support::write_text(dir.file("a_file"), "x");
  const std::string law = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  EXPECT_EQ(test_support::run_command(std::string(IMPACT_COMPARE_EXE) + " --law " + law +
                                        " --fe-sweep " + sweep + " --no-plots --output " +
                                        dir.file("a_file/out"),
                                      dir.file("log.txt")),
            1)
    << test_support::read_text(dir.file("log.txt"));
  EXPECT_NE(test_support::read_text(dir.file("log.txt")).find("key '--output'"),
            std::string::npos)
    << test_support::read_text(dir.file("log.txt"));
  EXPECT_EQ(test_support::read_text(dir.file("a_file")), "x");
}

// impact_compare interrupted while plotting (SIGINT, SIGTERM): plot.py stopped (a stand-in
// that ignores SIGINT), exit 130/143, the earlier output left as it was, no DIR.tmp.<pid>.
TEST(ImpactCompare, AnInterruptWhilePlottingLeavesTheEarlierOutput)
{
  test_support::ScratchDir dir("impact_compare_interrupt");
  const std::string sweep = dir.file("sweep.csv");
  test_support::write_text(sweep,
                           "# units: m/s,N,m,s,1,kg\n"
                           "v_in_m_per_s,peak_force_N,delta_max_m,contact_duration_s,"
                           "restitution,journal_mass_kg\n"
                           "0.1,481.4,9.8e-07,3.37e-05,0.9754,0.0398\n# status: complete\n");
  const std::string law = std::string(CLEARJOINT_SOURCE_DIR) + "/laws/paper_tB4.json";
  const std::string out = dir.file("out");
  ASSERT_EQ(test_support::run_command(std::string(IMPACT_COMPARE_EXE) + " --law " + law +
                                        " --fe-sweep " + sweep + " --no-plots --output " + out,
                                      dir.file("first.log")),
            0);
  const std::string old_manifest = test_support::read_text(out + "/manifest.json");
  test_support::write_text(dir.file("slow_plot.py"),
                           "import os, signal, time\n"
                           "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
                           "open(os.environ['PLOT_PID_FILE'], 'w').write(str(os.getpid()))\n"
                           "time.sleep(60)\n");
  for (const auto &[sig, code] : std::vector<std::pair<int, int>>{{SIGINT, 130}, {SIGTERM, 143}})
  {
    const std::string pid_file = dir.file("plot.pid");
    std::filesystem::remove(pid_file);
    const pid_t pid = test_support::start_process(
      IMPACT_COMPARE_EXE, {"--law", law, "--fe-sweep", sweep, "--output", out},
      dir.file("run.log"),
      {"CLEARJOINT_PLOT_SCRIPT=" + dir.file("slow_plot.py"), "PLOT_PID_FILE=" + pid_file});
    for (int i = 0; i < 3000 && test_support::read_text(pid_file).empty(); ++i)
      usleep(20000);
    ASSERT_FALSE(test_support::read_text(pid_file).empty())
      << test_support::read_text(dir.file("run.log"));
    const pid_t plot = std::stoi(test_support::read_text(pid_file));
    kill(pid, sig);
    EXPECT_EQ(test_support::wait_exit_code(pid), code)
      << test_support::read_text(dir.file("run.log"));
    EXPECT_EQ(test_support::read_text(out + "/manifest.json"), old_manifest);
    for (const auto &e : std::filesystem::directory_iterator(dir.path()))
      EXPECT_EQ(e.path().filename().string().find("out.tmp"), std::string::npos) << e.path();
    bool gone = false;
    for (int i = 0; i < 250 && !gone; ++i, usleep(20000))
      gone = kill(plot, 0) != 0;
    EXPECT_TRUE(gone) << "plot.py still running";
  }
}
