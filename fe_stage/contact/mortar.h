// Dual-mortar coupling of two non-matching contact surfaces (Wohlmuth's dual Lagrange
// multipliers with lumped D). No deal.II here: contact/mortar_pairing.cc hands in the surface
// faces of both bodies and turns each slave node's result into one linear non-penetration
// constraint
//     n_s · (u_s − Σ_m C_sm u_m) + gap_s = 0.
// Theory: B. I. Wohlmuth, "A mortar finite element method using dual spaces for the Lagrange
// multiplier", SIAM J. Numer. Anal. 38 (2000) 989–1012; Popp, Gee, Wall, "A finite deformation
// mortar contact formulation using a primal–dual active set strategy", IJNME 79 (2009) 1354
// (D, M and the weighted gap). Units: SI (positions in m, areas in m²).
#pragma once

#include <array>
#include <utility>
#include <vector>

namespace clearjoint::fe::mortar
{
  /// One quadrilateral surface face, 4 nodes (bilinear) or 9 nodes (biquadratic Lagrange), in
  /// deal.II's Q1/Q2 face order with face coordinates (a, b) ∈ [0,1]²:
  ///   4 nodes: vertices (0,0), (1,0), (0,1), (1,1);
  ///   9 nodes: those vertices, the edge midpoints (0,½), (1,½), (½,0), (½,1), the centre (½,½).
  /// The geometry is isoparametric: x(a,b) = Σ_k N_k(a,b) X_k.
  struct Face
  {
    std::vector<long> nodes;               ///< node ids (any unique key per body)
    std::vector<std::array<double, 3>> X;  ///< node positions [m], same order as `nodes`
  };

  /// A slave node's normal: unit vector from the master body INTO the slave body (the slave
  /// body's inward normal); the gap is measured along it. couple() uses the node normals
  /// only to orient the faces' geometric normals; the caller uses them in the constraint.
  struct SlaveNode
  {
    long id;
    std::array<double, 3> normal;  ///< [-], unit
  };

  struct Options
  {
    /// Iterated Gauss rule on each slave face: each direction is split into `subdivisions`
    /// intervals with `gauss_points` points each (default 4 × 3 → 144 points per face). The
    /// integrands have kinks where master faces meet, so one high-order rule would not help.
    /// subdivisions × gauss_points must be ≥ 3: with fewer points per direction the 9-node
    /// mass matrix Me is singular.
    unsigned subdivisions = 4;  ///< 1..1000
    unsigned gauss_points = 3;  ///< 1..20
    /// [m] largest |gap| a quadrature point may have to its master face; also inflates the
    /// master faces' bounding boxes for the search. Must be set (> 0).
    double max_distance = 0.0;
  };

  /// The result for one slave node.
  struct Coupling
  {
    long node;      ///< slave node id
    double weight;  ///< D_s = Σ_e ∫_e N_s dA [m²] (0 if the node is on no slave face)
    double gap;     ///< weighted gap G_s / D_s [m]; > 0 open, < 0 penetration
    /// True iff every quadrature point of every slave face containing the node, where the
    /// node's dual shape function ψ_s is non-zero, found a master face. ψ_s is a polynomial
    /// on the whole face, so one face hanging over the master's edge makes ALL its nodes
    /// incomplete. The caller should not use an incomplete node.
    bool complete;
    /// (master node id, C_sm = M_sm / D_s [-]), sorted by id; |C_sm| < 1e-14 dropped.
    std::vector<std::pair<long, double>> masters;
  };

  /// Couples the slave surface to the master surface. Returns one Coupling per entry of
  /// `slave_nodes`, in that order. For each slave quadrature point x_q the projection
  /// direction n_q is the slave face's geometric unit normal (∂x/∂a × ∂x/∂b, oriented to agree
  /// with Σ N_k n_k), and the master point solves X_master(a,b) = x_q − g n_q.
  /// Throws std::invalid_argument on bad input (node count not 4 or 9, X/nodes size mismatch,
  /// non-finite positions, a slave face node without a normal, a degenerate face, bad options);
  /// the message names the face index.
  /// Cost: master faces sit in a uniform bucket grid; ~2 s per 10⁶ slave quadrature points
  /// (7200 Q2 slave faces on 5200 master faces) on one core.
  /// Note: the caller must check `complete` and not use an incomplete node.
  std::vector<Coupling> couple(const std::vector<Face> &slave_faces,
                               const std::vector<SlaveNode> &slave_nodes,
                               const std::vector<Face> &master_faces, const Options &options);
}  // namespace clearjoint::fe::mortar
