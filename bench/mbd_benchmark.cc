// MBD speed-versus-accuracy benchmark (SPEC §5; not a test). Runs in-process (no output files):
//  1. wall time of each variant of the 0.1 s paper scene (best of N runs);
//  2. for each integrator (DP5, DP5 with the paper's max step 1e-5 s, CVODE BDF) and relative
//     tolerance: wall time against the error of the slider velocity and of the peak contact
//     forces, versus a tight-tolerance DP5 reference (rtol 1e-12).
// Writes Markdown tables to stdout and the raw numbers to <out>/mbd_variants.csv and
// <out>/mbd_tolerance.csv.
//   build/mbd_stage/mbd_benchmark [out_dir] [repeats]
#include "common/csv.h"
#include "common/log.h"
#include "common/strict_reader.h"
#include "mbd_stage/scene.h"
#include "mbd_stage/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace clearjoint;
using namespace clearjoint::mbd;

namespace
{
  const std::string scenes = std::string(CLEARJOINT_SOURCE_DIR) + "/mbd_stage/scenes";

  SimulationResult run(const nlohmann::json &doc)
  {
    Scene s = scene_from_json(doc, "bench", scenes);
    return simulate(s);
  }

  nlohmann::json scene(const std::string &name)
  {
    return read_yaml_file(scenes + "/" + name + ".yaml");
  }
} // namespace

int main(int argc, char **argv)
{
  log::set_level(log::Level::error);
  const std::string out = argc > 1 ? argv[1] : "bench_out";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::filesystem::create_directories(out);

  // 1. Variants
  std::printf("| scene (0.1 s) | wall time [s] (best of %d) | steps | RHS evals | impacts | peak F_n [N] | max rel. energy-balance error |\n", repeats);
  std::printf("|---|---|---|---|---|---|---|\n");
  CsvWriter vcsv(out + "/mbd_variants.csv",
                 {"variant", "wall_time", "n_steps", "n_rhs", "n_impacts", "peak_force", "energy_error"},
                 {"index", "s", "1", "1", "1", "N", "1"});
  const char *variants[] = {"johnson", "lankarani_nikravesh", "pereira", "fe_law", "fe_law_damped",
                            "ideal", "fe_law_frictionless", "energy_check", "tilted_1deg"};
  int vi = 0;
  for (const char *v : variants)
  {
    const nlohmann::json doc = scene(std::string("slider_crank_") + v);
    double best = 1e300;
    SimulationResult r;
    for (int k = 0; k < repeats; ++k)
    {
      r = run(doc);
      best = std::min(best, r.wall_time);
    }
    long impacts = 0;
    for (const auto &e : r.events)
      impacts += e.onset ? 1 : 0;
    std::printf("| %s | %.3f | %ld | %ld | %ld | %.1f | %.1e |\n", v, best, r.statistics.n_steps,
                r.statistics.n_rhs, impacts, r.peak_contact_force, r.max_relative_energy_error);
    vcsv.write_row({double(vi++), best, double(r.statistics.n_steps), double(r.statistics.n_rhs),
                    double(impacts), r.peak_contact_force, r.max_relative_energy_error});
  }
  vcsv.commit();

  // 2. Tolerance study on the FE law with dissipation.
  nlohmann::json ref_doc = scene("slider_crank_fe_law_damped");
  ref_doc["integrator"]["rtol"] = 1e-12;
  ref_doc["integrator"]["atol_position"] = 1e-14;
  ref_doc["integrator"]["atol_velocity"] = 1e-11;
  const SimulationResult ref = run(ref_doc);
  const auto v_ref = ref.column("slider_velocity"), t_ref = ref.column("t");
  std::printf("\nReference: DP5, rtol 1e-12 (atol 1e-14 m, 1e-11 m/s): %.2f s, first-impact peak %.3f N, max peak %.3f N\n\n",
              ref.wall_time, ref.first_impact_peak_force, ref.peak_contact_force);
  std::printf("| integrator | rtol | wall time [s] | steps | first-impact peak error | max-peak error | slider velocity error, t ≤ 0.02 s [m/s] | slider velocity error, t ≤ 0.1 s [m/s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  CsvWriter tcsv(out + "/mbd_tolerance.csv",
                 {"method", "rtol", "wall_time", "n_steps", "first_peak_rel_error",
                  "max_peak_rel_error", "v_error_20ms", "v_error_100ms"},
                 {"0=dopri5,1=dopri5_maxstep,2=bdf", "1", "s", "1", "1", "1", "m/s", "m/s"});
  const char *methods[] = {"dopri5", "dopri5, max step 1e-5 s", "bdf"};
  for (int m = 0; m < 3; ++m)
    for (const double rtol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10})
    {
      if (m == 2 && rtol < 1e-9)
        continue;  // BDF at 1e-10 needs > 1 min: not a useful operating point
      nlohmann::json d = scene("slider_crank_fe_law_damped");
      d["integrator"]["method"] = m == 2 ? "bdf" : "dopri5";
      d["integrator"]["rtol"] = rtol;
      d["integrator"]["atol_position"] = 1e-2 * rtol;  // m (the scenes' ratio)
      d["integrator"]["atol_velocity"] = 10 * rtol;    // m/s
      d["integrator"]["max_step"] = m == 1 ? 1e-5 : 0.0;
      const SimulationResult r = run(d);
      const auto v = r.column("slider_velocity"), t = r.column("t");
      double e20 = 0, e100 = 0;
      for (std::size_t i = 0; i < std::min(v.size(), v_ref.size()); ++i)
      {
        const double e = std::abs(v[i] - v_ref[i]);
        e100 = std::max(e100, e);
        if (t[i] <= 0.02)
          e20 = std::max(e20, e);
      }
      const double ef = std::abs(r.first_impact_peak_force / ref.first_impact_peak_force - 1);
      const double em = std::abs(r.peak_contact_force / ref.peak_contact_force - 1);
      std::printf("| %s | %.0e | %.3f | %ld | %.1e | %.1e | %.1e | %.1e |%s\n", methods[m], rtol,
                  r.wall_time, r.statistics.n_steps, ef, em, e20, e100,
                  r.complete ? "" : (" FAILED: " + r.failure).c_str());
      tcsv.write_row({double(m), rtol, r.wall_time, double(r.statistics.n_steps), ef, em, e20, e100});
    }
  tcsv.commit();
  return 0;
}
