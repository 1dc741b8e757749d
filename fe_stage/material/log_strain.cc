#include "fe_stage/material/log_strain.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace clearjoint::fe
{
  namespace
  {
    /// Below this |u| the first divided difference uses its series (see below).
    constexpr double first_series_threshold = 1e-4;
    /// Below this relative spread (z − x)/m the second divided difference uses its series.
    constexpr double second_series_threshold = 3e-2;
    /// Terms of the second divided difference's series: h_0 … h_12 (see below).
    constexpr int second_series_order = 12;

    /// The strain increments of the six Voigt unit vectors, rotated into the eigenbasis:
    /// H̃_I = Qᵀ H_I Q with H_I = voigt_to_strain(e_I) (½ off the diagonal for shears).
    std::array<Eigen::Matrix3d, 6> rotated_voigt_basis(const Eigen::Matrix3d &Q)
    {
      std::array<Eigen::Matrix3d, 6> h;
      for (int I = 0; I < 6; ++I)
        h[I] = Q.transpose() * voigt_to_strain(Vector6::Unit(I)) * Q;
      return h;
    }
  }  // namespace

  // ln x − ln y = ln((1 + u)/(1 − u)) = 2 artanh u with u = (x − y)/(x + y), and
  // x − y = 2 m u with m = (x + y)/2, so ln[x, y] = artanh(u)/(m u): no difference of two
  // logarithms, whose cancellation loses digits in proportion to |ln x|/|ln x − ln y| (all of
  // them as x → y) and ends in 0/0 at x = y. What remains is the 0/0 of artanh(u)/u at u = 0;
  // below |u| = 1e-4 the series artanh(u)/u = 1 + u²/3 + u⁴/5 + … is used, truncated after u⁴
  // (the first omitted term, u⁶/7 < 2e-25, is far below the rounding of the sum).
  double log_divided_difference(const double x, const double y)
  {
    const double m = 0.5 * (x + y);
    const double u = (x - y) / (x + y);
    if (std::abs(u) < first_series_threshold)
      {
        const double u2 = u * u;
        return (1.0 + u2 * (1.0 / 3.0 + u2 / 5.0)) / m;
      }
    return std::atanh(u) / (m * u);
  }

  // Sorted x ≤ y ≤ z, spread s = (z − x)/m with m the mean. For s ≥ 3e-2 the quotient
  // (ln[y, z] − ln[x, y])/(z − x): its numerator is ~ s/(2m) while each first difference is
  // accurate to ~2ε/m, so the relative error is ≲ 8ε/s ≤ 3e-14; the argument order
  // (smallest and largest at the ends) makes z − x the largest gap, so a pair of equal or
  // nearly equal arguments never sits in the denominator. For s < 3e-2 that cancellation would
  // grow without bound, and the Taylor series about the mean is used instead. For an analytic
  // f, f[x₀, x₁, x₂] = Σ_{k≥2} f⁽ᵏ⁾(m)/k! · h_{k−2}(x₀ − m, x₁ − m, x₂ − m), h_j the complete
  // homogeneous symmetric polynomial of degree j (h_1 = 0 about the mean); for ln,
  // f⁽ᵏ⁾(m)/k! = (−1)^{k+1}/(k m^k), so with δ_i = (x_i − m)/m
  //     ln[x, y, z] = m⁻² Σ_{k≥2} (−1)^{k+1} h_{k−2}(δ)/k,
  // h_j from the power sums p_i = Σ δ^i by Newton's identity h_j = (1/j) Σ_{i=1..j} p_i h_{j−i}.
  // |δ_i| ≤ 2s/3 < 0.02 and |h_j| ≤ (j+2)(j+1)/2 · 0.02^j, so truncating after h_12 leaves
  // < 105·0.02¹³/15 ~ 6e-22 relative: the series is as accurate as its rounding.
  namespace
  {
    /// ln[x, y, z] for sorted x ≤ y ≤ z, given d_xy = ln[x, y] and d_yz = ln[y, z].
    double sorted_second_difference(const double x, const double y, const double z,
                                    const double d_xy, const double d_yz)
    {
      if (x == z)  // f''(x)/2 exactly: the common case a = b = c of T : L's sum
        return -0.5 / (x * x);
      const double m = (x + y + z) / 3.0;
      if (z - x >= second_series_threshold * m)
        return (d_yz - d_xy) / (z - x);

      const std::array<double, 3> d = {(x - m) / m, (y - m) / m, (z - m) / m};
      std::array<double, second_series_order + 1> p{}, h{};
      std::array<double, 3> power = d;  // δ_i^j, by repeated multiplication (std::pow is slow)
      for (int j = 1; j <= second_series_order; ++j)
        {
          p[j] = power[0] + power[1] + power[2];
          for (int i = 0; i < 3; ++i)
            power[i] *= d[i];
        }
      h[0] = 1.0;
      for (int j = 1; j <= second_series_order; ++j)
        {
          double sum = 0.0;
          for (int i = 1; i <= j; ++i)
            sum += p[i] * h[j - i];
          h[j] = sum / j;
        }
      double series = 0.0;
      for (int k = 2; k <= second_series_order + 2; ++k)
        series += (k % 2 == 0 ? -1.0 : 1.0) * h[k - 2] / k;
      return series / (m * m);
    }
  }  // namespace

  double log_second_divided_difference(const double x, const double y, const double z)
  {
    std::array<double, 3> v = {x, y, z};
    std::sort(v.begin(), v.end());
    return sorted_second_difference(v[0], v[1], v[2], log_divided_difference(v[0], v[1]),
                                    log_divided_difference(v[1], v[2]));
  }

  LogStrain compute_log_strain(const Eigen::Matrix3d &green_lagrange)
  {
    LogStrain out;
    if (!green_lagrange.allFinite())
      return out;
    // Eigen's iterative (tridiagonal QR) solver, not computeDirect(): the closed-form cubic
    // loses the eigenvectors' accuracy for nearly repeated eigenvalues.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(green_lagrange);
    if (eig.info() != Eigen::Success)
      return out;
    const Eigen::Vector3d mu = eig.eigenvalues();  // ascending
    if (!(mu(0) > -0.5))                           // λ_min = 1 + 2μ_min ≤ 0
      return out;
    const Eigen::Matrix3d &Q = eig.eigenvectors();

    Eigen::Vector3d half_log;
    for (int a = 0; a < 3; ++a)
      {
        out.lambda(a) = 1.0 + 2.0 * mu(a);
        half_log(a) = 0.5 * std::log1p(2.0 * mu(a));
      }
    out.eigenvectors = Q;
    out.hencky = Q * half_log.asDiagonal() * Q.transpose();

    // E = ½ ln(I + 2E_GL), so dE = ½ D ln(C)[2 dE_GL] = D ln(C)[dE_GL]: in the eigenbasis
    // dẼ_ab = ln[λ_a, λ_b] dẼ_GL,ab (Daleckii–Krein).
    Eigen::Matrix3d &d1 = out.first_differences;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b)
        d1(a, b) = d1(b, a) = log_divided_difference(out.lambda(a), out.lambda(b));
    const auto h = rotated_voigt_basis(Q);
    for (int J = 0; J < 6; ++J)
      out.projection.col(J) = strain_to_voigt(Q * d1.cwiseProduct(h[J]).eval() * Q.transpose());
    out.valid = true;
    return out;
  }

  // T : ∂²E/∂E_GL²[H, K] = ½ T : D² ln(C)[2H, 2K] = 2 Σ_abc T̃_ab ln[λ_a, λ_c, λ_b]
  // (H̃_ac K̃_cb + K̃_ac H̃_cb) in the eigenbasis; with T̃, H̃, K̃ symmetric and the divided
  // difference symmetric in its arguments the two terms are equal (swap a and b in the second):
  // = 4 Σ_c Σ_ab H̃_ac W^c_ab K̃_bc, W^c_ab = T̃_ab ln[λ_a, λ_c, λ_b]. For the six Voigt
  // directions at once: M = 4 Σ_c A_c W^c A_cᵀ with A_c(I, a) = (H̃_I)_ac, symmetric by
  // construction.
  Matrix6 contract_second_derivative(const LogStrain &log_strain, const Eigen::Matrix3d &stress)
  {
    const Eigen::Matrix3d &Q = log_strain.eigenvectors;
    const Eigen::Vector3d &l = log_strain.lambda;
    const Eigen::Matrix3d T = Q.transpose() * stress * Q;

    // the ten distinct second divided differences, spread over the 27 index triples; the
    // eigenvalues are ascending, so a ≤ b ≤ c gives sorted arguments, and the first
    // differences are those of compute_log_strain
    const Eigen::Matrix3d &d1 = log_strain.first_differences;
    double g[3][3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b)
        for (int c = b; c < 3; ++c)
          {
            const double v = sorted_second_difference(l(a), l(b), l(c), d1(a, b), d1(b, c));
            g[a][b][c] = g[a][c][b] = g[b][a][c] = g[b][c][a] = g[c][a][b] = g[c][b][a] = v;
          }

    const auto h = rotated_voigt_basis(Q);
    Matrix6 M = Matrix6::Zero();
    for (int c = 0; c < 3; ++c)
      {
        Eigen::Matrix<double, 6, 3> A;
        for (int I = 0; I < 6; ++I)
          A.row(I) = h[I].col(c).transpose();
        Eigen::Matrix3d W;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            W(a, b) = T(a, b) * g[a][c][b];
        M.noalias() += A * W * A.transpose();
      }
    return 4.0 * M;
  }
}  // namespace clearjoint::fe
