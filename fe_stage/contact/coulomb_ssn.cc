#include "fe_stage/contact/coulomb_ssn.h"

#include "common/error.h"

#include <cmath>
#include <stdexcept>

namespace clearjoint::fe
{
  void check_coulomb_parameters(const CoulombParameters &p, const std::string &key_path,
                                const std::string &file)
  {
    if (!(std::isfinite(p.mu) && p.mu >= 0.0))
      throw InputError(file, key_path + ".mu", format_value(p.mu), ">= 0 (finite)",
                       "Coulomb friction coefficient");
    if (!(std::isfinite(p.c_n) && p.c_n > 0.0))
      throw InputError(file, key_path + ".c_n", format_value(p.c_n), "> 0 (finite)");
    if (!(std::isfinite(p.c_t) && p.c_t > 0.0))
      throw InputError(file, key_path + ".c_t", format_value(p.c_t), "> 0 (finite)");
  }

  FrictionState coulomb_state(const double xi, const double w_norm, const double mu,
                              const double band)
  {
    if (!(xi > band))  // (a NaN ξ is no contact: the caller's checks name it)
      return FrictionState::inactive;
    // Stick needs a disc of positive radius: at μ = 0 every active node slides freely.
    const double r = mu * xi;
    return r > 0.0 && w_norm <= r + band ? FrictionState::stick : FrictionState::slip;
  }

  bool keeps_or_decides_stick(const double xi, const double w_norm, const double mu,
                              const double band, const bool was_stick, const double edge)
  {
    const bool stick = coulomb_state(xi, w_norm, mu, band) == FrictionState::stick;
    // (a disc of positive radius, as coulomb_state's stick needs)
    if (stick != was_stick && w_norm > 0.0 && mu * xi > 0.0 && std::abs(w_norm - mu * xi) <= edge)
      return was_stick;
    return stick;
  }

  NodeNcp evaluate_coulomb_ncp(const double lambda_n, const Eigen::Vector2d &lambda_t,
                               const double gap, const Eigen::Vector2d &slip_t,
                               const CoulombParameters &p)
  {
    if (!(std::isfinite(lambda_n) && lambda_t.allFinite() && std::isfinite(gap) &&
          slip_t.allFinite()))
      throw std::invalid_argument("evaluate_coulomb_ncp: non-finite multiplier, gap or slip");

    const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
    NodeNcp out;
    out.jacobian.setZero();
    const double xi = lambda_n - p.c_n * gap;
    const Eigen::Vector2d w = lambda_t - p.c_t * slip_t;
    const double wn = w.norm();
    const double r = p.mu * xi;  // disc radius when active

    out.state = coulomb_state(xi, wn, p.mu);
    if (out.state == FrictionState::inactive)
      {
        out.r_n = lambda_n;
        out.r_t = lambda_t;
        out.jacobian(0, col_lambda_n) = 1.0;
        out.jacobian.block<2, 2>(1, col_lambda_t1) = I;
        return out;  // both forms: λ = 0 on inactive nodes
      }

    out.r_n = p.c_n * gap;
    out.jacobian(0, col_gap) = p.c_n;
    if (out.state == FrictionState::stick)
      {
        out.r_t = p.c_t * slip_t;
        out.jacobian.block<2, 2>(1, col_slip_t1) = p.c_t * I;
      }
    else
      {
        // wn > r ≥ 0 here, except μ = 0 with w = 0, where the direction is multiplied by 0.
        const Eigen::Vector2d w_hat = wn > 0.0 ? Eigen::Vector2d(w / wn) : Eigen::Vector2d::Zero();
        const Eigen::Matrix2d D = wn > 0.0 ?
                                    Eigen::Matrix2d((r / wn) * (I - w_hat * w_hat.transpose())) :
                                    Eigen::Matrix2d::Zero();
        out.r_t = lambda_t - r * w_hat;
        out.jacobian.block<2, 1>(1, col_lambda_n) = -p.mu * w_hat;
        out.jacobian.block<2, 1>(1, col_gap) = p.mu * p.c_n * w_hat;
        out.jacobian.block<2, 2>(1, col_lambda_t1) = I - D;
        out.jacobian.block<2, 2>(1, col_slip_t1) = p.c_t * D;
      }

    if (p.form == CoulombNcpForm::hsw)
      {
        // C_T = m R_T with m = max(μξ, |w|): μξ on stick nodes, |w| on slip nodes.
        Eigen::Matrix<double, 1, 6> dm = Eigen::Matrix<double, 1, 6>::Zero();
        double m;
        if (out.state == FrictionState::stick)
          {
            m = r;
            dm(col_lambda_n) = p.mu;
            dm(col_gap) = -p.mu * p.c_n;
          }
        else
          {
            m = wn;
            if (wn > 0.0)
              {
                const Eigen::Vector2d w_hat = w / wn;
                dm.segment<2>(col_lambda_t1) = w_hat.transpose();
                dm.segment<2>(col_slip_t1) = -p.c_t * w_hat.transpose();
              }
          }
        out.jacobian.bottomRows<2>() = m * out.jacobian.bottomRows<2>() + out.r_t * dm;
        out.r_t *= m;
      }
    return out;
  }
}  // namespace clearjoint::fe
