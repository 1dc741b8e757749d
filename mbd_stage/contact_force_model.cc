#include "mbd_stage/contact_force_model.h"

#include "common/error.h"
#include "laws/law_range_error.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace clearjoint::mbd
{
  ContactForceModel ContactForceModel::power_law(std::string name, laws::PowerLaw law)
  {
    ContactForceModel m;
    m.name_ = std::move(name);
    m.kind_ = ElasticLawKind::power_law;
    m.power_ = law;
    return m;
  }

  ContactForceModel ContactForceModel::law_file(std::string name, const laws::LawFile &law,
                                                const laws::RangePolicy policy)
  {
    ContactForceModel m;
    m.name_ = std::move(name);
    m.kind_ = ElasticLawKind::law_file;
    m.power_ = law.law;
    m.bounded_ = law.bounded(evaluation_policy(policy));
    m.policy_ = policy;
    return m;
  }

  ContactForceModel ContactForceModel::law_family(std::string name, laws::LawFamily family,
                                                  const laws::RangePolicy policy)
  {
    ContactForceModel m;
    m.name_ = std::move(name);
    m.kind_ = ElasticLawKind::law_family;
    m.family_ = std::move(family);
    m.policy_ = policy;
    return m;
  }

  ContactForceModel ContactForceModel::johnson(std::string name, JohnsonLaw law,
                                               const laws::RangePolicy policy)
  {
    ContactForceModel m;
    m.name_ = std::move(name);
    m.kind_ = ElasticLawKind::johnson;
    m.johnson_ = law;
    m.policy_ = policy;
    return m;
  }

  void ContactForceModel::set_damping(const laws::DampingModel model, const double restitution,
                                      const double min_impact_velocity)
  {
    damping_ = model;
    restitution_ = restitution;
    chi_ = laws::hysteresis_factor(model, restitution);
    min_impact_velocity_ = min_impact_velocity;
  }

  double ContactForceModel::impact_velocity(const double recorded) const
  {
    return std::max(recorded, min_impact_velocity_);
  }

  double ContactForceModel::elastic_force(const double delta, const double theta) const
  {
    if (delta <= 0.0)
      return 0.0;
    switch (kind_)
    {
      case ElasticLawKind::power_law:
        return power_.force(delta);
      case ElasticLawKind::law_file:
        return bounded_.force(delta);
      case ElasticLawKind::law_family:
      {
        const auto [lo, hi] = family_.valid_range_at(theta);
        return laws::BoundedPowerLaw(family_.at(theta), lo, hi, evaluation_policy(policy_))
          .force(delta);
      }
      case ElasticLawKind::johnson:
        return johnson_.force(delta);  // held at the peak force beyond δ_peak
    }
    return 0.0;
  }

  double ContactForceModel::elastic_energy(const double delta, const double theta) const
  {
    if (delta <= 0.0)
      return 0.0;
    switch (kind_)
    {
      case ElasticLawKind::power_law:
        return power_.energy(delta);
      case ElasticLawKind::law_file:
        return bounded_.energy(delta);
      case ElasticLawKind::law_family:
      {
        const auto [lo, hi] = family_.valid_range_at(theta);
        return laws::BoundedPowerLaw(family_.at(theta), lo, hi, laws::RangePolicy::extend)
          .energy(delta);
      }
      case ElasticLawKind::johnson:
        return johnson_.energy(delta);
    }
    return 0.0;
  }

  ContactForce ContactForceModel::force(const double delta, const double delta_dot,
                                        const double delta_dot_impact, const double theta) const
  {
    ContactForce f;
    if (delta <= 0.0)
      return f;
    f.elastic = elastic_force(delta, theta);
    f.total = chi_ == 0.0 ? f.elastic
                          : laws::damped_force(f.elastic, chi_, delta_dot,
                                               impact_velocity(delta_dot_impact));
    return f;
  }

  void ContactForceModel::observe_accepted(const double delta, const double theta) const
  {
    if (delta <= 0.0)
      return;
    counter_.max_delta_seen = std::max(counter_.max_delta_seen, delta);
    double lo = 0.0, hi = 0.0;
    switch (kind_)
    {
      case ElasticLawKind::power_law:
        return;  // analytic law: no range
      case ElasticLawKind::law_file:
        lo = bounded_.delta_min();
        hi = bounded_.delta_max();
        break;
      case ElasticLawKind::law_family:
        std::tie(lo, hi) = family_.valid_range_at(theta);
        break;
      case ElasticLawKind::johnson:
        hi = johnson_.peak_delta();
        break;
    }
    const bool below = delta < lo, above = delta > hi;
    if (!below && !above)
      return;
    ++(below ? counter_.n_below : counter_.n_above);
    if (policy_ == laws::RangePolicy::error)
      throw laws::LawRangeError(delta, lo, hi);
  }

  nlohmann::json ContactForceModel::describe() const
  {
    const char *accepted_note =
      "counted at the ends of accepted integration steps in contact; trial stages of rejected "
      "or accepted steps do not count";
    nlohmann::json j;
    j["name"] = name_;
    j["damping"] = laws::to_string(damping_);
    j["restitution"] = restitution_;
    j["chi"] = chi_;
    j["min_impact_velocity"] = {{"value", min_impact_velocity_}, {"unit", "m/s"}};
    switch (kind_)
    {
      case ElasticLawKind::power_law:
        j["law"] = {{"form", "F = K*delta^n"}, {"K", power_.K}, {"n", power_.n},
                    {"units", {{"K", "N/m^n"}, {"n", "1"}}}};
        break;
      case ElasticLawKind::law_file:
      {
        const auto &c = counter_;
        j["law"] = {{"form", "F = K*delta^n (law file)"}, {"K", power_.K}, {"n", power_.n},
                    {"units", {{"K", "N/m^n"}, {"n", "1"}}}};
        j["valid_range"] = {{"delta_min", bounded_.delta_min()},
                            {"delta_max", bounded_.delta_max()}, {"unit", "m"}};
        j["out_of_range"] = {{"policy", laws::to_string(policy_)},
                             {"n_accepted_steps_below", c.n_below},
                             {"n_accepted_steps_above", c.n_above},
                             {"max_delta_accepted", c.max_delta_seen}, {"unit", "m"},
                             {"note", accepted_note}};
        break;
      }
      case ElasticLawKind::law_family:
        j["law"] = {{"form", "law family over " + family_.parameter()},
                    {"n_members", family_.members().size()}};
        j["out_of_range"] = {{"policy", laws::to_string(policy_)},
                             {"n_accepted_steps_below", counter_.n_below},
                             {"n_accepted_steps_above", counter_.n_above},
                             {"n_parameter_out_of_range", family_.n_parameter_out_of_range()},
                             {"max_delta_accepted", counter_.max_delta_seen}, {"unit", "m"},
                             {"note", accepted_note}};
        break;
      case ElasticLawKind::johnson:
        j["law"] = {{"form", "Johnson: delta = F/(pi L E*) [ln(4 pi L E* dR / F) - 1]"},
                    {"peak_force", johnson_.peak_force()},
                    {"peak_delta", johnson_.peak_delta()},
                    {"units", {{"peak_force", "N"}, {"peak_delta", "m"}}}};
        j["out_of_range"] = {{"policy", laws::to_string(policy_)},
                             {"n_accepted_steps_beyond_peak", counter_.n_above},
                             {"max_delta_accepted", counter_.max_delta_seen}, {"unit", "m"},
                             {"note", accepted_note}};
        break;
    }
    return j;
  }
} // namespace clearjoint::mbd
