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

    /// The weight w of a point's residual (F_fit − F)/w: 1 N, or its force for relative.
    double weight_of(const double force, const Weighting weighting)
    {
      return weighting == Weighting::relative ? force : 1.0;
    }

    /// The points that are fitted, and how many origin rows (0, 0) were left out.
    struct FitPoints
    {
      std::vector<double> delta, force;  ///< [m], [N]
      unsigned int n_origin_rows_skipped = 0;
    };

    /// Checks every row (finite, δ ≥ 0, F ≥ 0, F = 0 at δ = 0, F > 0 for relative weighting
    /// where fitted) and keeps those in the fit range, without the origin rows.
    FitPoints select_fit_points(const std::vector<double> &delta_all,
                                const std::vector<double> &force_all, const FitOptions &options)
    {
      const std::string &src = options.source;
      FitPoints points;
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
          ++points.n_origin_rows_skipped;
          continue;
        }
        if (d == 0.0)
          bad_data(src, row, "delta = 0 m with force " + format_value(f) + " N",
                   "force 0 at delta 0 (F = K*delta^n passes through the origin)");
        if (d < options.range_min || d > options.range_max)
          continue;
        if (options.weighting == Weighting::relative && f == 0.0)
          bad_data(src, row + ", column 'force'", "0", "> 0 N for relative weighting");
        points.delta.push_back(d);
        points.force.push_back(f);
      }
      return points;
    }

    /// Two parameters need at least 3 points, forces that vary and two distinct δ.
    void check_points_determine_the_law(const FitPoints &points, const std::string &src)
    {
      const std::vector<double> &delta = points.delta, &force = points.force;
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
    }

    /// (K, n) to start from: --start, or the log–log fit; K > 0 and both finite.
    std::pair<double, double> checked_start(const FitPoints &points, const FitOptions &options)
    {
      const auto start = options.start ? *options.start : log_log_start(points.delta, points.force);
      if (!(start.first > 0) || !std::isfinite(start.first) || !std::isfinite(start.second))
        throw InputError("", "--start", format_value(start.first) + "," + format_value(start.second),
                         "K > 0 and finite n");
      return start;
    }

    /// Covariance of the scaled parameters (k, n): (JᵀJ)⁻¹, not yet scaled by s².
    struct ParameterCovariance
    {
      double kk, nn, kn;
    };

    /// The least-squares problem over (k, n) with K = K_scale·k, K_scale the start's K. Its
    /// residual blocks point at k_ and n_: it stays where it was made.
    class PowerLawLeastSquares
    {
    public:
      PowerLawLeastSquares(const FitPoints &points, const Weighting weighting,
                           const std::pair<double, double> &start)
        : K_scale_(start.first), n_(start.second)
      {
        for (std::size_t i = 0; i < points.delta.size(); ++i)
          problem_.AddResidualBlock(new PowerLawResidual(points.delta[i], points.force[i],
                                                         weight_of(points.force[i], weighting),
                                                         K_scale_),
                                    nullptr, &k_, &n_);
      }
      PowerLawLeastSquares(const PowerLawLeastSquares &) = delete;
      PowerLawLeastSquares &operator=(const PowerLawLeastSquares &) = delete;

      /// Solves to tight tolerances; throws NumericalError when it fails or K ≤ 0.
      ceres::Solver::Summary solve(const std::string &src)
      {
        ceres::Solver::Options solver_options;
        solver_options.linear_solver_type = ceres::DENSE_QR;
        solver_options.max_num_iterations = 500;
        // Tight tolerances: NIST DanWood is certified to 10 digits and we must match 6.
        solver_options.function_tolerance = 1e-15;
        solver_options.gradient_tolerance = 1e-15;
        solver_options.parameter_tolerance = 1e-14;
        solver_options.logging_type = ceres::SILENT;
        ceres::Solver::Summary summary;
        ceres::Solve(solver_options, &problem_, &summary);
        if (!summary.IsSolutionUsable() || summary.termination_type == ceres::FAILURE ||
            !std::isfinite(k_) || !std::isfinite(n_))
          throw NumericalError("the power-law fit of " + src + " did not converge: " +
                               summary.BriefReport());
        if (!(K() > 0.0))
          throw NumericalError("the power-law fit of " + src + " converged to K = " +
                               format_value(K()) +
                               " N/m^n <= 0; the data do not follow F = K*delta^n");
        return summary;
      }

      /// At the solution, from Ceres; throws NumericalError when the Jacobian is rank-deficient.
      ParameterCovariance compute_covariance(const std::string &src)
      {
        ceres::Covariance::Options cov_options;
        cov_options.algorithm_type = ceres::DENSE_SVD;
        ceres::Covariance covariance(cov_options);
        const std::vector<std::pair<const double *, const double *>> blocks = {
          {&k_, &k_}, {&n_, &n_}, {&k_, &n_}};
        if (!covariance.Compute(blocks, &problem_))
          throw NumericalError("the covariance of the fit of " + src +
                               " could not be computed (Jacobian rank-deficient at the solution)");
        ParameterCovariance c;
        covariance.GetCovarianceBlock(&k_, &k_, &c.kk);
        covariance.GetCovarianceBlock(&n_, &n_, &c.nn);
        covariance.GetCovarianceBlock(&k_, &n_, &c.kn);
        return c;
      }

      double K() const { return K_scale_ * k_; }  ///< [N/m^n]
      double n() const { return n_; }             ///< [1]
      double K_scale() const { return K_scale_; }

    private:
      double K_scale_, k_ = 1.0, n_;
      ceres::Problem problem_;
    };

    /// Residuals F − F_fit, their sums of squares (weighted and not), R², the largest
    /// relative residual and the residual standard deviation s = √(SSR_w / (N − 2)); returns
    /// the residual variance s².
    double add_residual_statistics(const FitPoints &points, const double K, const double n,
                                 const Weighting weighting, laws::FitDiagnostics &d)
    {
      const std::vector<double> &delta = points.delta, &force = points.force;
      const std::size_t N = delta.size();
      const double dof = static_cast<double>(N) - 2.0;
      double ssr_w = 0, ssr = 0, mean = 0;
      for (double f : force)
        mean += f / N;
      double sst = 0;
      for (std::size_t i = 0; i < N; ++i)
      {
        const double fit = K * std::pow(delta[i], n);
        const double r = force[i] - fit;
        const double w = weight_of(force[i], weighting);
        d.residual.push_back(r);
        ssr += r * r;
        ssr_w += (r / w) * (r / w);
        sst += (force[i] - mean) * (force[i] - mean);
        if (force[i] > 0)
          d.max_relative_residual = std::max(d.max_relative_residual, std::abs(r) / force[i]);
      }
      d.sum_squared_residuals = ssr_w;
      d.r_squared = 1.0 - ssr / sst;
      const double s2 = dof > 0 ? ssr_w / dof : 0.0;
      d.residual_std = std::sqrt(s2);
      return s2;
    }

    /// Standard errors, K–n correlation and 95 % intervals (Student t, N − 2 degrees of
    /// freedom): the covariance scaled by the residual variance s2 and by K_scale for K.
    void add_parameter_uncertainty(const ParameterCovariance &c, const double s2, const double K,
                                   const double n, const double K_scale,
                                   laws::FitDiagnostics &d)
    {
      const double dof = static_cast<double>(d.n_points) - 2.0;
      const double var_K = c.kk * K_scale * K_scale * s2, var_n = c.nn * s2;
      d.K_std_error = std::sqrt(var_K);
      d.n_std_error = std::sqrt(var_n);
      d.correlation_K_n = (var_K > 0 && var_n > 0) ? c.kn * K_scale * s2 / std::sqrt(var_K * var_n)
                                                   : 0.0;
      const double t = dof > 0 ? student_t_quantile(0.975, dof) : 0.0;
      d.K_ci95_low = K - t * d.K_std_error;
      d.K_ci95_high = K + t * d.K_std_error;
      d.n_ci95_low = n - t * d.n_std_error;
      d.n_ci95_high = n + t * d.n_std_error;
    }

    /// Condition number of the column-scaled Jacobian of the weighted residuals: how well the
    /// data pin K and n apart, independent of their units (1 = orthogonal columns).
    double jacobian_condition_number(const FitPoints &points, const double K, const double n,
                                     const Weighting weighting)
    {
      const std::size_t N = points.delta.size();
      Eigen::MatrixXd J(N, 2);
      for (std::size_t i = 0; i < N; ++i)
      {
        const double delta = points.delta[i], w = weight_of(points.force[i], weighting);
        J(i, 0) = std::pow(delta, n) / w;
        J(i, 1) = K * std::pow(delta, n) * std::log(delta) / w;
      }
      Eigen::MatrixXd Js = J;
      for (int c = 0; c < 2; ++c)
        Js.col(c) /= J.col(c).norm();
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js);
      const auto sv = svd.singularValues();
      return sv(1) > 0 ? sv(0) / sv(1) : std::numeric_limits<double>::infinity();
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
    FitPoints points = select_fit_points(delta_all, force_all, options);
    result.n_origin_rows_skipped = points.n_origin_rows_skipped;
    check_points_determine_the_law(points, src);
    result.start_used = checked_start(points, options);

    PowerLawLeastSquares least_squares(points, options.weighting, result.start_used);
    const ceres::Solver::Summary summary = least_squares.solve(src);
    const ParameterCovariance covariance = least_squares.compute_covariance(src);
    const double K = least_squares.K(), n = least_squares.n();

    laws::FitDiagnostics &d = result.diagnostics;
    d.n_points = points.delta.size();
    d.weighting = options.weighting == Weighting::relative ? "relative" : "absolute";
    const auto [d_min, d_max] = std::minmax_element(points.delta.begin(), points.delta.end());
    d.fit_delta_min = *d_min;
    d.fit_delta_max = *d_max;
    const double s2 = add_residual_statistics(points, K, n, options.weighting, d);
    add_parameter_uncertainty(covariance, s2, K, n, least_squares.K_scale(), d);
    d.condition_number = jacobian_condition_number(points, K, n, options.weighting);
    d.solver_summary = summary.BriefReport();
    d.delta = std::move(points.delta);
    d.force = std::move(points.force);

    result.law = laws::PowerLaw{K, n};
    return result;
  }
} // namespace clearjoint::fit
