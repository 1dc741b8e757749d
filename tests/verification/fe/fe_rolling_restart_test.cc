// The rolling study's restart files (fe_stage --write-restart / --resume,
// solve/rolling_restart.h): a run cut short after a step and resumed from the state it wrote
// ends where the uninterrupted run ends, its earlier steps replayed as they were; a state of
// another scene, of another number of ranks, a damaged or a missing one is an input error that
// names what is wrong. On the deformable journal with finite strain (the study's default
// kinematics), which carries the most state across a step: the mortar search's partners, the
// journal's turn ψ, both bodies' plastic history. ~30 s.
#include "fe_test_util.h"

#include "common/error.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

using namespace clearjoint;
using namespace clearjoint::fe;
using namespace clearjoint::fe::test;

namespace
{
  namespace fs = std::filesystem;

  /// What the callback throws to cut a run short after a step, as a kill would (the state of
  /// that step is written before the callbacks run).
  struct CutShort
  {};

  std::string restart_scene(const std::string &extra = "")
  {
    return "study: rolling\n"
           "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
           "loading: {delta_max: 1.0e-5, journal: core}\n"
           "rolling: {n_steps: 6, ramp_time: 0.02, end_time: 0.03}\n"
           "material: {kinematics: finite}\n" +
           extra;
  }

  /// A folder of its own for the test (the ranks agree on it: rank 0's pid), empty.
  std::string fresh_folder(const std::string &name, MPI_Comm comm = MPI_COMM_WORLD)
  {
    long pid = static_cast<long>(::getpid());
    MPI_Bcast(&pid, 1, MPI_LONG, 0, comm);
    const std::string dir =
      testing::TempDir() + "clearjoint_restart_" + name + "_" + std::to_string(pid);
    if (rank(comm) == 0)
      fs::remove_all(dir);
    MPI_Barrier(comm);
    return dir;
  }

  RunResult run_with(const FeScene &s, const RunOptions::Restart &restart,
                     const std::function<void(const RollingStepRecord &)> &on_step = {},
                     MPI_Comm comm = MPI_COMM_WORLD)
  {
    RunOptions o;
    o.write_fields = false;
    o.comm = comm;
    o.restart = restart;
    o.on_rolling_step = on_step;
    return run_scene(s, o);
  }

  /// The run cut short after `steps` steps, its state in `dir`.
  void run_cut_short(const FeScene &s, const std::string &dir, const unsigned int steps,
                     MPI_Comm comm = MPI_COMM_WORLD)
  {
    RunOptions::Restart r;
    r.write_dir = dir;
    EXPECT_THROW(run_with(
                   s, r,
                   [&](const RollingStepRecord &rec) {
                     if (rec.step == steps)
                       throw CutShort{};
                   },
                   comm),
                 CutShort);
  }

  /// The resumed run against the uninterrupted one, step by step. The resumed run's first
  /// solves have no kept factors to precondition GMRES with (solve/factorization_reuse.h), so
  /// its linear solves differ from the uninterrupted run's within the solver's tolerance
  /// (1e-10 of the residual): 1e-8 of each quantity's scale leaves room for that and nothing
  /// more (measured: 6e-13 of D_p, 5e-12 of the largest ε_p, 1e-11 of F).
  void expect_same_run(const RunResult &full, const RunResult &resumed, const FeScene &s)
  {
    ASSERT_TRUE(full.complete) << full.message;
    ASSERT_TRUE(resumed.complete) << resumed.message;
    ASSERT_EQ(full.rolling_steps.size(), resumed.rolling_steps.size());
    ASSERT_EQ(resumed.increments.size(), resumed.rolling_steps.size());
    const auto &end = full.rolling_steps.back();
    for (std::size_t k = 0; k < full.rolling_steps.size(); ++k)
      {
        const auto &a = full.rolling_steps[k], &b = resumed.rolling_steps[k];
        EXPECT_EQ(a.step, b.step);
        EXPECT_EQ(a.time, b.time) << "step " << a.step;  // the same steps, no other cuts
        EXPECT_NEAR(a.force_normal, b.force_normal, 1e-8 * end.force_normal) << "step " << a.step;
        EXPECT_NEAR(a.gamma_rate, b.gamma_rate, 1e-8 * s.rolling.omega_B) << "step " << a.step;
        EXPECT_NEAR(a.gamma, b.gamma, 1e-8 * end.gamma) << "step " << a.step;
        EXPECT_NEAR(a.plastic_dissipation, b.plastic_dissipation, 1e-8 * end.plastic_dissipation)
          << "step " << a.step;
        EXPECT_NEAR(a.friction_dissipation, b.friction_dissipation, 1e-8 * end.friction_dissipation)
          << "step " << a.step;
        EXPECT_NEAR(a.elastic_energy, b.elastic_energy, 1e-8 * end.elastic_energy)
          << "step " << a.step;
        EXPECT_NEAR(a.work_frame, b.work_frame, 1e-8 * end.work_frame) << "step " << a.step;
        EXPECT_NEAR(a.max_plastic_strain, b.max_plastic_strain, 1e-8 * end.max_plastic_strain)
          << "step " << a.step;
        EXPECT_NEAR(a.gamma_paper, b.gamma_paper, 1e-8 * std::abs(end.gamma_paper))
          << "step " << a.step;
      }
    EXPECT_GT(end.max_plastic_strain, 0.0);  // the plastic history is carried
    EXPECT_GT(end.friction_dissipation, 0.0);
  }
}  // namespace

TEST(FeRollingRestart, AResumedRunEndsWhereTheUninterruptedRunEnds)
{
  const FeScene s = scene(restart_scene());
  const RunResult full = run(s);

  const std::string dir = fresh_folder("resume");
  run_cut_short(s, dir, 3);
  ASSERT_TRUE(fs::exists(dir + "/state/rank-0.bin"));
  RunOptions::Restart r;
  r.resume_dir = dir;
  unsigned int replayed = 0;
  const RunResult resumed = run_with(s, r, [&](const RollingStepRecord &rec) {
    // the first three arrive before any new step: the earlier run's, replayed
    if (rec.step <= 3)
      ++replayed;
  });
  EXPECT_EQ(replayed, 3u);
  expect_same_run(full, resumed, s);
  std::printf("restart: F %.12g / %.12g N, D_p %.12g / %.12g J (uninterrupted / resumed)\n",
              full.rolling_steps.back().force_normal, resumed.rolling_steps.back().force_normal,
              full.rolling_steps.back().plastic_dissipation,
              resumed.rolling_steps.back().plastic_dissipation);
  fs::remove_all(dir);
}

// The state must belong to the scene that reads it: another μ is an input error naming
// contact.mu with both values; a truncated file, and a folder without a state, are input
// errors naming the file or --resume. Nothing is run from them.
TEST(FeRollingRestart, AnotherSceneADamagedFileOrNoStateIsAnInputError)
{
  const FeScene s = scene(restart_scene());
  const std::string dir = fresh_folder("refused");
  run_cut_short(s, dir, 1);
  RunOptions::Restart r;
  r.resume_dir = dir;
  try
    {
      run_with(scene(restart_scene("contact: {mu: 0.2}\n")), r);
      ADD_FAILURE() << "another scene was resumed";
    }
  catch (const InputError &e)
    {
      EXPECT_EQ(e.key_path(), "contact.mu") << e.what();
      EXPECT_NE(std::string(e.what()).find("0.3"), std::string::npos) << e.what();
    }

  const std::string file = dir + "/state/rank-0.bin";
  fs::resize_file(file, fs::file_size(file) / 2);
  try
    {
      run_with(s, r);
      ADD_FAILURE() << "a truncated state was resumed";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("ends early"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }

  fs::remove_all(dir + "/state");
  try
    {
      run_with(s, r);
      ADD_FAILURE() << "a folder without a state was resumed";
    }
  catch (const InputError &e)
    {
      EXPECT_EQ(e.key_path(), "--resume") << e.what();
    }
  fs::remove_all(dir);
}

// On two ranks: each writes its own part, and the resumed run ends where the uninterrupted one
// ends (same tolerance as above); a state of two ranks read by one is an input error naming
// --resume and the number of ranks.
TEST(FeMpi, RollingRestartOnTwoRanks)
{
  if (world_size() < 2)
    GTEST_SKIP() << "needs mpirun -np 2";
  const FeScene s = scene(restart_scene());
  const RunResult full = run(s);
  const std::string dir = fresh_folder("mpi");
  run_cut_short(s, dir, 3);
  RunOptions::Restart r;
  r.resume_dir = dir;
  const RunResult resumed = run_with(s, r);
  expect_same_run(full, resumed, s);

  MPI_Comm self;
  MPI_Comm_split(MPI_COMM_WORLD, rank() == 0 ? 0 : MPI_UNDEFINED, 0, &self);
  if (rank() == 0)
    {
      try
        {
          run_with(s, r, {}, self);
          ADD_FAILURE() << "a two-rank state was resumed on one rank";
        }
      catch (const InputError &e)
        {
          EXPECT_EQ(e.key_path(), "--resume") << e.what();
          EXPECT_NE(std::string(e.what()).find("-np 2"), std::string::npos) << e.what();
        }
      MPI_Comm_free(&self);
    }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank() == 0)
    fs::remove_all(dir);
}
