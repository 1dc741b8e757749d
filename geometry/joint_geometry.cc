#include "geometry/joint_geometry.h"

#include "common/error.h"

#include <cmath>

namespace clearjoint::geometry
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;

    void require(bool ok, const std::string &file, const std::string &key, double value,
                 const std::string &allowed, const std::string &detail = "")
    {
      if (!ok)
        throw InputError(file, key, format_value(value), allowed, detail);
    }
  } // namespace

  double degrees(const double radians) { return radians * 180.0 / pi; }
  double radians(const double degrees) { return degrees * pi / 180.0; }

  JointGeometry JointGeometry::from_journal(const double R_B, const double t_B, const double L_B,
                                            const double R_J, const double L_J,
                                            const std::string &file,
                                            const std::string &key_prefix)
  {
    const std::string p = key_prefix.empty() ? "" : key_prefix + ".";
    require(std::isfinite(R_J) && R_J > 0.0, file, p + "R_J", R_J, "> 0 m");
    require(std::isfinite(L_J) && L_J > 0.0, file, p + "L_J", L_J, "> 0 m");
    require(!(R_J >= R_B), file, p + "R_J", R_J, "< R_B = " + format_value(R_B) + " m",
            "journal larger than bearing: no radial clearance");
    require(!(L_J >= L_B), file, p + "L_J", L_J, "< L_B = " + format_value(L_B) + " m",
            "journal longer than bearing: no axial clearance");
    JointGeometry g{R_B, t_B, L_B, R_B - R_J, 0.5 * (L_B - L_J)};
    g.validate(file, key_prefix);
    return g;
  }

  void JointGeometry::validate(const std::string &file, const std::string &key_prefix) const
  {
    const std::string p = key_prefix.empty() ? "" : key_prefix + ".";
    require(std::isfinite(R_B) && R_B > 0.0, file, p + "R_B", R_B, "> 0 m");
    require(std::isfinite(t_B) && t_B > 0.0, file, p + "t_B", t_B, "> 0 m");
    require(std::isfinite(L_B) && L_B > 0.0, file, p + "L_B", L_B, "> 0 m");
    require(std::isfinite(c_r) && c_r > 0.0, file, p + "c_r", c_r,
            "0 < c_r < R_B = " + format_value(R_B) + " m",
            c_r < 0.0 ? "negative radial clearance: journal larger than bearing" : "");
    require(c_r < R_B, file, p + "c_r", c_r, "0 < c_r < R_B = " + format_value(R_B) + " m",
            "journal radius R_J = R_B - c_r would be <= 0");
    require(std::isfinite(c_a) && c_a > 0.0, file, p + "c_a", c_a,
            "0 < c_a < L_B/2 = " + format_value(0.5 * L_B) + " m",
            "journal length L_J = L_B - 2 c_a would be >= L_B");
    require(c_a < 0.5 * L_B, file, p + "c_a", c_a,
            "0 < c_a < L_B/2 = " + format_value(0.5 * L_B) + " m",
            "journal length L_J = L_B - 2 c_a would be <= 0");
  }

  std::optional<double> theta_max(const JointGeometry &geometry)
  {
    geometry.validate();
    const double c = geometry.c_r, R = geometry.R_J(), H = 0.5 * geometry.L_J();
    const auto f = [&](double t) { return c + R * (1.0 - std::cos(t)) - H * std::sin(t); };
    const auto df = [&](double t) { return R * std::sin(t) - H * std::cos(t); };

    // f(0) = c > 0; f is decreasing on [0, θ*] with its minimum R_B − D at θ*.
    const double theta_star = std::atan2(H, R);
    const double f_star = f(theta_star);
    if (f_star > 0.0)
      return std::nullopt;  // D < R_B: no contact of opposite rims at any tilt
    if (f_star == 0.0)
      return theta_star;    // grazing: double root

    double lo = 0.0, hi = theta_star;  // f(lo) > 0 > f(hi)
    double t = 0.5 * (lo + hi);
    for (int it = 0; it < 200; ++it)
    {
      const double ft = f(t);
      if (ft > 0.0)
        lo = t;
      else if (ft < 0.0)
        hi = t;
      else
        return t;
      const double d = df(t);
      double next = (d != 0.0) ? t - ft / d : 0.5 * (lo + hi);
      if (!(next > lo && next < hi))
        next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
      const double step = std::abs(next - t);
      t = next;
      if (step <= 1e-15 || hi - lo <= 1e-15)
        return t;
    }
    throw NumericalError("theta_max: Eq. 3 did not converge in 200 iterations (bracket [" +
                         format_value(lo) + ", " + format_value(hi) + "] rad)");
  }

  void check_tilt(const JointGeometry &geometry, const double theta_rad, const std::string &file,
                  const std::string &key_path)
  {
    const auto limit = theta_max(geometry);
    const std::string where = "R_B = " + format_value(geometry.R_B) +
                              " m, c_r = " + format_value(geometry.c_r) +
                              " m, L_B = " + format_value(geometry.L_B) +
                              " m, c_a = " + format_value(geometry.c_a) + " m";
    if (!std::isfinite(theta_rad) || theta_rad < 0.0)
      throw InputError(file, key_path, format_value(degrees(theta_rad)) + " deg",
                       limit ? "0 <= theta <= theta_max = " + format_value(degrees(*limit)) + " deg"
                             : "0 <= theta < 90 deg");
    if (limit)
    {
      // Relative 1e-12: only round-off of the computed θ_max passed back in is forgiven.
      if (theta_rad > *limit * (1.0 + 1e-12))
        throw InputError(file, key_path, format_value(degrees(theta_rad)) + " deg",
                         "0 <= theta <= theta_max = " + format_value(degrees(*limit)) + " deg",
                         "theta > theta_max from Eq. 3 (" + where +
                           "): the tilted journal would pass through the bearing");
    }
    else if (theta_rad >= 0.5 * pi)
      throw InputError(file, key_path, format_value(degrees(theta_rad)) + " deg",
                       "0 <= theta < 90 deg",
                       "Eq. 3 has no root for " + where + " (the journal is shorter than its turning "
                       "diameter), so only the 90 deg limit applies");
  }
} // namespace clearjoint::geometry
