// The contact problem's nodes and their decisions: the locally relevant contact nodes (each a
// row: DoFs, partners, normal, gap, force and its active/stick state), which of them slip in
// this iteration, friction's constant c_T of the increment, and the active-set update after a
// solve — each node's class by contact/coulomb_ssn.h's law (the semi-smooth Newton step of
// Hüeber–Stadler–Wohlmuth 2008; contact/active_set.cc).
//
// The pairing's nodes fill it (contact/contact_pairing.h, contact/contact_pattern.cc), the
// constraint and friction rows read them (solve/contact_rows.cc), the evaluation after a
// solve writes their forces and gaps (results/reactions.cc).
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/scene.h"

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <map>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  class ContactProblem
  {
  public:
    /// What one active-set update changed.
    struct Change
    {
      unsigned int n_changed = 0;  // nodes whose active or stick state changed (all ranks)
      double slip_residual = 0.0;  // [N] largest |t − μλŵ| at nodes that slipped in the
                                   // solve and still slip (all ranks): Coulomb's slip law
      double force_scale = 0.0;    // [N] largest normal nodal force λ (all ranks)
      std::string changed;         // the first few changed nodes, "(x, y, z) mm
                                   // stick→slip, …" (this rank's; for messages)
    };

    ContactProblem(const FeScene &scene, const DofSpace &dofs, MPI_Comm comm);

    /// The locally relevant candidates (and watched nodes), in the pairing's order.
    std::vector<ContactNode> &nodes() { return nodes_; }
    const std::vector<ContactNode> &nodes() const { return nodes_; }
    /// contact.mu > 0
    bool friction() const { return friction_; }

    /// c_T / c of this increment's iterations: contact.tangential_scale at its start.
    double tangential_scale() const { return tangential_scale_; }
    void reset_tangential_scale();
    /// Lowers c_T when the stick/slip decisions have not settled by `iteration` (0-based), or
    /// at once when the stick/slip iteration `cycles` (its slip-law residual not halving:
    /// contact/stick_slip_progress.h); true when it did (friction only).
    bool soften_tangential_scale(unsigned int iteration, bool cycles);

    /// The nodes that slip in this iteration (active, not sticking) and their DoFs; returns
    /// whether any rank has one (the system is then nonsymmetric; collective).
    bool collect_slipping();
    const std::vector<unsigned int> &slipping() const { return slipping_; }
    /// The slipping node that owns DoF d (an index into nodes()), or −1.
    int slipping_node_of(const types::global_dof_index d) const
    {
      const auto it = slipping_dof_.find(d);
      return it == slipping_dof_.end() ? -1 : int(it->second);
    }
    /// Whether any rank has a slipping node in this iteration (GMRES, not CG).
    bool nonsymmetric() const { return nonsymmetric_; }

    /// After a solve whose forces and gaps are in the nodes: the normal (ξ = λ − c ĝ > c ε_g)
    /// and Coulomb decisions, and each slipping node's direction and κ for the next solve
    /// (c the complementarity constant [N/m], ε_g [m] the round-off band; collective).
    Change update_active_set(double c, double eps_g);

    /// Within this fraction of the largest normal nodal force of Coulomb's cone's edge
    /// (| |w| − μξ |), a node keeps its stick or slip label (update_active_set says why).
    static constexpr double edge_tolerance = 1e-5;

    /// Whether the contact holds DoF k of the node: a DoF fixed by a symmetry plane carries
    /// that plane's reaction, not contact (on the plane the friction force lies in it).
    bool holds(const ContactNode &cn, const unsigned int k) const
    {
      return !dofs_.fixed().is_constrained(cn.dofs[k]);
    }
    /// v with the components the contact does not hold (fixed by a symmetry plane or a
    /// support, or hanging) set to zero.
    Tensor<1, dim> held_components(const ContactNode &cn, Tensor<1, dim> v) const
    {
      for (unsigned int k = 0; k < dim; ++k)
        if (!holds(cn, k))
          v[k] = 0.0;
      return v;
    }
    /// The contact force on a node: K u on the DoFs the contact holds.
    Tensor<1, dim> traction(const ContactNode &cn) const
    {
      return held_components(cn, cn.traction);
    }
    /// The slip of a node in this increment, on the components the contact holds: a node on
    /// a symmetry plane cannot slip across it (its partner combination may move across it
    /// when the partners are not on the plane themselves, as a mortar coupling's are not).
    Tensor<1, dim> slip_increment(const ContactNode &cn) const
    {
      return tangential(held_components(cn, cn.relative - cn.relative_converged), cn.n);
    }
    /// Sets the node's constrained component: the largest component of the normal n
    /// (|n_c| > 0.3) whose DoF is not already constrained. False if there is none (a hanging
    /// or supported node: it follows its masters and is no contact node).
    bool choose_constrained_component(ContactNode &cn, const Tensor<1, dim> &n) const;
    /// P_T = I − n nᵀ at the node.
    static Tensor<2, dim> tangent_projection(const ContactNode &cn)
    {
      return Tensor<2, dim>(unit_symmetric_tensor<dim>()) - outer_product(cn.n, cn.n);
    }

  private:
    /// [N] the largest λ over the nodes in contact (ξ > band), all ranks (collective).
    double largest_normal_force(double c, double band) const;

    const FeScene &scene_;
    const DofSpace &dofs_;
    MPI_Comm comm_;
    const bool friction_;
    std::vector<ContactNode> nodes_;
    double tangential_scale_ = 1.0;
    std::vector<unsigned int> slipping_;  // indices into nodes_, ascending
    std::map<types::global_dof_index, unsigned int> slipping_dof_;  // any of their DoFs → node
    bool nonsymmetric_ = false;
  };
}  // namespace clearjoint::fe::detail
