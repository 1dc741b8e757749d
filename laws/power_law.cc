#include "laws/power_law.h"

#include "common/error.h"
#include "laws/law_range_error.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::laws
{
  double PowerLaw::force(const double delta) const
  {
    return delta > 0.0 ? K * std::pow(delta, n) : 0.0;
  }

  double PowerLaw::stiffness(const double delta) const
  {
    return delta > 0.0 ? n * K * std::pow(delta, n - 1.0) : 0.0;
  }

  double PowerLaw::energy(const double delta) const
  {
    return delta > 0.0 ? K * std::pow(delta, n + 1.0) / (n + 1.0) : 0.0;
  }

  RangePolicy parse_range_policy(const std::string &name)
  {
    if (name == "error")
      return RangePolicy::error;
    if (name == "clamp")
      return RangePolicy::clamp;
    if (name == "extend")
      return RangePolicy::extend;
    throw InputError("", "out_of_range", name, "one of error|clamp|extend");
  }

  std::string to_string(const RangePolicy policy)
  {
    switch (policy)
    {
      case RangePolicy::error:
        return "error";
      case RangePolicy::clamp:
        return "clamp";
      case RangePolicy::extend:
        return "extend";
    }
    return "?";
  }

  BoundedPowerLaw::BoundedPowerLaw(PowerLaw law, const double delta_min, const double delta_max,
                                   const RangePolicy policy)
    : law_(law)
    , delta_min_(delta_min)
    , delta_max_(delta_max)
    , policy_(policy)
  {
    if (!(law.K > 0.0) || !std::isfinite(law.K))
      throw InputError("", "law.K", format_value(law.K), "(0, inf) N/m^n");
    if (!(law.n > 0.0) || !std::isfinite(law.n))
      throw InputError("", "law.n", format_value(law.n), "(0, inf)");
    if (!(delta_min >= 0.0 && delta_max > delta_min && std::isfinite(delta_max)))
      throw InputError("", "valid_range", format_value(delta_min) + ":" + format_value(delta_max),
                       "0 <= delta_min < delta_max < inf m");
  }

  double BoundedPowerLaw::checked(const double delta) const
  {
    if (delta <= 0.0)
      return delta;
    counter_.max_delta_seen = std::max(counter_.max_delta_seen, delta);
    const bool below = delta < delta_min_, above = delta > delta_max_;
    if (!below && !above)
      return delta;
    (below ? counter_.n_below : counter_.n_above) += 1;
    switch (policy_)
    {
      case RangePolicy::error:
        throw LawRangeError(delta, delta_min_, delta_max_);
      case RangePolicy::clamp:
        return above ? delta_max_ : delta;  // below δ_min: the callers apply the chord
      case RangePolicy::extend:
        return delta;
    }
    return delta;
  }

  // Under "clamp", beyond δ_max the force stays at F(δ_max); below δ_min (only when a law was
  // fitted without the origin) it is the chord F(δ_min)·δ/δ_min, so F stays continuous and 0 at 0.
  double BoundedPowerLaw::force(const double delta) const
  {
    const double d = checked(delta);
    if (policy_ == RangePolicy::clamp && delta > 0.0 && delta < delta_min_)
      return law_.force(delta_min_) * delta / delta_min_;
    return law_.force(d);
  }

  double BoundedPowerLaw::stiffness(const double delta) const
  {
    const double d = checked(delta);
    if (policy_ == RangePolicy::clamp && delta > delta_max_)
      return 0.0;
    if (policy_ == RangePolicy::clamp && delta > 0.0 && delta < delta_min_)
      return law_.force(delta_min_) / delta_min_;
    return law_.stiffness(d);
  }

  double BoundedPowerLaw::energy(const double delta) const
  {
    const double d = checked(delta);
    if (policy_ == RangePolicy::clamp && delta > delta_max_)
      return law_.energy(delta_max_) + law_.force(delta_max_) * (delta - delta_max_);
    if (policy_ == RangePolicy::clamp && delta > 0.0 && delta < delta_min_)
      return 0.5 * law_.force(delta_min_) * delta * delta / delta_min_;
    return law_.energy(d);
  }
} // namespace clearjoint::laws
