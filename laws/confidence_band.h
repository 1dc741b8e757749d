// Laws at the edges of a fitted law's 95 % confidence region, to show how much an MBD result
// depends on the uncertainty of K and n (the report's band).
//
// K and n of a contact fit are strongly correlated (|ρ| > 0.99 is typical): moving K and n to
// the ends of their separate intervals at the same time gives laws far outside what the data
// allow. We move along the two principal directions of the joint estimate instead:
//   - along the ridge: n = n̂ ± t·σ_n with K = K̂ + (ρ·σ_K/σ_n)·(n − n̂) (K's conditional mean);
//   - across it:       n = n̂ with K = K̂ ± t·σ_K·√(1 − ρ²) (K's conditional spread),
// with t the Student-t factor of the stored 95 % interval.
//
// The regression interval sees only the scatter of the FE points about the fit, not the error
// of the FE points themselves. When the law carries the mesh's measured discretisation error e
// of F (law_file.h), two more variants scale the whole law by 1 ∓ e (K·(1 ∓ e), n kept): the
// measured error is of F at δ_max, and a uniform scale is the simplest law change that moves
// F(δ_max) by exactly that much. The MBD band is the envelope of all variants; the report
// compares the regression-only and mesh-only envelopes to say which dominates.
#pragma once

#include "laws/law_file.h"

#include <string>
#include <vector>

namespace clearjoint::laws
{
  struct BandLaw
  {
    std::string name;  ///< "n_low", "n_high", "K_low", "K_high"; "mesh_low", "mesh_high"
    std::string source;  ///< "regression" or "discretisation"
    LawFile law;
  };

  /// Throws InputError if the law has no diagnostics (a paper law) or a variant has K ≤ 0.
  std::vector<BandLaw> confidence_band_laws(const LawFile &law, const std::string &source);
} // namespace clearjoint::laws
