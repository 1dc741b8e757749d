// The Hencky strain and its derivatives (fe_stage/material/log_strain.h): E = ½ ln C against
// Eigen's matrix logarithm, the divided differences of ln against long-double quotients on
// both sides of their series thresholds and at coincident arguments, P = ∂E/∂E_GL and
// T : ∂²E/∂E_GL² against central differences for distinct, two equal and three equal
// eigenvalues of C.
#include "fe_stage/material/log_strain.h"

#include <gtest/gtest.h>

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <random>

using namespace clearjoint::fe;

namespace
{
  Eigen::Matrix3d random_rotation(std::mt19937 &rng)
  {
    std::normal_distribution<double> n(0.0, 1.0);
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  }

  /// E_GL = Q diag(mu) Qᵀ with a random rotation Q (so that repeated eigenvalues come with
  /// eigenvectors that are not the coordinate axes).
  Eigen::Matrix3d green_lagrange(std::mt19937 &rng, const Eigen::Vector3d &mu)
  {
    const Eigen::Matrix3d Q = random_rotation(rng);
    return Q * mu.asDiagonal() * Q.transpose();
  }

  /// Long-double references (64-bit mantissa, ε ≈ 1.1e-19): the first difference as
  /// log1p((x − y)/y)/(x − y), x − y exact for doubles this close, accurate to a few 1e-19;
  /// the second as a quotient of those, accurate to ~1e-18/s for a relative spread s.
  long double ref_first(long double x, long double y) { return std::log1p((x - y) / y) / (x - y); }
  long double ref_second(long double x, long double y, long double z)
  {
    return (ref_first(y, z) - ref_first(x, y)) / (z - x);
  }
}  // namespace

TEST(LogStrain, HenckyStrainMatchesMatrixLogarithm)
{
  std::mt19937 rng(30);
  std::uniform_real_distribution<double> u(-0.3, 0.6);
  for (int trial = 0; trial < 20; ++trial)
    {
      const Eigen::Matrix3d egl = green_lagrange(rng, Eigen::Vector3d(u(rng), u(rng), u(rng)));
      const LogStrain ls = compute_log_strain(egl);
      ASSERT_TRUE(ls.valid);
      const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + 2.0 * egl;
      const Eigen::Matrix3d ref = 0.5 * C.log();
      // Two different algorithms (eigen-decomposition and Schur–Padé), both backward stable:
      // agreement to a few ε times |E| ~ 1.
      EXPECT_LT((ls.hencky - ref).cwiseAbs().maxCoeff(), 1e-14) << "trial " << trial;
    }
  // Small strains keep their digits: E_GL = 1e-9 diag(1, 2, 3) gives E = E_GL − E_GL² + …
  const Eigen::Matrix3d tiny = 1e-9 * Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix();
  const LogStrain ls = compute_log_strain(tiny);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(ls.hencky(a, a), std::log1p(2.0 * tiny(a, a)) / 2, 1e-16 * tiny(a, a));
}

TEST(LogStrain, NotPositiveDefiniteOrNotFinite)
{
  EXPECT_FALSE(compute_log_strain(Eigen::Vector3d(0.1, -0.5, 0.2).asDiagonal().toDenseMatrix())
                 .valid);  // λ = 1 + 2(−0.5) = 0
  EXPECT_FALSE(compute_log_strain(-Eigen::Matrix3d::Identity()).valid);
  Eigen::Matrix3d nan = Eigen::Matrix3d::Zero();
  nan(1, 2) = nan(2, 1) = std::nan("");
  EXPECT_FALSE(compute_log_strain(nan).valid);
}

TEST(LogStrain, DividedDifferencesAcrossTheirSeriesThresholds)
{
  for (const double x : {0.3, 1.0, 4.0})
    {
      // Coincident arguments: the derivatives.
      EXPECT_DOUBLE_EQ(log_divided_difference(x, x), 1.0 / x);
      EXPECT_DOUBLE_EQ(log_second_divided_difference(x, x, x), -0.5 / (x * x));
      // First difference, separations across |u| = 1e-4 (relative gap 2e-4): the series
      // below, artanh above; against the long-double quotient where that is accurate.
      for (const double t : {1e-3, 2.1e-4, 1.9e-4, 1e-2, 0.5, 3.0})
        {
          const double y = x * (1.0 + t);
          EXPECT_NEAR(log_divided_difference(x, y), static_cast<double>(ref_first(x, y)), 2e-15 / x)
            << "x = " << x << ", t = " << t;
          EXPECT_EQ(log_divided_difference(x, y), log_divided_difference(y, x));
        }
      // Nearly equal: 1/m (1 + u²/3) with u ~ 1e-10, i.e. 1/m to the last bit.
      const double y = x * (1.0 + 2e-10);
      EXPECT_NEAR(log_divided_difference(x, y), 2.0 / (x + y), 1e-16 / x);

      // Second difference, spreads across 3e-2 (series below, quotient above), in all
      // orders of the arguments, including two equal ones.
      for (const double s : {2e-3, 2.9e-2, 3.1e-2, 0.1, 1.0})
        for (const auto &w : {Eigen::Vector3d(0.0, 0.4, 1.0), Eigen::Vector3d(0.0, 0.0, 1.0),
                              Eigen::Vector3d(0.0, 1.0, 1.0)})
          {
            const double a = x * (1.0 + s * w(0)), b = x * (1.0 + s * w(1)),
                         c = x * (1.0 + s * w(2));
            // Long-double reference from two distinct pairs (an equal pair uses 1/x exactly).
            const long double r =
              w(0) == w(1) ? (ref_first(b, c) - 1.0L / static_cast<long double>(a)) / (c - a) :
              w(1) == w(2) ? (1.0L / static_cast<long double>(b) - ref_first(a, b)) / (c - a) :
                             ref_second(a, b, c);
            const double g = log_second_divided_difference(a, b, c);
            // 1e-13 relative: the long-double reference is good to ~1e-18/s ≤ 5e-16; the
            // double quotient branch to ≲ 8ε/s ≤ 3e-14 just above the threshold.
            EXPECT_NEAR(g, static_cast<double>(r), 1e-13 * std::abs(g))
              << "x = " << x << ", s = " << s << ", w = " << w.transpose();
            EXPECT_EQ(g, log_second_divided_difference(c, a, b));
            EXPECT_EQ(g, log_second_divided_difference(b, c, a));
          }
      // Nearly equal triple: −1/(2m²) with m the mean, the next term ~ s² = 1e-18.
      const double a = x * (1 - 1e-9), b = x, c = x * (1 + 1e-9);
      EXPECT_NEAR(log_second_divided_difference(a, b, c), -0.5 / (x * x), 1e-15 / (x * x));
    }
}

namespace
{
  /// P = ∂E/∂E_GL and T : ∂²E/∂E_GL² against central differences at E_GL, with a
  /// non-coaxial T. h = 1e-5: the truncation error h²|E'''| ~ 1e-10 and the rounding
  /// ε|E|/h ~ 1e-11 of the difference quotient are both below the 1e-8 (P ~ 1) tolerance.
  void check_derivatives(const Eigen::Matrix3d &egl, const Eigen::Matrix3d &T,
                         const std::string &what)
  {
    const double h = 1e-5;
    const LogStrain ls = compute_log_strain(egl);
    ASSERT_TRUE(ls.valid) << what;
    const Matrix6 M = contract_second_derivative(ls, T);
    EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-14 * M.cwiseAbs().maxCoeff()) << what;
    const Vector6 T_v = stress_to_voigt(T);
    Matrix6 P_fd, M_fd;
    for (int J = 0; J < 6; ++J)
      {
        const Eigen::Matrix3d d = h * voigt_to_strain(Vector6::Unit(J));
        const LogStrain plus = compute_log_strain(egl + d), minus = compute_log_strain(egl - d);
        P_fd.col(J) = (strain_to_voigt(plus.hencky) - strain_to_voigt(minus.hencky)) / (2.0 * h);
        M_fd.col(J) =
          (plus.projection.transpose() * T_v - minus.projection.transpose() * T_v) / (2.0 * h);
      }
    EXPECT_LT((ls.projection - P_fd).cwiseAbs().maxCoeff(), 1e-8) << what << "\n"
                                                                  << ls.projection << "\n"
                                                                  << P_fd;
    EXPECT_LT((M - M_fd).cwiseAbs().maxCoeff(), 1e-8 * T.cwiseAbs().maxCoeff()) << what << "\n"
                                                                                << M << "\n"
                                                                                << M_fd;
  }
}  // namespace

TEST(LogStrain, DerivativesAgainstFiniteDifferences)
{
  std::mt19937 rng(3005);
  std::uniform_real_distribution<double> u(-0.3, 0.8);
  const auto random_T = [&] {
    Eigen::Matrix3d a = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
    return Eigen::Matrix3d(a + a.transpose());
  };
  for (int trial = 0; trial < 6; ++trial)
    check_derivatives(green_lagrange(rng, Eigen::Vector3d(u(rng), u(rng), u(rng))), random_T(),
                      "distinct, trial " + std::to_string(trial));
  check_derivatives(green_lagrange(rng, Eigen::Vector3d(0.4, 0.4, -0.2)), random_T(), "two equal");
  check_derivatives(green_lagrange(rng, Eigen::Vector3d(-0.1, 0.3, 0.3)), random_T(),
                    "two equal (larger pair)");
  check_derivatives(green_lagrange(rng, Eigen::Vector3d(0.2, 0.2 + 1e-9, -0.1)), random_T(),
                    "nearly equal pair");
  check_derivatives(0.25 * Eigen::Matrix3d::Identity(), random_T(), "three equal");
  check_derivatives(Eigen::Matrix3d::Zero(), random_T(), "undeformed");

  // Three equal eigenvalues: P = I/λ whatever eigenvectors the solver returned.
  const LogStrain iso = compute_log_strain(green_lagrange(rng, Eigen::Vector3d::Constant(0.3)));
  EXPECT_LT((iso.projection - Matrix6::Identity() / 1.6).cwiseAbs().maxCoeff(), 1e-15);
}
