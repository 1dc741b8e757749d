#include "fe_stage/results/vtu_files.h"

#include "common/atomic_file.h"
#include "fe_stage/results/collective_write.h"

#include <deal.II/base/utilities.h>

#include <sstream>

namespace clearjoint::fe
{
  std::string write_vtu_pieces(const dealii::DataOutInterface<3, 3> &out, const std::string &dir,
                               const unsigned int counter, MPI_Comm comm)
  {
    using dealii::Utilities::int_to_string;
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    // As write_vtu_with_pvtu_record(dir + "/", "solution", counter, comm, 4, 0) names them.
    const unsigned int n_digits =
      dealii::Utilities::needed_digits(static_cast<unsigned int>(n_ranks - 1));
    const std::string stem = "solution_" + int_to_string(counter, 4);
    const auto piece = [&](const int r) {
      return stem + "." + int_to_string(static_cast<unsigned int>(r), n_digits) + ".vtu";
    };
    write_collectively(comm, [&] {
      write_file(dir + "/" + piece(rank), [&](std::ostream &o) { out.write_vtu(o); });
    });
    const std::string pvtu = stem + ".pvtu";
    write_collectively(comm, [&] {
      if (rank != 0)
        return;
      std::vector<std::string> pieces;
      for (int r = 0; r < n_ranks; ++r)
        pieces.push_back(piece(r));
      write_file(dir + "/" + pvtu, [&](std::ostream &o) { out.write_pvtu_record(o, pieces); });
    });
    return pvtu;
  }

  void write_pvd(const std::string &dir,
                 const std::vector<std::pair<double, std::string>> &records, MPI_Comm comm)
  {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    write_collectively(comm, [&] {
      if (rank != 0)
        return;
      std::ostringstream text;  // small: composed in memory, written in one piece
      dealii::DataOutBase::write_pvd_record(text, records);
      write_file_atomically(dir + "/solution.pvd", text.str());
    });
  }
}  // namespace clearjoint::fe
