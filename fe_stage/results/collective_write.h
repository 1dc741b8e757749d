// Writes on some MPI ranks, failures known to all (issue 33): a full disk while one rank
// writes (rank 0 its CSV rows, manifests and plots; every rank its VTU piece) must not leave
// the other ranks waiting in the next collective call. The ranks meet after each write; if
// any failed, every rank throws the same WriteError (the lowest failing rank's file and
// reason), so fe_stage ends on all ranks together with one line from rank 0. No deal.II.
#pragma once

#include <mpi.h>

#include <functional>
#include <stdexcept>

namespace clearjoint::fe
{
  /// Thrown on the ranks whose own step succeeded when another rank's step failed with
  /// something other than a WriteError (that rank rethrows its own exception and reports it).
  class StoppedElsewhere : public std::runtime_error
  {
  public:
    explicit StoppedElsewhere(int exit_code);
    int exit_code() const { return code_; }

  private:
    int code_;
  };

  /// Runs `write` on this rank (e.g. only on rank 0: `if (root) ...`), then meets the others
  /// (collective on `comm`): if any rank's write failed, every rank throws — the WriteError of
  /// the lowest failing rank on all of them, or else the failing rank its own exception and
  /// the others StoppedElsewhere with its exit code.
  void write_collectively(MPI_Comm comm, const std::function<void()> &write);

  /// True once write_collectively has thrown on every rank together (no rank is left waiting:
  /// no MPI_Abort needed).
  bool failed_together();
}  // namespace clearjoint::fe
