// main() for the FE test executables: MPI, p4est and deal.II are initialised once (one thread
// per rank), and only rank 0 prints GoogleTest's report.
#include "fe_stage/fe_model.h"

#include <gtest/gtest.h>

int main(int argc, char **argv)
{
  const auto runtime = clearjoint::fe::make_runtime(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0)
    {
      auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
  return RUN_ALL_TESTS();
}
