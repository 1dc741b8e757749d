// The logarithmic (Hencky) strain of a finite deformation and its first two derivatives, the
// kinematic part of finite-strain plasticity in the logarithmic strain space (issue 30 item 1,
// FE_DESIGN §4.2). No deal.II: Eigen 3×3 tensors and 6×6 Voigt matrices in the layout of
// material/j2_plasticity.h.
//
// Theory: C. Miehe, N. Apel, M. Lambrecht, "Anisotropic additive plasticity in the logarithmic
// strain space: modular kinematic formulation and implementation based on incremental
// minimization principles for standard materials", CMAME 191 (2002) 5383–5425, §2–3: with the
// right Cauchy–Green tensor C = FᵀF = I + 2E_GL (E_GL the Green–Lagrange strain),
//     E = ½ ln C                  the Hencky strain,
//     P = 2 ∂E/∂C = ∂E/∂E_GL      the projection that maps the stress T conjugate to E to the
//                                  second Piola–Kirchhoff stress S = T : P,
//     L = 4 ∂²E/∂C∂C = ∂²E/∂E_GL² whose contraction T : L is the tangent's geometric part,
//                                  ℂ = Pᵀ : ℂ_log : P + T : L.
// They are computed from the spectral decomposition C = Σ λ_a N_a⊗N_a with the
// Daleckii–Krein formulas (R. Bhatia, "Matrix Analysis", Springer 1997, §V.3 for the first
// derivative; the second follows by differentiating it once more, and the unit tests check
// both against finite differences): for an isotropic tensor function f(C), in the eigenbasis
// {N_a},
//     (Df(C)[H])_ab      = f[λ_a, λ_b] H_ab,
//     (D²f(C)[H, K])_ab  = Σ_c f[λ_a, λ_c, λ_b] (H_ac K_cb + K_ac H_cb),
// with f[·,·] and f[·,·,·] the first and second divided differences of f = ln (f[x, x] = f'(x),
// f[x, x, x] = f''(x)/2, and so on). Unlike the formulas written with the eigenprojections'
// derivatives (as Miehe et al. write them, dividing by λ_a − λ_b), these are continuous where
// eigenvalues coincide; the eigenvectors of a repeated eigenvalue are arbitrary, and the
// results do not depend on their choice. The divided differences are evaluated so that they
// keep full precision for equal and nearly equal arguments (log_strain.cc says how).
//
// Voigt: strains (E, E_GL and their increments) in engineering shear [11, 22, 33, 2·23,
// 2·13, 2·12], stresses with no factor [11, 22, 33, 23, 13, 12]. Then the double contraction
// is the dot product, dE_V = P_V dE_GL,V, S_V = P_Vᵀ T_V, and the 6×6 of T : L is symmetric.
//
// Units: all strains [-]; T and the contraction T : L carry the unit of T (Pa).
#pragma once

#include "fe_stage/material/j2_plasticity.h"  // Matrix6, Vector6, the Voigt helpers

#include <Eigen/Dense>

namespace clearjoint::fe
{
  /// E = ½ ln C, its derivative and the spectral data the second derivative needs.
  struct LogStrain
  {
    /// false: C is not positive definite (an eigenvalue of C ≤ 0, or a non-finite input);
    /// the other fields are then not meaningful.
    bool valid = false;
    Eigen::Matrix3d hencky = Eigen::Matrix3d::Zero();  ///< E = ½ ln C [-]
    /// P_V = ∂E_V/∂E_GL,V (= 2∂E/∂C), strain Voigt (engineering shear) on both sides [-].
    Matrix6 projection = Matrix6::Identity();
    Eigen::Vector3d lambda = Eigen::Vector3d::Ones();            ///< eigenvalues of C, ascending
    Eigen::Matrix3d eigenvectors = Eigen::Matrix3d::Identity();  ///< N_a as columns
    /// ln[λ_a, λ_b], the first divided differences of ln (1/λ_a on the diagonal)
    Eigen::Matrix3d first_differences = Eigen::Matrix3d::Identity();
  };

  /// The Hencky strain of C = I + 2 E_GL from the Green–Lagrange strain (symmetric, [-]).
  /// Taking E_GL rather than C keeps the small strains' digits: the eigenvalues of E_GL are
  /// accurate relative to E_GL, and ln λ_a = log1p(2 μ_a) (μ_a the eigenvalues of E_GL), where
  /// ln of λ_a = 1 + 2μ_a would lose them to the rounding of 1 + 2μ_a. The price is at the
  /// other end: λ_a is then known to ~ε absolute, so a principal stretch √λ_a below ~1e-4
  /// loses digits and one below ~1e-8 gives λ_a ≤ 0 (valid = false), far beyond any element
  /// a solver should accept.
  LogStrain compute_log_strain(const Eigen::Matrix3d &green_lagrange);

  /// T : L as a symmetric 6×6 (row and column in strain Voigt, engineering shear): for
  /// increments dE_GL,1 and dE_GL,2, dE_GL,1ᵀ · M · dE_GL,2 = T : ∂²E/∂E_GL²[dE_GL,1, dE_GL,2]
  /// [unit of T]. `stress` is T (symmetric), in the same frame as the C of `log_strain`.
  Matrix6 contract_second_derivative(const LogStrain &log_strain, const Eigen::Matrix3d &stress);

  /// First divided difference of ln: (ln x − ln y)/(x − y), 1/x at x = y; x, y > 0.
  double log_divided_difference(double x, double y);

  /// Second divided difference of ln: (ln[y, z] − ln[x, y])/(z − x) for distinct arguments,
  /// symmetric in its arguments, −1/(2x²) at x = y = z; x, y, z > 0.
  double log_second_divided_difference(double x, double y, double z);
}  // namespace clearjoint::fe
