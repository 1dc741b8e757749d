// A contact node: one row of the contact problem — which DoFs, facing which partner nodes (none
// for a rigid obstacle, one for node-to-node, several for mortar), and its state (active,
// stick/slip, force, gap) in the current iteration. deal.II value types only.
#pragma once

#include "fe_stage/core/dim.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <array>
#include <vector>

namespace clearjoint::fe::detail
{

  /// A contact candidate node: its three displacement DoFs, reference position and the
  /// component whose DoF carries the contact constraint.
  struct ContactNode
  {
    std::array<types::global_dof_index, dim> dofs;
    /// Two-body contact: the other body's point facing this node is Σ weight·(partner node);
    /// node-to-node (matching meshes) has one partner of weight 1, a mortar coupling several.
    struct Partner
    {
      std::array<types::global_dof_index, dim> dofs;
      double weight = 1.0;
      bool driven_y = false;  // the partner's y-DoF is driven by the journal load
    };
    std::vector<Partner> partners;
    /// Σ weight·(partner's mesh position) and Σ weight: where the partner combination sits
    /// in its own body's frame (the rolling study's turning journal is placed from them).
    Point<dim> partner_X;
    double partner_weight = 0.0;
    bool two_body = false;
    Point<dim> X;
    unsigned int constrained_component = 1;
    bool owned = false;     // owned by this rank (its x-DoF is locally owned)
    bool candidate = true;  // false: only watched for penetration, never constrained
    bool active = false;
    // Values of the last evaluation:
    double lambda = 0.0;  // [N] normal contact force on the body (≥ 0 in contact)
    double gap = 0.0;     // [m] linearised gap ĝ = g0 + n·u
    double weight = 0.0;  // [m²] ∫ φ_i dA over the contact surface (nodal area)
    Tensor<1, dim> n;
    double g0 = 0.0;
    // Coulomb friction (contact.mu > 0), solved by a semi-smooth Newton method (active_set.cc
    // and contact_rows.cc): an active node sticks (its whole relative displacement is
    // constrained: no new tangential slip) or slips (normal constraint, and the friction force
    // linearised about the last iterate: μλ·ŵ along the slip direction plus κ·Q·w across it).
    bool stick = true;
    Tensor<1, dim> traction;            // [N] total contact force on this node (K u at its DoFs)
    Tensor<1, dim> slip_direction;      // ŵ = w/|w|: unit tangent of the friction force (slipping)
    double kappa = 0.0;                 // [1] μξ/|w| < 1 of the slipping node's linearisation
    Tensor<1, dim> relative;            // [m] u − u_partner (rigid obstacle: − its translation)
    Tensor<1, dim> relative_converged;  // [m] the same at the last converged increment
    /// [m] the rigid obstacle's surface point facing the node: its displacement since the
    /// start (radial: (0, −δ, 0); rolling: accumulated step by step), now and at the last
    /// converged step. relative = u − obstacle_u. Two deformable bodies: the rigid motion of
    /// the partner combination's frame (the rolling study's turning journal; else 0), so that
    /// relative = u − Σ w R u_p − obstacle_u (R: partner_rotation in model.h).
    Tensor<1, dim> obstacle_u, obstacle_u_converged;
    /// [N] elastoplastic: the linearisation's load b at the node's DoFs (traction = K u − b)
    Tensor<1, dim> load_offset;
  };

  /// The part of v tangential to the unit normal n: (I − n nᵀ) v.
  inline Tensor<1, dim> tangential(const Tensor<1, dim> &v, const Tensor<1, dim> &n)
  {
    return v - (v * n) * n;
  }
}  // namespace clearjoint::fe::detail
