#include "fit_stage/power_law_fitter.h"

#include "common/error.h"
#include "fit_stage/student_t.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace clearjoint::fit
{
  namespace
  {
    // One data point's residual (K·δ^n − F)/w, with K = K_scale·k so that both parameters
    // Ceres sees are of order one (K is ~1e8 N/m^n for our contact data, n ~ 1).
    struct PowerLawResidual final : ceres::SizedCostFunction<1, 1, 1>
    {
      PowerLawResidual(double delta, double force, double weight, double K_scale)
        : delta_(delta), force_(force), inv_w_(1.0 / weight), K_scale_(K_scale)
      {}

      bool Evaluate(const double *const *p, double *residual, double **jacobian) const override
      {
        const double K = K_scale_ * p[0][0], n = p[1][0];
        const double dn = std::pow(delta_, n);
        residual[0] = (K * dn - force_) * inv_w_;
        if (jacobian)
        {
          if (jacobian[0])
            jacobian[0][0] = K_scale_ * dn * inv_w_;
          if (jacobian[1])
            jacobian[1][0] = K * dn * std::log(delta_) * inv_w_;
        }
        return std::isfinite(residual[0]);
      }

      double delta_, force_, inv_w_, K_scale_;
    };

    [[noreturn]] void bad_data(const std::string &source, const std::string &what,
                               const std::string &value, const std::string &allowed)
    {
      throw InputError(source, what, value, allowed);
    }
  } // namespace

  std::pair<double, double> log_log_start(const std::vector<double> &delta,
                                          const std::vector<double> &force)
  {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::size_t m = 0;
    for (std::size_t i = 0; i < delta.size(); ++i)
      if (delta[i] > 0 && force[i] > 0)
      {
        const double x = std::log(delta[i]), y = std::log(force[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
      }
    const double denom = m * sxx - sx * sx;
    if (m < 2 || !(std::abs(denom) > 0))
      throw InputError("the log–log start needs at least 2 points with distinct delta > 0 and "
                       "force > 0; give --start K,n");
    const double n = (m * sxy - sx * sy) / denom;
    const double lnK = (sy - n * sx) / m;
    return {std::exp(lnK), n};
  }

  FitResult fit_power_law(const std::vector<double> &delta_all,
                          const std::vector<double> &force_all, const FitOptions &options)
  {
    const std::string &src = options.source;
    if (delta_all.size() != force_all.size())
      throw std::logic_error("fit_power_law: delta and force differ in length");

    FitResult result;
    std::vector<double> delta, force;
    for (std::size_t i = 0; i < delta_all.size(); ++i)
    {
      const double d = delta_all[i], f = force_all[i];
      const std::string row = "row " + std::to_string(i + 1);
      if (!std::isfinite(d))
        bad_data(src, row + ", column 'delta'", format_value(d), "a finite number >= 0 m");
      if (!std::isfinite(f))
        bad_data(src, row + ", column 'force'", format_value(f), "a finite number >= 0 N");
      if (d < 0)
        bad_data(src, row + ", column 'delta'", format_value(d), "[0, inf) m");
      if (f < 0)
        bad_data(src, row + ", column 'force'", format_value(f), "[0, inf) N");
      if (d == 0.0 && f == 0.0)
      {
        ++result.n_origin_rows_skipped;
        continue;
      }
      if (d == 0.0)
        bad_data(src, row, "delta = 0 m with force " + format_value(f) + " N",
                 "force 0 at delta 0 (F = K*delta^n passes through the origin)");
      if (d < options.range_min || d > options.range_max)
        continue;
      if (options.weighting == Weighting::relative && f == 0.0)
        bad_data(src, row + ", column 'force'", "0", "> 0 N for relative weighting");
      delta.push_back(d);
      force.push_back(f);
    }
    if (delta.size() < 3)
      bad_data(src, "rows", std::to_string(delta.size()) + " points with delta > 0 in the fit range",
               "at least 3 points (2 parameters and a residual)");
    const auto [f_min, f_max] = std::minmax_element(force.begin(), force.end());
    if (*f_max - *f_min <= 1e-12 * std::abs(*f_max))
      bad_data(src, "column 'force'", "constant " + format_value(*f_max) + " N",
               "forces that vary with delta (a constant cannot be fitted by K*delta^n)");
    const auto [d_min, d_max] = std::minmax_element(delta.begin(), delta.end());
    if (*d_max - *d_min <= 1e-12 * *d_max)
      bad_data(src, "column 'delta'", "constant " + format_value(*d_max) + " m",
               "at least two distinct delta values");

    const auto start = options.start ? *options.start : log_log_start(delta, force);
    if (!(start.first > 0) || !std::isfinite(start.first) || !std::isfinite(start.second))
      throw InputError("", "--start", format_value(start.first) + "," + format_value(start.second),
                       "K > 0 and finite n");
    result.start_used = start;

    // Solve.
    const double K_scale = start.first;
    double k = 1.0, n = start.second;
    ceres::Problem problem;
    for (std::size_t i = 0; i < delta.size(); ++i)
    {
      const double w = options.weighting == Weighting::relative ? force[i] : 1.0;
      problem.AddResidualBlock(new PowerLawResidual(delta[i], force[i], w, K_scale), nullptr, &k,
                               &n);
    }
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::DENSE_QR;
    solver_options.max_num_iterations = 500;
    // Tight tolerances: NIST DanWood is certified to 10 digits and we must match 6.
    solver_options.function_tolerance = 1e-15;
    solver_options.gradient_tolerance = 1e-15;
    solver_options.parameter_tolerance = 1e-14;
    solver_options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    if (!summary.IsSolutionUsable() || summary.termination_type == ceres::FAILURE ||
        !std::isfinite(k) || !std::isfinite(n))
      throw NumericalError("the power-law fit of " + src + " did not converge: " +
                           summary.BriefReport());
    const double K = K_scale * k;
    if (!(K > 0.0))
      throw NumericalError("the power-law fit of " + src + " converged to K = " + format_value(K) +
                           " N/m^n <= 0; the data do not follow F = K*delta^n");

    // Covariance of (k, n) from Ceres: (JᵀJ)⁻¹, to be scaled by the residual variance s².
    ceres::Covariance::Options cov_options;
    cov_options.algorithm_type = ceres::DENSE_SVD;
    ceres::Covariance covariance(cov_options);
    const std::vector<std::pair<const double *, const double *>> blocks = {
      {&k, &k}, {&n, &n}, {&k, &n}};
    if (!covariance.Compute(blocks, &problem))
      throw NumericalError("the covariance of the fit of " + src +
                           " could not be computed (Jacobian rank-deficient at the solution)");
    double c_kk, c_nn, c_kn;
    covariance.GetCovarianceBlock(&k, &k, &c_kk);
    covariance.GetCovarianceBlock(&n, &n, &c_nn);
    covariance.GetCovarianceBlock(&k, &n, &c_kn);

    // Diagnostics.
    laws::FitDiagnostics &d = result.diagnostics;
    const std::size_t N = delta.size();
    const double dof = static_cast<double>(N) - 2.0;
    d.n_points = N;
    d.weighting = options.weighting == Weighting::relative ? "relative" : "absolute";
    d.fit_delta_min = *d_min;
    d.fit_delta_max = *d_max;
    d.delta = delta;
    d.force = force;
    double ssr_w = 0, ssr = 0, mean = 0;
    for (double f : force)
      mean += f / N;
    double sst = 0;
    Eigen::MatrixXd J(N, 2);
    for (std::size_t i = 0; i < N; ++i)
    {
      const double fit = K * std::pow(delta[i], n);
      const double r = force[i] - fit;
      const double w = options.weighting == Weighting::relative ? force[i] : 1.0;
      d.residual.push_back(r);
      ssr += r * r;
      ssr_w += (r / w) * (r / w);
      sst += (force[i] - mean) * (force[i] - mean);
      if (force[i] > 0)
        d.max_relative_residual = std::max(d.max_relative_residual, std::abs(r) / force[i]);
      J(i, 0) = std::pow(delta[i], n) / w;
      J(i, 1) = K * std::pow(delta[i], n) * std::log(delta[i]) / w;
    }
    d.sum_squared_residuals = ssr_w;
    d.r_squared = 1.0 - ssr / sst;
    const double s2 = dof > 0 ? ssr_w / dof : 0.0;
    d.residual_std = std::sqrt(s2);
    const double var_K = c_kk * K_scale * K_scale * s2, var_n = c_nn * s2;
    d.K_std_error = std::sqrt(var_K);
    d.n_std_error = std::sqrt(var_n);
    d.correlation_K_n = (var_K > 0 && var_n > 0) ? c_kn * K_scale * s2 / std::sqrt(var_K * var_n)
                                                 : 0.0;
    const double t = dof > 0 ? student_t_quantile(0.975, dof) : 0.0;
    d.K_ci95_low = K - t * d.K_std_error;
    d.K_ci95_high = K + t * d.K_std_error;
    d.n_ci95_low = n - t * d.n_std_error;
    d.n_ci95_high = n + t * d.n_std_error;
    // Condition number of the column-scaled Jacobian: how well the data pin K and n apart,
    // independent of their units (1 = orthogonal columns).
    Eigen::MatrixXd Js = J;
    for (int c = 0; c < 2; ++c)
      Js.col(c) /= J.col(c).norm();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js);
    const auto sv = svd.singularValues();
    d.condition_number = sv(1) > 0 ? sv(0) / sv(1) : std::numeric_limits<double>::infinity();
    d.solver_summary = summary.BriefReport();

    result.law = laws::PowerLaw{K, n};
    return result;
  }
} // namespace clearjoint::fit
