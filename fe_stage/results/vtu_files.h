// The VTU pieces, the PVTU record and the PVD collection of fe_stage's fields, written with
// the file names deal.II's write_vtu_with_pvtu_record gives them, through common/atomic_file.h's
// checked streams: a full disk or an I/O error is a WriteError naming the file and the OS
// reason on every rank (collective_write.h), not deal.II's ExcIO with its stack trace.
#pragma once

#include <deal.II/base/data_out_base.h>

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace clearjoint::fe
{
  /// Every rank writes DIR/solution_<counter>.<rank>.vtu, rank 0 the .pvtu record; returns
  /// the record's file name (in DIR). Collective on `comm`.
  std::string write_vtu_pieces(const dealii::DataOutInterface<3, 3> &out, const std::string &dir,
                               unsigned int counter, MPI_Comm comm);

  /// Rank 0 replaces DIR/solution.pvd with `records` (time, pvtu name). Collective on `comm`.
  void write_pvd(const std::string &dir,
                 const std::vector<std::pair<double, std::string>> &records, MPI_Comm comm);
}  // namespace clearjoint::fe
