#include "laws/damping.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::laws
{
  namespace
  {
    struct Entry
    {
      DampingModel model;
      const char *name;
    };
    constexpr Entry entries[] = {
      {DampingModel::none, "none"},
      {DampingModel::lankarani_nikravesh, "lankarani_nikravesh"},
      {DampingModel::hunt_crossley, "hunt_crossley"},
      {DampingModel::flores, "flores"},
      {DampingModel::gonthier, "gonthier"},
    };
  } // namespace

  std::vector<std::string> damping_model_names()
  {
    std::vector<std::string> names;
    for (const auto &e : entries)
      names.emplace_back(e.name);
    return names;
  }

  DampingModel parse_damping_model(const std::string &name)
  {
    for (const auto &e : entries)
      if (name == e.name)
        return e.model;
    std::string all;
    for (const auto &n : damping_model_names())
      all += (all.empty() ? "" : "|") + n;
    throw InputError("", "damping", name, "one of " + all);
  }

  std::string to_string(const DampingModel model)
  {
    for (const auto &e : entries)
      if (model == e.model)
        return e.name;
    return "?";
  }

  double hysteresis_factor(const DampingModel model, const double c_e)
  {
    if (!(c_e > 0.0 && c_e <= 1.0))
      throw InputError("", "restitution", format_value(c_e), "(0, 1]");
    switch (model)
    {
      case DampingModel::none:
        return 0.0;
      case DampingModel::lankarani_nikravesh:
        return 3.0 * (1.0 - c_e * c_e) / 4.0;
      case DampingModel::hunt_crossley:
        return 3.0 * (1.0 - c_e) / 2.0;
      case DampingModel::flores:
        return 8.0 * (1.0 - c_e) / (5.0 * c_e);
      case DampingModel::gonthier:
        return (1.0 - c_e * c_e) / c_e;
    }
    return 0.0;
  }

  double damping_force(const double F_el, const double chi, const double delta_dot,
                       const double delta_dot_impact)
  {
    if (chi == 0.0)
      return 0.0;
    if (!(delta_dot_impact > 0.0))
      throw NumericalError("damped contact force needs the impact rate delta_dot_impact > 0, got " +
                           format_value(delta_dot_impact) + " m/s");
    return F_el * chi * delta_dot / delta_dot_impact;
  }

  double damped_force(const double F_el, const double chi, const double delta_dot,
                      const double delta_dot_impact)
  {
    return std::max(0.0, F_el + damping_force(F_el, chi, delta_dot, delta_dot_impact));
  }
} // namespace clearjoint::laws
