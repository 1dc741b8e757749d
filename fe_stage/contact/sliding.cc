// Finite sliding (contact.sliding: finite): after every converged increment the mortar search is
// done again between the surfaces as they are now, x = X + u, so a node is coupled to the
// partners that face it after the surfaces have slid past each other, not to those that faced
// it in the reference configuration.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  /// The new couplings replace the old in place when they fit the sparsity pattern (the same
  /// candidate nodes, each node's new partners among its old ones); otherwise the pattern,
  /// the ghost DoFs and the static matrix are rebuilt with them, the displacement and each
  /// node's active/stick state kept. Either way each node's g0 is set so that its linearised
  /// gap at the converged u is the weighted gap found there, and slip counts from u_start (the
  /// increment's start) with the new partners. Returns how far the coupling moved (the
  /// largest over the candidate nodes of Σ_m |ΔC_sm| and |Δgap|/δ_max). `rebuild` forces the
  /// rebuild: after a failed attempt restored nodes_ whose partners the pattern no longer has.
  double ContactModel::follow_sliding(const TrilinosWrappers::MPI::Vector &u_start,
                                      const bool rebuild)
  {
    // How much the coupling moved: per node the sum of |C_new − C_old| over its partners
    // [1] and the change of its linearised gap at u [m] (against δ_max).
    const double delta_max = scene_.loading.delta_max;
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(*mapping_, dof_handler_, support);
    std::map<types::global_dof_index, ContactNode> fresh;
    find_mortar_contact_nodes(support, fresh, &solution_);

    auto partner_set = [](const ContactNode &cn) {
      std::set<types::global_dof_index> s;
      for (const auto &p : cn.partners)
        s.insert(p.dofs[0]);
      return s;
    };
    bool fits = fresh.size() == nodes_.size();
    for (const auto &cn : nodes_)
      {
        if (!fits)
          break;
        const auto it = fresh.find(cn.dofs[0]);
        if (it == fresh.end() || (it->second.candidate && !cn.candidate) ||
            it->second.constrained_component != cn.constrained_component)
          {
            fits = false;
            break;
          }
        const auto old_partners = partner_set(cn);
        for (const auto &p : it->second.partners)
          fits = fits && old_partners.count(p.dofs[0]) > 0;
      }
    double change = 0.0;
    for (const auto &cn : nodes_)
      {
        const auto it = fresh.find(cn.dofs[0]);
        if (!cn.candidate || it == fresh.end())
          continue;
        std::map<types::global_dof_index, double> dc;
        for (const auto &p : cn.partners)
          dc[p.dofs[0]] -= p.weight;
        for (const auto &p : it->second.partners)
          dc[p.dofs[0]] += p.weight;
        double sum = 0.0;
        for (const auto &[d, c] : dc)
          sum += std::abs(c);
        // the weighted gap found at x against the linearised gap the last solve had at u
        const double gap_change = std::abs(it->second.gap - cn.gap) / delta_max;
        change = std::max({change, sum, gap_change});
      }
    // collective: every rank takes the same branch (the rebuild is collective)
    fits = !rebuild && Utilities::MPI::min(fits ? 1u : 0u, comm_) == 1u;
    change = Utilities::MPI::max(change, comm_);
    if (fits)
      for (auto &cn : nodes_)
        {
          const ContactNode &f = fresh.at(cn.dofs[0]);
          cn.partners = f.partners;
          cn.g0 = f.g0;
        }
    else
      {
        const TrilinosWrappers::MPI::Vector u_owned = solution_owned_;
        const TrilinosWrappers::MPI::Vector u_ghosted = solution_;  // the old ghost layout
        std::map<types::global_dof_index, ContactNode> old_state;
        for (const auto &cn : nodes_)
          old_state.emplace(cn.dofs[0], cn);
        // the DoF numbering stays (same mesh); the ghosts, the pattern and A_static change
        search_displacement_ = &u_ghosted;
        prepare_mesh();
        search_displacement_ = nullptr;
        solution_owned_ = u_owned;
        solution_ = solution_owned_;
        for (auto &cn : nodes_)
          {
            const auto it = old_state.find(cn.dofs[0]);
            if (it == old_state.end())
              continue;  // a node that came into reach starts open
            cn.active = it->second.active && cn.candidate;
            cn.stick = it->second.stick;
          }
        ++n_sliding_rebuilds_;
      }
    // Friction: the slip of the (re-solved or next) increment counts from its start, u_start,
    // measured with the new partners.
    TrilinosWrappers::MPI::Vector start(owned_, relevant_, comm_);
    start = u_start;
    for (auto &cn : nodes_)
      for (unsigned int c = 0; c < dim; ++c)
        {
          cn.relative_converged[c] = start[cn.dofs[c]];
          for (const auto &p : cn.partners)
            cn.relative_converged[c] -= p.weight * start[p.dofs[c]];
        }
    evaluate_contact(0.0);  // relative displacements and gaps at u with the new couplings
    return change;
  }
} // namespace clearjoint::fe::detail
