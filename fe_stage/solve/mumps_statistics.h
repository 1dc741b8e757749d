// MUMPS's own counts of a factorization, read through Trilinos' Amesos. Apart from the direct
// solver because Amesos_Mumps.h (MUMPS's C interface) clashes with deal.II's names in the
// solve unity group; this file includes no deal.II header.
#pragma once

class Amesos_BaseSolver;

namespace clearjoint::fe::detail
{
  struct MumpsStatistics
  {
    double factorization_flops = 0.0;  // RINFOG(3): the last factorization's flops, all ranks
    double factor_entries = 0.0;       // INFOG(29): the entries of its factors, all ranks
    /// INFOG(17) after the analysis: the memory its factorization will need in core, all
    /// ranks [MB] (MUMPS's estimate, before ICNTL(14)'s relaxation)
    double estimated_memory_mb = 0.0;
  };

  /// The counts of `solver`'s last analysis and factorization; zeros when it is not Amesos'
  /// MUMPS.
  MumpsStatistics mumps_statistics(Amesos_BaseSolver &solver);
}  // namespace clearjoint::fe::detail
