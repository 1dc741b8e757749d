#include "fe_stage/solve/rolling_kinematics.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::fe::rolling
{
  Vec3 rotate_z(const Vec3 &v, const double angle)
  {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]};
  }

  double Motion::delta(const double t) const
  {
    return delta_max * std::clamp(t / ramp_time, 0.0, 1.0);
  }

  Vec3 Motion::centre_fixed(const double t) const { return {0.0, -c_r - delta(t), 0.0}; }

  Vec3 Motion::centre_frame(const double t) const { return rotate_z(centre_fixed(t), -phi(t)); }

  Vec3 journal_surface_step(const Vec3 &c0, const Vec3 &c1, const double R_J, const Vec3 &n,
                            const double delta_psi)
  {
    const Vec3 before = rotate_z(n, -delta_psi);
    Vec3 d;
    for (int k = 0; k < 3; ++k)
      d[k] = (c1[k] + R_J * n[k]) - (c0[k] + R_J * before[k]);
    return d;
  }

  double paper_angle(const Vec3 &U, const double R)
  {
    const double u = std::sqrt(U[0] * U[0] + U[1] * U[1]);  // Eq. 4: the x–y components
    return 2.0 * std::asin(std::min(1.0, 0.5 * u / R));     // Eq. 5 / 6
  }

  double unwrap_paper_angle(const double chord, const bool positive, const double previous)
  {
    const double turn = 2.0 * std::acos(-1.0);
    const double a = positive ? chord : -chord;  // θ ≡ a (mod 2π)
    return a + turn * std::round((previous - a) / turn);
  }

  SlipStages slip_stages(const std::vector<double> &t, const std::vector<double> &v,
                         const double fall_fraction, const double settle_band)
  {
    SlipStages s;
    const std::size_t n = std::min(t.size(), v.size());
    if (n < 3)
      return s;
    std::size_t i_max = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(v[i]) > std::abs(v[i_max]))
        i_max = i;
    s.v_max = std::abs(v[i_max]);
    s.v_final = v[n - 1];
    if (!(s.v_max > 0.0))
      return s;
    // stage (i) ends where the relative speed first falls below fall_fraction of its largest
    // value; if it never does before the end, the stages are not located (the run ended in
    // gross slip, or the slip speed only wanders about its level)
    std::size_t i_fall = n;
    for (std::size_t i = i_max; i < n; ++i)
      if (std::abs(v[i]) < fall_fraction * s.v_max)
        {
          i_fall = i;
          break;
        }
    if (i_fall == n)
      return s;
    // stage (iii) starts after the last step outside the band about the final speed
    std::size_t i_settle = i_fall;
    for (std::size_t i = i_fall; i < n; ++i)
      if (std::abs(v[i] - s.v_final) > settle_band * s.v_max)
        i_settle = i + 1;
    s.end_of_slip = t[i_fall];
    s.settled = t[std::min(i_settle, n - 1)];
    s.found = true;
    return s;
  }

}  // namespace clearjoint::fe::rolling
