// The elastic contact law F = K·δ^n (SI: δ in m, F in N, K in N/m^n) and its valid range.
// One implementation, used by fit_stage (to write laws) and mbd_stage (to evaluate them).
#pragma once

#include <cstdint>
#include <string>

namespace clearjoint::laws
{
  /// F = K·δ^n for δ > 0, and 0 for δ ≤ 0 (no contact, no adhesion).
  struct PowerLaw
  {
    double K = 0.0;  ///< [N/m^n] stiffness coefficient
    double n = 1.0;  ///< [1] exponent

    /// [N] F(δ); δ in m.
    double force(double delta) const;
    /// [N/m] dF/dδ = n·K·δ^(n−1) for δ > 0, 0 for δ ≤ 0. For n < 1 it grows without bound
    /// as δ → 0+ (SPEC §6); callers that need a finite slope at onset must bound it.
    double stiffness(double delta) const;
    /// [J] elastic energy ∫₀^δ F dδ' = K·δ^(n+1)/(n+1) for δ > 0, 0 otherwise.
    double energy(double delta) const;
  };

  /// What happens when a law is evaluated outside the δ range it was fitted on (SPEC §3).
  enum class RangePolicy
  {
    error,   ///< throw LawRangeError
    clamp,   ///< F(δ_max), zero slope, beyond δ_max; the chord F(δ_min)·δ/δ_min below δ_min
    extend,  ///< evaluate the power law anyway (extrapolate), and count it
  };
  RangePolicy parse_range_policy(const std::string &name);  // "error" | "clamp" | "extend"
  std::string to_string(RangePolicy policy);

  /// How often a law was evaluated outside its valid range (reported in summaries).
  struct RangeCounter
  {
    std::uint64_t n_below = 0, n_above = 0;
    double max_delta_seen = 0.0;  ///< [m]
  };

  /// A power law together with its valid range [δ_min, δ_max] and the policy applied outside.
  /// δ ≤ 0 is never out of range: it means no contact, and F = 0.
  class BoundedPowerLaw
  {
  public:
    BoundedPowerLaw() = default;
    /// delta_min, delta_max in m, 0 ≤ delta_min < delta_max.
    BoundedPowerLaw(PowerLaw law, double delta_min, double delta_max, RangePolicy policy);

    double force(double delta) const;      ///< [N]
    double stiffness(double delta) const;  ///< [N/m]
    /// [J] elastic energy consistent with force(): clamped beyond δ_max under clamp.
    double energy(double delta) const;

    const PowerLaw &law() const { return law_; }
    double delta_min() const { return delta_min_; }
    double delta_max() const { return delta_max_; }
    RangePolicy policy() const { return policy_; }
    const RangeCounter &counter() const { return counter_; }
    void reset_counter() const { counter_ = RangeCounter{}; }

  private:
    /// Returns the δ at which to evaluate, counting and applying the policy.
    double checked(double delta) const;

    PowerLaw law_;
    double delta_min_ = 0.0, delta_max_ = 0.0;
    RangePolicy policy_ = RangePolicy::error;
    mutable RangeCounter counter_;
  };
} // namespace clearjoint::laws
