// The rolling study's restart files (fe_stage --write-restart DIR, --resume DIR; docs/fe.md
// "Restart files"), as Abaqus/Standard's *RESTART, WRITE and READ: a run long enough to outlive
// its session (the converged 1 mm reference on the finest ring takes hours) writes its state
// after every converged step (or every `every` steps) and a later run continues from it.
//
// DIR/state/rank-<r>.bin holds what rank r needs: the header (the scene as the run read it,
// the number of ranks and DoFs, the step), then each owner's part in order — the run's
// records and ledgers (RollingRun), the spin stepper's (SpinStepper::write_restart) and the
// model's: u, the points' history, the contact nodes (Model::write_restart). A write goes to
// DIR/writing and is swapped in whole: a run killed while writing leaves the last complete
// state (DIR/previous while the swap is cut short, read as well). The same mesh and partition
// are needed to read it: the same scene (output.* aside), the same number of ranks, the same
// build.
#pragma once

#include "fe_stage/core/restart_stream.h"
#include "fe_stage/scene.h"

#include <mpi.h>

#include <string>

namespace clearjoint::fe::detail
{
  class RestartFolder
  {
  public:
    RestartFolder(std::string dir, MPI_Comm comm);

    /// Each rank's bytes, collectively; every rank throws the WriteError when one failed.
    void write(const RestartWriter &bytes) const;
    /// This rank's bytes, collectively; an InputError naming --resume (or the file) on every
    /// rank when there is no complete state or it was written by another number of ranks.
    RestartReader read() const;

    const std::string &dir() const { return dir_; }

    /// The folder under `dir` holding its last complete state: `state`, or `previous` when a
    /// swap was cut short between its two renames; empty when there is none.
    static std::string complete_state(const std::string &dir);

  private:
    std::string dir_;
    MPI_Comm comm_;
    int rank_ = 0, n_ranks_ = 1;
  };

  /// What a restart file begins with, and the checks that it fits the run reading it.
  struct RestartHeader
  {
    std::string scene;  // scene_to_json without `output`, as text
    unsigned int n_ranks = 1;
    unsigned long long n_dofs = 0;
    unsigned int steps = 0;  // converged steps so far
    double time = 0.0;       // [s] at the last of them

    static RestartHeader of(const FeScene &scene, unsigned int n_ranks, unsigned long long n_dofs);
    void write(RestartWriter &out) const;
    /// Reads the header and checks it against `expected` (this run's): another scene is an
    /// InputError naming the first key that differs and both values, another number of ranks
    /// or DoFs one naming them. Returns the file's header.
    static RestartHeader read(RestartReader &in, const RestartHeader &expected);
  };
}  // namespace clearjoint::fe::detail
