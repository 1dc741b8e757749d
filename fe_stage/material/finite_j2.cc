#include "fe_stage/material/finite_j2.h"

#include "fe_stage/material/log_strain.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace clearjoint::fe
{
  namespace
  {
    std::string describe(const char *what, const double value)
    {
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, "%s%.6g", what, value);
      return buffer;
    }

    FiniteJ2Response failed(std::string reason)
    {
      FiniteJ2Response out;
      out.status.converged = false;
      out.status.reason = std::move(reason);
      return out;
    }
  }  // namespace

  FiniteJ2::FiniteJ2(J2Plasticity small_strain)
    : law_(std::move(small_strain))
  {}

  FiniteJ2Response FiniteJ2::evaluate(const Eigen::Matrix3d &F, J2History &history) const
  {
    return evaluate_displacement_gradient(F - Eigen::Matrix3d::Identity(), history);
  }

  FiniteJ2Response FiniteJ2::evaluate_displacement_gradient(const Eigen::Matrix3d &grad_u,
                                                            J2History &history) const
  {
    if (!grad_u.allFinite())
      return failed("deformation gradient not finite (NaN or Inf)");
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad_u;
    const double J = F.determinant();
    if (!(J > 0.0))
      return failed(describe("det F = ", J) + " <= 0 (inverted or collapsed element)");

    const Eigen::Matrix3d green_lagrange =
      0.5 * (grad_u + grad_u.transpose() + grad_u.transpose() * grad_u);
    const LogStrain log_strain = compute_log_strain(green_lagrange);
    if (!log_strain.valid)
      return failed(
        describe("C = F^T F not positive definite or not finite in floating point (det F = ", J) +
        ")");

    const J2State previous_trial = history.trial;  // restored if the result is not finite
    const J2Response r = law_.evaluate(log_strain.hencky, history);
    FiniteJ2Response out;
    out.status.return_map = r.status;
    if (!r.status.converged)
      {
        out.status.converged = false;
        out.status.reason = describe("return map not converged: |f| = ", r.status.residual) +
                            describe(" Pa after ", r.status.iterations) + " iterations";
        return out;
      }

    const Matrix6 &P = log_strain.projection;
    out.hencky_strain = log_strain.hencky;
    out.hencky_stress = r.stress;
    out.stress_pk2 = voigt_to_stress(P.transpose() * stress_to_voigt(r.stress));
    out.tangent = P.transpose() * r.tangent * P + contract_second_derivative(log_strain, r.stress);
    out.stress_pk1 = F * out.stress_pk2;
    out.kirchhoff = out.stress_pk1 * F.transpose();
    out.cauchy = out.kirchhoff / J;
    out.J = J;
    out.plastic = r.plastic;
    out.delta_alpha = r.delta_alpha;
    out.plastic_work = r.plastic_work;

    // Finite input can still overflow (|F| ~ 1e154 …); report it rather than pass on Inf/NaN.
    if (!(out.stress_pk1.allFinite() && out.tangent.allFinite()))
      {
        history.trial = previous_trial;
        return failed("stress or tangent not finite (deformation beyond the range of double)");
      }
    return out;
  }

  double FiniteJ2::elastic_energy(const Eigen::Matrix3d &grad_u, const J2State &state) const
  {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + grad_u;
    if (!grad_u.allFinite() || !(F.determinant() > 0.0))
      return std::numeric_limits<double>::quiet_NaN();
    const LogStrain log_strain =
      compute_log_strain(0.5 * (grad_u + grad_u.transpose() + grad_u.transpose() * grad_u));
    if (!log_strain.valid)
      return std::numeric_limits<double>::quiet_NaN();
    return law_.elastic_energy(log_strain.hencky, state);
  }
}  // namespace clearjoint::fe
