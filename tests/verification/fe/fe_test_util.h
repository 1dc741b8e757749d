// Helpers shared by the FE tests: MPI/deal.II runtime in main(), scenes from YAML text, and a
// least-squares power-law fit in log–log space (the fit stage's job; here only to check Hertz).
#pragma once

#include "common/strict_reader.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace clearjoint::fe::test
{
  inline FeScene scene(const std::string &yaml_body)
  {
    return scene_from_json(parse_yaml_string("schema: clearjoint.fe/1\n" + yaml_body, "test"),
                           "test");
  }

  inline RunResult run(const FeScene &s, MPI_Comm comm = MPI_COMM_WORLD)
  {
    RunOptions o;
    o.write_fields = false;
    o.comm = comm;
    return run_scene(s, o);
  }

  /// The pipeline's reduced rolling scene (fe_stage/scenes/rolling.yaml): 10 µm in 20 ms,
  /// held to 40 ms, μ = 0.3 and the SPEC hardening (the study's defaults), the coarse ring.
  /// rolling_keys: more keys of the rolling block, each followed by ", ". Small strain unless
  /// `kinematics` says finite (the study's default since issue 30): the tests on it were
  /// written, and their figures measured, in small strain, where a 10 µm push strains the bore
  /// by ~0.01.
  inline std::string reduced_rolling(const unsigned int n_steps,
                                     const std::string &journal = "rigid",
                                     const std::string &rolling_keys = "",
                                     const std::string &kinematics = "small")
  {
    return "study: rolling\n"
           "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
           "loading: {delta_max: 1.0e-5, journal: " +
           journal +
           "}\n"
           "rolling: {" +
           rolling_keys + "n_steps: " + std::to_string(n_steps) +
           ", ramp_time: 0.02, end_time: 0.04}\n"
           "material: {kinematics: " +
           kinematics + "}\n";
  }

  /// Least squares of log F = log K + n log δ over the increments; returns {K, n}.
  inline std::pair<double, double> fit_power_law(const RunResult &r)
  {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = r.increments.size();
    for (const auto &i : r.increments)
      {
        const double x = std::log(i.delta), y = std::log(i.force);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
      }
    const double n = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    return {std::exp((sy - n * sx) / m), n};
  }

  inline int rank(MPI_Comm comm = MPI_COMM_WORLD)
  {
    int r;
    MPI_Comm_rank(comm, &r);
    return r;
  }

  inline int world_size()
  {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
  }

  /// The np = 2 tests' two runs of one scene: on all ranks, and on rank 0 alone (the reference;
  /// filled on rank 0 only, and only if the run on all ranks completed — its status is the same
  /// on every rank, so every rank takes the same branch).
  struct AllRanksAndRankZero
  {
    RunResult all;
    std::optional<RunResult> rank_zero;
  };

  inline AllRanksAndRankZero run_on_all_ranks_and_on_rank_zero(const FeScene &s)
  {
    AllRanksAndRankZero r;
    r.all = run(s, MPI_COMM_WORLD);
    if (!r.all.complete)
      return r;
    MPI_Comm self;
    MPI_Comm_split(MPI_COMM_WORLD, rank() == 0 ? 0 : MPI_UNDEFINED, 0, &self);
    if (rank() == 0)
      {
        r.rank_zero = run(s, self);
        MPI_Comm_free(&self);
      }
    return r;
  }
} // namespace clearjoint::fe::test
