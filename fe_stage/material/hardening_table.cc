#include "fe_stage/material/hardening_table.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace clearjoint::fe
{
  namespace
  {
    std::string entry(const std::string &key_path, std::size_t i, int column)
    {
      return key_path + "[" + std::to_string(i) + "][" + std::to_string(column) + "]";
    }
  }  // namespace

  HardeningTable::HardeningTable(std::vector<HardeningPoint> points, const std::string &key_path,
                                 const std::string &file, const Beyond beyond)
    : points_(std::move(points))
    , beyond_(beyond)
    , tail_slope_(0.0)
  {
    if (points_.empty())
      throw InputError(
        file, key_path, "[]",
        "a list of at least one [eps_p, sigma_y] point (eps_p in [-], sigma_y in Pa)");
    for (std::size_t i = 0; i < points_.size(); ++i)
      {
        const HardeningPoint &p = points_[i];
        if (!std::isfinite(p.eps_p))
          throw InputError(file, entry(key_path, i, 0), format_value(p.eps_p),
                           "a finite plastic strain >= 0 [-]");
        if (!std::isfinite(p.sigma_y))
          throw InputError(file, entry(key_path, i, 1), format_value(p.sigma_y),
                           "a finite yield stress > 0 Pa");
        if (i == 0 && p.eps_p != 0.0)
          throw InputError(file, entry(key_path, i, 0), format_value(p.eps_p),
                           "0 (the table must start at zero plastic strain)");
        if (i > 0 && !(p.eps_p > points_[i - 1].eps_p))
          throw InputError(file, entry(key_path, i, 0), format_value(p.eps_p),
                           "> " + format_value(points_[i - 1].eps_p) +
                             " (plastic strains strictly increasing)");
        if (!(p.sigma_y > 0.0))
          throw InputError(file, entry(key_path, i, 1), format_value(p.sigma_y), "> 0 Pa");
        if (i > 0 && p.sigma_y < points_[i - 1].sigma_y)
          throw InputError(file, entry(key_path, i, 1), format_value(p.sigma_y),
                           ">= " + format_value(points_[i - 1].sigma_y) +
                             " Pa (yield stresses non-decreasing: no softening)");
      }
    const std::size_t n = points_.size();
    if (beyond_ == Beyond::extend_last_segment && n >= 2)
      tail_slope_ = (points_[n - 1].sigma_y - points_[n - 2].sigma_y) /
                    (points_[n - 1].eps_p - points_[n - 2].eps_p);
  }

  HardeningTable HardeningTable::spec_default()
  {
    // SPEC §2: σ_y = 168.2 + 280.25·ε_p MPa at ε_p = 0, 0.1, …, 1.0. The strains are formed as
    // i/10 (not by summing 0.1) so that the last one is exactly 1.0.
    std::vector<HardeningPoint> p;
    for (int i = 0; i <= 10; ++i)
      {
        const double e = i / 10.0;
        p.push_back({e, (168.2 + 280.25 * e) * 1e6});
      }
    return HardeningTable(std::move(p), "material.hardening");
  }

  std::size_t HardeningTable::segment(const double eps_p) const
  {
    if (!(eps_p >= 0.0))
      throw std::invalid_argument("HardeningTable: equivalent plastic strain " +
                                  format_value(eps_p) + " is not >= 0");
    // First point with ε > eps_p; the segment starts one before it.
    const auto it = std::upper_bound(points_.begin(), points_.end(), eps_p,
                                     [](double e, const HardeningPoint &p) { return e < p.eps_p; });
    return static_cast<std::size_t>(it - points_.begin()) - 1;
  }

  double HardeningTable::segment_end(const std::size_t k) const
  {
    return k + 1 < points_.size() ? points_[k + 1].eps_p : std::numeric_limits<double>::infinity();
  }

  double HardeningTable::slope(const double eps_p) const
  {
    const std::size_t k = segment(eps_p);
    if (k + 1 == points_.size())
      return tail_slope_;
    return (points_[k + 1].sigma_y - points_[k].sigma_y) /
           (points_[k + 1].eps_p - points_[k].eps_p);
  }

  double HardeningTable::yield_stress(const double eps_p) const
  {
    const std::size_t k = segment(eps_p);
    return points_[k].sigma_y + slope(eps_p) * (eps_p - points_[k].eps_p);
  }
}  // namespace clearjoint::fe
