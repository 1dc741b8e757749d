// MBD speed-versus-accuracy benchmark (SPEC §5; not a test). Runs in-process (no output files):
//  1. wall time of each variant of the 0.1 s paper scene (best of N runs);
//  1b. for every shipped 0.1 s scene, the shipped defaults against the same scene at DP5
//     rtol 1e-12 (issue 14 item 1: slider velocity within 1e-4 m/s over 0–20 ms, first-impact
//     peak within 0.1 %), with the deepest stage penetration and the floor counter;
//  2. for two scenes (FE law with damping, energy check), each integrator (DP5, Verner 6(5),
//     Fehlberg 8(7), CVODE BDF) and relative tolerance: wall time against the error of the
//     slider velocity (0–20 ms and 0–100 ms) and of the first-impact peak force, versus a
//     tight-tolerance DP5 reference (rtol 1e-12).
// Writes Markdown tables to stdout and the raw numbers to <out>/mbd_variants.csv,
// <out>/mbd_default_accuracy.csv and <out>/mbd_tolerance.csv.
//   build/mbd_stage/mbd_benchmark [out_dir] [repeats] [sections]
// sections: a comma-separated subset of variants,accuracy,tolerance (default: all three).
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
  const std::string sections = argc > 3 ? argv[3] : "variants,accuracy,tolerance";
  const auto wanted = [&](const char *s) { return sections.find(s) != std::string::npos; };
  std::filesystem::create_directories(out);
  const char *variants[] = {"johnson", "lankarani_nikravesh", "pereira", "fe_law", "fe_law_damped",
                            "ideal", "fe_law_frictionless", "energy_check", "tilted_1deg",
                            "floating_pin"};

  // 1. Variants
  if (wanted("variants"))
  {
  std::printf("| scene (0.1 s) | wall time [s] (best of %d) | steps | RHS evals | impacts | peak F_n [N] | max rel. energy-balance error |\n", repeats);
  std::printf("|---|---|---|---|---|---|---|\n");
  CsvWriter vcsv(out + "/mbd_variants.csv",
                 {"variant", "wall_time", "n_steps", "n_rhs", "n_impacts", "peak_force", "energy_error"},
                 {"index", "s", "1", "1", "1", "N", "1"});
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
  }

  // 1b. The shipped defaults against rtol 1e-12, every scene (one run each: errors, not times).
  if (wanted("accuracy"))
  {
    std::printf("\n| scene (0.1 s) | rtol (scene) | steps | first-impact peak [N] | its error | slider velocity error, t ≤ 0.02 s [m/s] | t ≤ 0.1 s [m/s] | deepest stage δ [µm] | onsets floored |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    CsvWriter acsv(out + "/mbd_default_accuracy.csv",
                   {"variant", "rtol", "n_steps", "first_peak", "first_peak_rel_error",
                    "v_error_20ms", "v_error_100ms", "max_delta_any_stage", "n_floored"},
                   {"index", "1", "1", "N", "1", "m/s", "m/s", "m", "1"});
    int ai = 0;
    for (const char *v : variants)
    {
      const nlohmann::json doc = scene(std::string("slider_crank_") + v);
      const SimulationResult def = run(doc);
      nlohmann::json tight_doc = doc;
      tight_doc["integrator"]["rtol"] = 1e-12;
      tight_doc["integrator"]["atol_position"] = 1e-14;  // m
      tight_doc["integrator"]["atol_velocity"] = 1e-11;  // m/s
      const SimulationResult tight = run(tight_doc);
      const auto vd = def.column("slider_velocity"), vt = tight.column("slider_velocity"),
                 t = def.column("t");
      double e20 = 0, e100 = 0;
      for (std::size_t i = 0; i < std::min(vd.size(), vt.size()); ++i)
      {
        const double e = std::abs(vd[i] - vt[i]);
        e100 = std::max(e100, e);
        if (t[i] <= 0.02 + 1e-12)
          e20 = std::max(e20, e);
      }
      const double ef = tight.first_impact_peak_force > 0
                          ? std::abs(def.first_impact_peak_force / tight.first_impact_peak_force - 1)
                          : 0.0;
      double deepest = 0;
      long floored = 0;
      for (const nlohmann::json &cj : def.summary.value("clearance_joints", nlohmann::json::array()))
      {
        for (const auto &[k, d] : cj["depth_guard"]["max_delta_any_stage"].items())
          deepest = std::max(deepest, d.get<double>());
        for (const auto &[k, n] : cj["impact_velocity_floor"]["n_onsets_floored"].items())
          floored += n.get<long>();
      }
      std::printf("| %s | %.0e | %ld | %.3f | %.1e | %.1e | %.1e | %.1f | %ld |%s\n", v,
                  doc["integrator"]["rtol"].get<double>(), def.statistics.n_steps,
                  def.first_impact_peak_force, ef, e20, e100, 1e6 * deepest, floored,
                  def.complete && tight.complete ? "" : " FAILED");
      acsv.write_row({double(ai++), doc["integrator"]["rtol"].get<double>(),
                      double(def.statistics.n_steps), def.first_impact_peak_force, ef, e20, e100,
                      deepest, double(floored)});
    }
    acsv.commit();
  }

  // 2. Tolerance study against a DP5 rtol 1e-12 run, on two scenes.
  CsvWriter tcsv(out + "/mbd_tolerance.csv",
                 {"scene", "method", "rtol", "wall_time", "n_steps", "n_rhs", "first_peak_rel_error",
                  "v_error_20ms", "v_error_100ms"},
                 {"0=fe_law_damped;1=energy_check", "0=dopri5;1=verner6;2=fehlberg8;3=bdf", "1",
                  "s", "1", "1", "1", "m/s", "m/s"});
  const char *tol_scenes[] = {"fe_law_damped", "energy_check"};
  const char *methods[] = {"dopri5", "verner6", "fehlberg8", "bdf"};
  for (int si = 0; si < 2 && wanted("tolerance"); ++si)
  {
    const std::string name = std::string("slider_crank_") + tol_scenes[si];
    nlohmann::json ref_doc = scene(name);
    ref_doc["integrator"]["rtol"] = 1e-12;
    ref_doc["integrator"]["atol_position"] = 1e-14;
    ref_doc["integrator"]["atol_velocity"] = 1e-11;
    const SimulationResult ref = run(ref_doc);
    const auto v_ref = ref.column("slider_velocity");
    std::printf("\n%s — reference DP5 rtol 1e-12 (atol 1e-14 m, 1e-11 m/s): %.2f s, %ld steps, "
                "first-impact peak %.3f N\n\n",
                tol_scenes[si], ref.wall_time, ref.statistics.n_steps, ref.first_impact_peak_force);
    std::printf("| integrator | rtol | wall time [s] (best of %d) | steps | RHS evals | first-impact peak error | slider velocity error, t ≤ 0.02 s [m/s] | slider velocity error, t ≤ 0.1 s [m/s] | note |\n", repeats);
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < 4; ++m)
      for (const double rtol : {1e-8, 1e-9, 1e-10, 1e-11, 1e-12})
      {
        if (m == 3 && rtol < 1e-10)
          continue;  // BDF below 1e-10 takes tens of seconds: not an operating point
        nlohmann::json d = scene(name);
        d["integrator"]["method"] = methods[m];
        d["integrator"]["rtol"] = rtol;
        d["integrator"]["atol_position"] = 1e-2 * rtol;  // m (the scenes' ratio)
        d["integrator"]["atol_velocity"] = 10 * rtol;    // m/s
        SimulationResult r;
        double best = 1e300;
        for (int k = 0; k < repeats; ++k)
        {
          r = run(d);
          best = std::min(best, r.wall_time);
        }
        const auto v = r.column("slider_velocity"), t = r.column("t");
        double e20 = 0, e100 = 0;
        for (std::size_t i = 0; i < std::min(v.size(), v_ref.size()); ++i)
        {
          const double e = std::abs(v[i] - v_ref[i]);
          e100 = std::max(e100, e);
          if (t[i] <= 0.02 + 1e-12)
            e20 = std::max(e20, e);
        }
        const double ef = std::abs(r.first_impact_peak_force / ref.first_impact_peak_force - 1);
        // A failed run's numbers cover only the part it reached: the note says so in the table.
        std::printf("| %s | %.0e | %.3f | %ld | %ld | %.1e | %.1e | %.1e | %s |\n", methods[m], rtol,
                    best, r.statistics.n_steps, r.statistics.n_rhs, ef, e20, e100,
                    r.complete ? "" : ("FAILED at t = " + std::to_string(r.rows.empty() ? 0.0 : r.rows.back()[0]) + " s (last output): " + r.failure).c_str());
        if (r.complete)  // a failed run's errors cover only the part it reached: not plotted
          tcsv.write_row({double(si), double(m), rtol, best, double(r.statistics.n_steps),
                          double(r.statistics.n_rhs), ef, e20, e100});
      }
  }
  tcsv.commit();
  return 0;
}
