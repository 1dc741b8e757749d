// A normal contact-force model: an elastic law F_el(δ) — Hertz, Johnson, Pereira, a power law
// from a law file, or a law family evaluated at the current misalignment θ — times the damping
// bracket of laws/damping.h:  F = F_el(δ)·[1 + χ(c_e)·δ̇/δ̇⁻]  (SPEC §4). The scene names both.
// Outside a law's valid range the scene's policy (error | clamp | extend) applies. Only accepted
// states count (observe_accepted, called by the integrator after every accepted step): the
// force evaluations inside a step are trial stages, which the error test may reject, so they
// neither count nor stop the run — under "error" a trial stage beyond the range is evaluated
// on the extrapolated law, and the run stops only if an accepted state leaves the range.
#pragma once

#include "laws/damping.h"
#include "laws/law_family.h"
#include "laws/law_file.h"
#include "laws/power_law.h"
#include "mbd_stage/cylinder_contact_laws.h"

#include <nlohmann/json.hpp>

#include <string>

namespace clearjoint::mbd
{
  enum class ElasticLawKind
  {
    power_law,   ///< analytic power law (Hertz, Pereira, a linear spring), no range
    law_file,    ///< F = K·δ^n from a clearjoint.law/1 file, with its valid range
    law_family,  ///< clearjoint.law_family/1 over θ, evaluated at the current tilt
    johnson,     ///< Johnson's implicit law
  };

  /// Result of one evaluation.
  struct ContactForce
  {
    double total = 0.0;    ///< [N] F, never negative
    double elastic = 0.0;  ///< [N] F_el
  };

  class ContactForceModel
  {
  public:
    ContactForceModel() = default;
    static ContactForceModel power_law(std::string name, laws::PowerLaw law);
    static ContactForceModel law_file(std::string name, const laws::LawFile &law,
                                      laws::RangePolicy policy);
    static ContactForceModel law_family(std::string name, laws::LawFamily family,
                                        laws::RangePolicy policy);
    static ContactForceModel johnson(std::string name, JohnsonLaw law, laws::RangePolicy policy);

    /// Sets the damping term (χ from laws::hysteresis_factor) and the floor of δ̇⁻ [m/s].
    void set_damping(laws::DampingModel model, double restitution, double min_impact_velocity);

    /// [N] F_el(δ) at misalignment theta [rad] (used only by law families).
    double elastic_force(double delta, double theta = 0.0) const;
    /// [J] ∫₀^δ F_el dδ'.
    double elastic_energy(double delta, double theta = 0.0) const;
    /// δ [m], δ̇ [m/s] (> 0 approaching), δ̇⁻ [m/s] the rate recorded at impact.
    ContactForce force(double delta, double delta_dot, double delta_dot_impact,
                       double theta = 0.0) const;

    /// δ̇⁻ actually used: max(recorded, floor) (a grazing impact has δ̇⁻ → 0 and would make
    /// the damping ratio δ̇/δ̇⁻ unbounded).
    double impact_velocity(double recorded) const;
    double min_impact_velocity() const { return min_impact_velocity_; }  ///< [m/s] the floor

    /// An accepted state with penetration δ [m] at tilt θ [rad] in an active contact: updates
    /// the range counters and the largest δ seen; under "error" throws laws::LawRangeError if δ
    /// is outside the law's valid range (Johnson: beyond its peak).
    void observe_accepted(double delta, double theta = 0.0) const;

    const std::string &name() const { return name_; }
    ElasticLawKind kind() const { return kind_; }
    laws::DampingModel damping() const { return damping_; }
    double chi() const { return chi_; }
    /// Summary: kind, parameters, range policy and how often the range was left.
    nlohmann::json describe() const;
    /// Accepted steps that ended outside the valid range.
    std::uint64_t n_out_of_range() const { return counter_.n_below + counter_.n_above; }
    double max_delta_accepted() const { return counter_.max_delta_seen; }  ///< [m]

  private:
    std::string name_;
    ElasticLawKind kind_ = ElasticLawKind::power_law;
    laws::PowerLaw power_;
    laws::BoundedPowerLaw bounded_;
    laws::LawFamily family_;
    JohnsonLaw johnson_;
    laws::RangePolicy policy_ = laws::RangePolicy::extend;  // the scene's policy
    // What a force evaluation does outside the range: "error" evaluates the extrapolated law
    // (a trial stage must not stop the run; observe_accepted enforces "error").
    static laws::RangePolicy evaluation_policy(laws::RangePolicy p)
    {
      return p == laws::RangePolicy::error ? laws::RangePolicy::extend : p;
    }
    laws::DampingModel damping_ = laws::DampingModel::none;
    double restitution_ = 1.0, chi_ = 0.0, min_impact_velocity_ = 1e-4;
    mutable laws::RangeCounter counter_;  // accepted states only (observe_accepted)
  };
} // namespace clearjoint::mbd
