// Per-node complementarity functions of 3D Coulomb friction with dual (nodal) Lagrange
// multipliers, for a semi-smooth Newton method / primal–dual active set (issue 11 item 3).
// No deal.II: the FE core evaluates one node at a time and places the rows in its system.
//
// Theory: S. Hüeber, G. Stadler, B. I. Wohlmuth, "A primal-dual active set algorithm for
// three-dimensional contact problems with Coulomb friction", SIAM J. Sci. Comput. 30 (2008)
// 572–596; A. Gitterle, A. Popp, M. W. Gee, W. A. Wall, "Finite deformation frictional mortar
// contact using a semi-smooth Newton method with consistent linearization", IJNME 84 (2010)
// 543–571 (the same functions with full linearisation; MOOSE's
// ComputeFrictionalForceLMMechanicalContact follows them).
//
// Per slave node, in its (n, t1, t2) basis:
//   λ_n ≥ 0   normal multiplier, compressive positive;
//   λ_T ∈ R²  tangential multiplier: the friction traction on the slave body;
//   g         (weighted) normal gap, > 0 open;
//   s_T ∈ R²  (weighted) tangential slip increment of the slave relative to the master over
//             the step.
// Units are the caller's, consistently: with dual mortar, λ a pressure [Pa] and g, s_T
// weighted by the nodal D [m³] (or λ a nodal force [N] and g, s_T in m); c_n and c_t convert
// gap units into multiplier units ([Pa/m³] or [N/m]). The residual R then carries λ's unit.
// Coulomb: λ_n ≥ 0, g ≥ 0, λ_n g = 0; |λ_T| ≤ μλ_n; s_T = 0 if |λ_T| < μλ_n; otherwise
// λ_T = −μλ_n s_T/|s_T| (friction opposes the slip). With ξ = λ_n − c_n g and
// w = λ_T − c_t s_T these hold iff
//   R_n = λ_n − max(0, ξ) = 0,
//   R_T = λ_T − P_{μ max(0,ξ)}(w) = 0,      P_r(w) the projection onto the disc |w| ≤ r,
// for any c_n, c_t > 0 (the constants change the Newton path, not the solution). Classes:
//   inactive: ξ ≤ 0              R_n = λ_n,    R_T = λ_T
//   stick:    |w| ≤ μξ (μξ > 0)  R_n = c_n g,  R_T = c_t s_T
//   slip:     otherwise          R_n = c_n g,  R_T = λ_T − μξ w/|w|
// This is HSW's tangential function C_T = max(μξ, |w|) λ_T − μ max(0, ξ) w divided by
// max(μξ, |w|) > 0 on active nodes (the `hsw` form keeps that factor; on inactive nodes both use
// λ_T = 0, as HSW's algorithm does). The projection form's derivative is bounded (the slip
// terms carry μξ/|w| < 1), needs no special case at μ = 0, and keeps R in force units.
// The derivative is the full generalised derivative of the class's branch, including the
// linearised slip direction d(w/|w|) = (I − ŵŵᵀ)/|w| dw: no frozen direction, no relaxation.
#pragma once

#include <Eigen/Dense>

#include <string>

namespace clearjoint::fe
{
  enum class FrictionState
  {
    inactive,
    stick,
    slip
  };

  enum class CoulombNcpForm
  {
    projection,  ///< R_T = λ_T − P(w): force units, bounded derivative (default)
    hsw,         ///< HSW 2008's C_T on active nodes (force² units)
  };

  struct CoulombParameters
  {
    double mu = 0.1;   ///< friction coefficient [-], ≥ 0
    double c_n = 1.0;  ///< normal complementarity constant [λ unit / g unit], > 0
    double c_t = 1.0;  ///< tangential complementarity constant [λ unit / s unit], > 0
    CoulombNcpForm form = CoulombNcpForm::projection;
  };

  /// InputError naming key_path.mu (≥ 0, finite) or key_path.c_n / .c_t (> 0, finite).
  /// c is a numerical constant with no effect on the solution; a good choice is of the order
  /// of the stiffness seen by a contact node (the diagonal of K, in the multiplier's units).
  void check_coulomb_parameters(const CoulombParameters &p, const std::string &key_path,
                                const std::string &file = "");

  /// Column order of NodeNcp::jacobian.
  enum NcpColumn : int
  {
    col_lambda_n = 0,
    col_lambda_t1 = 1,
    col_lambda_t2 = 2,
    col_gap = 3,
    col_slip_t1 = 4,
    col_slip_t2 = 5,
  };

  struct NodeNcp
  {
    FrictionState state;
    double r_n;           ///< R_n [λ unit]
    Eigen::Vector2d r_t;  ///< R_T [λ unit] (projection form) or [λ unit²] (hsw form)
    /// ∂(R_n, R_T1, R_T2)/∂(λ_n, λ_T1, λ_T2, g, s_T1, s_T2), columns as NcpColumn.
    Eigen::Matrix<double, 3, 6> jacobian;
  };

  /// The class of a node from ξ = λ_n − c_n g and |w| = |λ_T − c_t s_T| — the decision of
  /// evaluate_coulomb_ncp, and of the FE model's active set (contact/active_set.cc): inactive
  /// where ξ ≤ band, stick where μξ > 0 and |w| ≤ μξ + band, slip otherwise. `band` ≥ 0 [λ
  /// unit] is a round-off margin: the FE model makes its decisions deterministic across rank
  /// counts with it (a penetration below 1e-9 of the push is not contact); 0 is the exact law.
  FrictionState coulomb_state(double xi, double w_norm, double mu, double band = 0.0);

  /// The FE model's stick decision for a node in contact that was in contact before
  /// (was_stick its label then): coulomb_state's, except within `edge` [λ unit] of the cone's
  /// edge, | |w| − μξ | ≤ edge with w ≠ 0, where the node keeps its label — there stick and slip
  /// are the same state to that tolerance, and re-deciding on round-off let a node flip for
  /// every iteration (contact/active_set.cc). edge = 0: coulomb_state's decision.
  bool keeps_or_decides_stick(double xi, double w_norm, double mu, double band, bool was_stick,
                              double edge);

  /// Classifies the node and evaluates its residuals and generalised derivative. All inputs
  /// must be finite (std::invalid_argument otherwise: the caller's Newton has diverged).
  NodeNcp evaluate_coulomb_ncp(double lambda_n, const Eigen::Vector2d &lambda_t, double gap,
                               const Eigen::Vector2d &slip_t, const CoulombParameters &p);
}  // namespace clearjoint::fe
