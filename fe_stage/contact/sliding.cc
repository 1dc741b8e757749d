// Finite sliding (contact.sliding: finite): after every converged increment the mortar search is
// done again between the surfaces as they are now, x = X + u, so a node is coupled to the
// partners that face it after the surfaces have slid past each other, not to those that faced
// it in the reference configuration. ContactPattern's second file (contact/contact_pattern.h).
#include "fe_stage/contact/contact_pattern.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_tools.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace clearjoint::fe::detail
{
  /// The new couplings replace the old in place when they fit the sparsity pattern (the same
  /// candidate nodes, each node's new partners among its old ones); otherwise the pattern,
  /// the ghost DoFs and the static matrix are rebuilt with them, the displacement and each
  /// node's active/stick state kept. Either way each node's g0 is set so that its linearised
  /// gap at the converged u is the weighted gap found there, and slip counts from u_start (the
  /// increment's start) with the new partners. Returns how far the coupling moved (the
  /// largest over the candidate nodes of Σ_m |ΔC_sm| and |Δgap|/δ_max). `rebuild` forces the
  /// rebuild: after a failed attempt restored contact_.nodes() whose partners the pattern no
  /// longer has (pair_restored).
  double ContactPattern::follow_sliding(const TrilinosWrappers::MPI::Vector &u_start,
                                        const bool rebuild)
  {
    // How much the coupling moved: per node the sum of |C_new − C_old| over its partners
    // [1] and the change of its linearised gap at u [m] (against δ_max).
    const double delta_max = scene_.loading.delta_max;
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(bodies_.mapping(), dofs_.handler(), support);
    const ContactPairing::Nodes fresh = pairing_.find(support, &state_.u());

    // the new couplings fit the pattern when every new candidate was one in the pattern, with
    // the same constrained component and its new partners among the pattern's
    bool fits = fresh.size() == contact_.nodes().size();
    for (const auto &cn : contact_.nodes())
      {
        if (!fits)
          break;
        const auto it = fresh.find(cn.dofs[0]);
        if (it == fresh.end())
          {
            fits = false;
            break;
          }
        if (!it->second.candidate)
          continue;
        const auto in_pattern = pattern_partners_.find(cn.dofs[0]);
        if (in_pattern == pattern_partners_.end() ||
            it->second.constrained_component != in_pattern->second.component)
          {
            fits = false;
            break;
          }
        for (const auto &p : it->second.partners)
          fits = fits && in_pattern->second.partners.count(p.dofs[0]) > 0;
      }
    double change = 0.0;
    for (const auto &cn : contact_.nodes())
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
      for (auto &cn : contact_.nodes())
        {
          const ContactNode &f = fresh.at(cn.dofs[0]);
          cn.partners = f.partners;
          // the pattern's candidates stay candidates (their lines are in it)
          cn.candidate = pattern_partners_.count(cn.dofs[0]) > 0;
          cn.active = cn.active && cn.candidate;
          cn.constrained_component = f.constrained_component;
          cn.partner_X = f.partner_X;
          cn.partner_weight = f.partner_weight;
          cn.g0 = f.g0;
          cn.n = f.n;
        }
    else
      {
        const TrilinosWrappers::MPI::Vector u_owned = state_.u_owned();
        const TrilinosWrappers::MPI::Vector u_ghosted = state_.u();  // the old ghost layout
        std::map<types::global_dof_index, ContactNode> old_state;
        for (const auto &cn : contact_.nodes())
          old_state.emplace(cn.dofs[0], cn);
        // the DoF numbering stays (same mesh); the ghosts, the pattern and A_static change
        mesh_.prepare_mesh(&u_ghosted);
        state_.u_owned() = u_owned;
        state_.publish();
        for (auto &cn : contact_.nodes())
          {
            const auto it = old_state.find(cn.dofs[0]);
            if (it == old_state.end())
              continue;  // a node that came into reach starts open
            cn.active = it->second.active && cn.candidate;
            cn.stick = it->second.stick;
          }
        if (system_.kind() == Assembler::Operator::tangent)  // elastoplastic
          system_.keep_elastic_operator();                   // the new pattern's elastic matrices
        ++n_rebuilds_;
      }
    // Friction: the slip of the (re-solved or next) increment counts from its start, u_start,
    // measured with the new partners.
    // The turning journal: the slip counts from the step's start, where the journal's frame
    // had the last converged pose (frame_.centre_previous, ψ of the last converged step):
    // the new partners' frame motion and turn there. (The pose now: set_obstacle_position.)
    const bool turning = plan_.journal_turns_deformable();
    const Tensor<2, dim> Q_start =
      turning ? JournalFrame::rotation_z(frame_.psi_converged) : frame_.partner_rotation;
    if (turning)
      {
        evaluation_.set_obstacle_position(0.0);
        for (auto &cn : contact_.nodes())
          cn.obstacle_u_converged =
            frame_.partner_motion(cn, frame_.centre_previous, frame_.psi_converged);
      }
    TrilinosWrappers::MPI::Vector start(dofs_.owned(), dofs_.relevant(), comm_);
    start = u_start;
    for (auto &cn : contact_.nodes())
      {
        for (unsigned int c = 0; c < dim; ++c)
          cn.relative_converged[c] = start[cn.dofs[c]];
        cn.relative_converged -=
          frame_.partner_displacement(cn, start, &Q_start) + cn.obstacle_u_converged;
      }
    // relative displacements and gaps at u with the new couplings
    evaluation_.evaluate_contact(0.0);
    return change;
  }

  void ContactPattern::pair_restored(const TrilinosWrappers::MPI::Vector &u,
                                     const unsigned int rebuilds_saved)
  {
    // finite sliding rebuilt the pattern for couplings of the failed attempt: pair the
    // restored state again so that the pattern holds its partners (the rolling study's turning
    // journal, not finite sliding, searches again at its next evaluation anyway)
    if (finite_sliding() && n_rebuilds_ != rebuilds_saved)
      follow_sliding(u, true);
  }
}  // namespace clearjoint::fe::detail
