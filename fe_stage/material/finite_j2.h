// Finite-strain von Mises (J2) plasticity in the logarithmic strain space: the small-strain
// radial return of material/j2_plasticity.h (hardening table, consistent tangent) applied to
// the Hencky strain, its stress and tangent mapped back to the reference configuration.
// Issue 30 item 1 (the material point law; the total-Lagrangian assembly is the FE side's),
// FE_DESIGN §4.2. No deal.II: Eigen 3×3 tensors, the tangent a 6×6 in j2_plasticity.h's Voigt
// layout.
//
// Theory: C. Miehe, N. Apel, M. Lambrecht, CMAME 191 (2002) 5383–5425 (the "logarithmic strain
// space" of §3, with the additive split E = E_e + E_p of the Hencky strain there). With the
// deformation gradient F (det F > 0), C = FᵀF = I + 2E_GL:
//   1. E = ½ ln C and P = ∂E/∂E_GL, L = ∂²E/∂E_GL² (material/log_strain.h);
//   2. J2Plasticity::evaluate on E with the same history (the plastic strain is now the plastic
//      log strain E_p, trace 0, and α the equivalent plastic strain): the stress T conjugate to
//      E and ℂ_log = dT/dE (the small-strain consistent tangent, unchanged);
//   3. S = T : P (second Piola–Kirchhoff), ℂ = dS/dE_GL = Pᵀ : ℂ_log : P + T : L.
// Then the first Piola stress F S, the Kirchhoff stress τ = F S Fᵀ and the Cauchy stress
// σ = τ/J, J = det F. The model is objective: S depends on C only, so a rotation R applied on
// the left of F leaves S and the history unchanged and rotates τ and σ to R τ Rᵀ. The elastic
// part is Hencky's hyperelasticity ψ = ½(E − E_p) : ℂ_e : (E − E_p); the yield function acts on
// T (for coaxial T and C, T = Rᵀ τ R is the rotated Kirchhoff stress), so in uniaxial tension
// the table's σ_y(α) is the Kirchhoff stress and the Cauchy stress is σ_y(α)/J with
// J = exp((1 − 2ν) σ_y/E) for the elastic volume change (plastic flow is isochoric,
// tr E_p = 0, det exp(E_p) = 1): a relative (1 − 2ν)σ_y/E below σ_y(α), 0.03–0.09 % on the
// SPEC table (168–448 MPa, E = 207 GPa). (The
// yield function on the Kirchhoff stress is also the choice of J. C. Simo's multiplicative
// model, CMAME 99 (1992) 61–112.)
//
// Voigt layout of the tangent (as j2_plasticity.h): rows S_V = [S11, S22, S33, S23, S13, S12],
// columns E_GL,V = [E11, E22, E33, 2E23, 2E13, 2E12] (engineering shear), so dS_V = ℂ_V dE_GL,V
// and ℂ_V(I, J) = ℂ_ijkl = ∂S_ij/∂E_kl (minor-symmetric) with (i, j) = voigt_index[I],
// (k, l) = voigt_index[J]: deal.II's SymmetricTensor<4, 3> takes ℂ_V with no factors.
//
// Bad iterates: evaluate() never throws. A non-finite F, det F ≤ 0, a C that is not positive
// definite in floating point, a return map that did not converge or a non-finite result give
// status.converged = false with status.reason saying which (the caller cuts the step or
// shortens its line search); the other fields are then not meaningful and history.trial is not
// written.
//
// Units: strains [-], stresses and moduli [Pa], plastic work and energies per reference volume
// [J/m³].
#pragma once

#include "fe_stage/material/j2_plasticity.h"

#include <Eigen/Dense>

#include <string>

namespace clearjoint::fe
{
  struct FiniteJ2Status
  {
    bool converged = true;
    std::string reason;       ///< why not converged; empty when converged
    ReturnStatus return_map;  ///< the small-strain return's own status
  };

  struct FiniteJ2Response
  {
    Eigen::Matrix3d stress_pk2;     ///< second Piola–Kirchhoff stress S [Pa]
    Eigen::Matrix3d stress_pk1;     ///< first Piola–Kirchhoff stress F S [Pa]
    Eigen::Matrix3d kirchhoff;      ///< τ = F S Fᵀ [Pa]
    Eigen::Matrix3d cauchy;         ///< σ = τ/J [Pa]
    Eigen::Matrix3d hencky_stress;  ///< T, conjugate to the Hencky strain [Pa]
    Eigen::Matrix3d hencky_strain;  ///< E = ½ ln C [-]
    double J = 1.0;                 ///< det F [-]
    /// dS/dE_GL [Pa], Voigt layout above (symmetric: major symmetry of the algorithmic
    /// tangent of this associative, isotropic-hardening law).
    Matrix6 tangent;
    bool plastic = false;
    double delta_alpha = 0.0;  ///< α_{n+1} − α_n [-]
    /// T_{n+1} : ΔE_p = σ_y(α_{n+1}) Δα ≥ 0 per reference volume [J/m³].
    double plastic_work = 0.0;
    FiniteJ2Status status;
  };

  class FiniteJ2
  {
  public:
    /// The small-strain law supplies E, ν, the hardening table and the return map.
    explicit FiniteJ2(J2Plasticity small_strain);

    /// Response to the deformation gradient F from history.committed; writes history.trial
    /// only (and only when converged).
    FiniteJ2Response evaluate(const Eigen::Matrix3d &F, J2History &history) const;

    /// The same from the displacement gradient H = ∇u = F − I, so that C − I = H + Hᵀ + HᵀH
    /// keeps the digits of small strains (FᵀF − I would lose them to the rounding of F's
    /// diagonal): what a total-Lagrangian assembly has at a quadrature point.
    FiniteJ2Response evaluate_displacement_gradient(const Eigen::Matrix3d &grad_u,
                                                    J2History &history) const;

    /// Stored (elastic) energy per reference volume ½(E − E_p) : ℂ_e : (E − E_p) [J/m³] for the
    /// displacement gradient H and a state; NaN where E cannot be formed (det F ≤ 0 …).
    double elastic_energy(const Eigen::Matrix3d &grad_u, const J2State &state) const;

    const J2Plasticity &small_strain() const { return law_; }

  private:
    J2Plasticity law_;
  };
}  // namespace clearjoint::fe
