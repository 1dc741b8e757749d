#include "fe_stage/material/j2_plasticity.h"

#include "common/error.h"

#include <cmath>
#include <limits>

namespace clearjoint::fe
{
  namespace
  {
    const double sqrt_3_2 = std::sqrt(1.5);

    Eigen::Matrix3d deviator(const Eigen::Matrix3d &a)
    {
      return a - (a.trace() / 3.0) * Eigen::Matrix3d::Identity();
    }

    /// σ_y on table segment k (k = n_points − 1: the tail), evaluated at α. Used instead of
    /// HardeningTable::yield_stress inside the return so the segment is the one the walk is on
    /// even when α sits on a table point up to rounding.
    double sigma_on_segment(const HardeningTable &t, std::size_t k, double alpha, double &H)
    {
      const auto &p = t.points();
      H = t.slope(p[k].eps_p);  // the slope to the right of point k: segment k's
      return p[k].sigma_y + H * (alpha - p[k].eps_p);
    }
  }  // namespace

  double von_mises_stress(const Eigen::Matrix3d &sigma)
  {
    const Eigen::Matrix3d s = deviator(sigma);
    return sqrt_3_2 * std::sqrt(s.cwiseProduct(s).sum());
  }

  Vector6 strain_to_voigt(const Eigen::Matrix3d &eps)
  {
    Vector6 e;
    e << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(1, 2), 2 * eps(0, 2), 2 * eps(0, 1);
    return e;
  }

  Eigen::Matrix3d voigt_to_strain(const Vector6 &e)
  {
    Eigen::Matrix3d m;
    m << e(0), e(5) / 2, e(4) / 2,  //
      e(5) / 2, e(1), e(3) / 2,     //
      e(4) / 2, e(3) / 2, e(2);
    return m;
  }

  Vector6 stress_to_voigt(const Eigen::Matrix3d &s)
  {
    Vector6 v;
    v << s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1);
    return v;
  }

  Eigen::Matrix3d voigt_to_stress(const Vector6 &v)
  {
    Eigen::Matrix3d m;
    m << v(0), v(5), v(4),  //
      v(5), v(1), v(3),     //
      v(4), v(3), v(2);
    return m;
  }

  J2Plasticity::J2Plasticity(const double E, const double nu, HardeningTable hardening,
                             const std::string &key_path, const std::string &file)
    : E_(E)
    , nu_(nu)
    , table_(std::move(hardening))
  {
    if (!(std::isfinite(E) && E > 0))
      throw InputError(file, key_path + ".E", format_value(E), "> 0 Pa");
    if (!(std::isfinite(nu) && nu > -1.0 && nu < 0.5))
      throw InputError(file, key_path + ".nu", format_value(nu), "(-1, 0.5)");
    K_ = E / (3.0 * (1.0 - 2.0 * nu));
    G_ = E / (2.0 * (1.0 + nu));
  }

  Matrix6 J2Plasticity::elastic_tangent() const
  {
    Matrix6 C = Matrix6::Zero();
    for (int I = 0; I < 3; ++I)
      for (int J = 0; J < 3; ++J)
        C(I, J) = K_ + 2.0 * G_ * ((I == J ? 1.0 : 0.0) - 1.0 / 3.0);
    for (int I = 3; I < 6; ++I)
      C(I, I) = G_;  // 2G·½ on the engineering shear strain
    return C;
  }

  double J2Plasticity::elastic_energy(const Eigen::Matrix3d &eps, const J2State &state) const
  {
    const Eigen::Matrix3d e = eps - state.eps_p;
    const double tr = e.trace();
    const Eigen::Matrix3d d = deviator(e);
    return 0.5 * K_ * tr * tr + G_ * d.cwiseProduct(d).sum();
  }

  J2Response J2Plasticity::evaluate(const Eigen::Matrix3d &eps, J2History &history) const
  {
    J2Response out;
    const J2State &n = history.committed;
    if (!eps.allFinite())
      {
        out.status.converged = false;
        out.status.residual = std::numeric_limits<double>::quiet_NaN();
        return out;
      }
    const Eigen::Matrix3d eps_e = eps - n.eps_p;
    const double tr = eps_e.trace();
    const Eigen::Matrix3d s_tr = 2.0 * G_ * deviator(eps_e);
    const double s_norm = std::sqrt(s_tr.cwiseProduct(s_tr).sum());
    const double q_tr = sqrt_3_2 * s_norm;
    const double sy_n = table_.yield_stress(n.alpha);

    // Elastic unless the trial stress is outside the yield surface by more than round-off
    // (1e-12 relative): re-evaluating a converged plastic state must not start a new return.
    if (q_tr - sy_n <= 1e-12 * sy_n)
      {
        history.trial = n;
        out.stress = K_ * tr * Eigen::Matrix3d::Identity() + s_tr;
        out.tangent = elastic_tangent();
        return out;
      }

    // Return: Newton on f(Δγ) = q* − 3GΔγ − σ_y(α_n + Δγ), steps clamped to segment ends.
    const int max_iter = static_cast<int>(table_.n_points()) + extra_iterations;
    std::size_t k = table_.segment(n.alpha);
    double dg = 0.0;
    double H = 0.0;
    double r = 0.0;
    int it = 0;
    bool done = false;
    while (it < max_iter && !done)
      {
        ++it;
        r = q_tr - 3.0 * G_ * dg - sigma_on_segment(table_, k, n.alpha + dg, H);
        const double step = r / (3.0 * G_ + H);
        const double end = table_.segment_end(k) - n.alpha;  // Δγ at the end of segment k
        if (dg + step <= end)
          {
            dg += step;
            done = true;
          }
        else
          {
            dg = end;  // the root lies beyond this table point
            ++k;
          }
      }
    r = q_tr - 3.0 * G_ * dg - sigma_on_segment(table_, k, n.alpha + dg, H);
    out.status.iterations = it;
    out.status.residual = std::abs(r);
    // Inside one segment the step is exact up to rounding of numbers of size q*; 1e-10·q*
    // leaves room for a few roundings while catching a wrong segment or a failed walk.
    out.status.converged = done && std::isfinite(dg) && std::abs(r) <= 1e-10 * q_tr;
    if (!out.status.converged)
      return out;

    const Eigen::Matrix3d nn = s_tr / s_norm;
    const Eigen::Matrix3d deps_p = sqrt_3_2 * dg * nn;
    history.trial.eps_p = n.eps_p + deps_p;
    history.trial.alpha = n.alpha + dg;
    out.stress = K_ * tr * Eigen::Matrix3d::Identity() + s_tr - 2.0 * G_ * deps_p;
    out.plastic = true;
    out.delta_alpha = dg;
    out.plastic_work = out.stress.cwiseProduct(deps_p).sum();

    // Consistent tangent (Simo & Hughes Eq. 3.3.10); H is the slope of the final segment.
    const double theta = 1.0 - 3.0 * G_ * dg / q_tr;
    const double theta_bar = 3.0 * G_ / (3.0 * G_ + H) - (1.0 - theta);
    const Vector6 N = stress_to_voigt(nn);  // tensor components, no factor 2
    Matrix6 C = Matrix6::Zero();
    for (int I = 0; I < 3; ++I)
      for (int J = 0; J < 3; ++J)
        C(I, J) = K_ + 2.0 * G_ * theta * ((I == J ? 1.0 : 0.0) - 1.0 / 3.0);
    for (int I = 3; I < 6; ++I)
      C(I, I) = G_ * theta;
    C -= 2.0 * G_ * theta_bar * N * N.transpose();
    out.tangent = C;
    return out;
  }
}  // namespace clearjoint::fe
