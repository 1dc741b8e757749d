// Small-strain von Mises (J2) plasticity with isotropic hardening from a HardeningTable:
// backward-Euler radial return and its consistent (algorithmic) tangent. Issue 13 item 1,
// FE_DESIGN §3.3 material/. No deal.II: tensors are Eigen 3×3 matrices, the tangent a 6×6
// Voigt matrix (layout below), so the FE side converts with a few lines.
//
// Theory: J. C. Simo, T. J. R. Hughes, "Computational Inelasticity", Springer 1998, §3.3
// (radial return, Box 3.2) and §3.3.2 (consistent elastoplastic tangent moduli, Eq. 3.3.10).
// With K = E/(3(1−2ν)), G = E/(2(1+ν)), trial deviator s* = 2G dev(ε − ε_p,n),
// q* = √(3/2)|s*|, n = s*/|s*|, the return solves for Δγ (= Δα, the equivalent plastic strain
// increment)
//     f(Δγ) = q* − 3G Δγ − σ_y(α_n + Δγ) = 0,
// then ε_p = ε_p,n + √(3/2) Δγ n, s = s* − 2G √(3/2) Δγ n. f is piecewise linear and strictly
// decreasing (G > 0, H ≥ 0), so the root is unique. The solver is Newton with each step
// clamped to the end of the current table segment: inside a segment f is linear and one Newton
// step is exact, otherwise the iterate moves to the next table point. It ends after at most
// (segments crossed + 1) steps; the count is bounded and the final |f| checked (ReturnStatus).
//
// Tangent, with θ = 1 − 3GΔγ/q*, θ̄ = 3G/(3G + H) − (1 − θ), H the slope of the segment the
// solution lies on:   C = K 1⊗1 + 2Gθ I_dev − 2Gθ̄ n⊗n   (elastic step: θ = 1, θ̄ = 0).
//
// Voigt layout (the "mixed" convention, so that C is symmetric and C_IJ = C_ijkl exactly):
//   stress [σ11, σ22, σ33, σ23, σ13, σ12],
//   strain [ε11, ε22, ε33, 2ε23, 2ε13, 2ε12] (engineering shear strains).
//
// Units: strains [-], stresses and moduli [Pa], plastic work per volume [J/m³ = Pa].
#pragma once

#include "fe_stage/material/hardening_table.h"

#include <Eigen/Dense>

#include <string>

namespace clearjoint::fe
{
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  using Vector6 = Eigen::Matrix<double, 6, 1>;

  /// Index pairs of the Voigt layout above: voigt_index[I] = {i, j}.
  constexpr int voigt_index[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

  /// Voigt index of the tensor pair (i, j) (either order): C_ijkl = C(voigt_of(i, j),
  /// voigt_of(k, l)) converts the 6×6 tangent to a 4th-order tensor (deal.II's
  /// SymmetricTensor<4, 3>) with no factors.
  constexpr int voigt_of(int i, int j)
  {
    return i == j ? i : 6 - i - j;  // (1,2) → 3, (0,2) → 4, (0,1) → 5
  }

  /// von Mises equivalent stress √(3/2 s:s) [Pa] of a symmetric stress tensor.
  double von_mises_stress(const Eigen::Matrix3d &sigma);

  /// Symmetric strain tensor → Voigt strain (engineering shear); the inverse below.
  Vector6 strain_to_voigt(const Eigen::Matrix3d &eps);
  Eigen::Matrix3d voigt_to_strain(const Vector6 &e);
  /// Symmetric stress tensor → Voigt stress (no factors); the inverse below.
  Vector6 stress_to_voigt(const Eigen::Matrix3d &sigma);
  Eigen::Matrix3d voigt_to_stress(const Vector6 &s);

  /// History of one quadrature point.
  struct J2State
  {
    Eigen::Matrix3d eps_p = Eigen::Matrix3d::Zero();  ///< plastic strain tensor [-], trace 0
    double alpha = 0.0;  ///< equivalent plastic strain ∫√(2/3)|dε_p| [-]
  };

  /// Trial/commit: evaluate() writes only `trial`; the caller copies it to `committed` after a
  /// converged step (commit()); a cut step simply evaluates again from `committed`.
  struct J2History
  {
    J2State committed;
    J2State trial;
    void commit() { committed = trial; }
  };

  struct ReturnStatus
  {
    bool converged = true;
    int iterations = 0;     ///< local Newton steps (0 for an elastic step)
    double residual = 0.0;  ///< |f(Δγ)| at the end [Pa]
  };

  struct J2Response
  {
    Eigen::Matrix3d stress;  ///< Cauchy stress σ_{n+1} [Pa] (small strain)
    Matrix6 tangent;         ///< consistent tangent dσ/dε, Voigt layout above [Pa]
    bool plastic = false;
    double delta_alpha = 0.0;  ///< Δγ = α_{n+1} − α_n [-]
    /// Plastic work per volume of the step, σ_{n+1} : Δε_p = σ_y(α_{n+1}) Δα ≥ 0 [J/m³]:
    /// what backward Euler dissipates plus the energy stored by hardening (cold work).
    double plastic_work = 0.0;
    ReturnStatus status;
  };

  class J2Plasticity
  {
  public:
    /// E [Pa] > 0 and ν ∈ (−1, 0.5) are checked; an InputError names `key_path`.E / .nu.
    J2Plasticity(double E, double nu, HardeningTable hardening,
                 const std::string &key_path = "material", const std::string &file = "");

    /// Stress and consistent tangent for the total strain `eps` (symmetric, [-]) from
    /// history.committed; writes history.trial only. A non-finite strain or a return that
    /// did not converge gives status.converged = false (the caller cuts the step); the other
    /// fields are then not meaningful.
    J2Response evaluate(const Eigen::Matrix3d &eps, J2History &history) const;

    /// Elastic tangent K 1⊗1 + 2G I_dev in the Voigt layout [Pa].
    Matrix6 elastic_tangent() const;

    /// Elastic strain energy per volume ½(ε − ε_p):C:(ε − ε_p) [J/m³] for a given state.
    double elastic_energy(const Eigen::Matrix3d &eps, const J2State &state) const;

    double bulk_modulus() const { return K_; }
    double shear_modulus() const { return G_; }
    const HardeningTable &hardening() const { return table_; }

    /// Local Newton limit: segments in the table plus this many steps.
    static constexpr int extra_iterations = 5;

  private:
    double E_, nu_, K_, G_;
    HardeningTable table_;
  };
}  // namespace clearjoint::fe
