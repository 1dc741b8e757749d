// MUMPS's counts of a factorization (solve/mumps_statistics.h).
#include "fe_stage/solve/mumps_statistics.h"

#include <Amesos_Mumps.h>

namespace clearjoint::fe::detail
{
  MumpsStatistics mumps_statistics(Amesos_BaseSolver &solver)
  {
    MumpsStatistics s;
    if (auto *mumps = dynamic_cast<Amesos_Mumps *>(&solver))
      {
        // (MUMPS's arrays are 1-based in its manual, 0-based here)
        s.factorization_flops = mumps->GetRINFOG()[2];
        s.factor_entries = double(mumps->GetINFOG()[28]);
        s.estimated_memory_mb = double(mumps->GetINFOG()[16]);
      }
    return s;
  }
}  // namespace clearjoint::fe::detail
