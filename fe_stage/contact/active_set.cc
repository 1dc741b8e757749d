// The active-set decisions after a solve: which nodes are in contact, which of them stick or
// slip (Coulomb), and the linearisation of each slipping node's friction force for the next
// solve — one step of a semi-smooth Newton method on the complementarity functions of
// Hüeber–Stadler–Wohlmuth (2008), in the projection form of contact/coulomb_ssn.h.
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/coulomb_ssn.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace clearjoint::fe::detail
{
  ContactProblem::ContactProblem(const FeScene &scene, const DofSpace &dofs, MPI_Comm comm)
    : scene_(scene)
    , dofs_(dofs)
    , comm_(comm)
    , friction_(scene.contact.mu > 0.0)
  {}

  // Friction's constant c_T only steers the Newton path: a converged state (settled sets,
  // slip law met) is the same for every c_T (docs/fe.md). A few nodes at the stick/slip border
  // can flip every iteration at a given c_T (seen with hanging nodes in the contact zone, and
  // in the rolling study); each 8 iterations that have not settled after the first 12
  // therefore take c_T down by 0.3, to 1e-3 of the scene's value at most.
  void ContactProblem::reset_tangential_scale()
  {
    tangential_scale_ = scene_.contact.tangential_scale;
  }

  bool ContactProblem::soften_tangential_scale(const unsigned int iteration, const bool cycles)
  {
    constexpr unsigned int patient = 12, every = 8;
    const bool unsettled = iteration >= patient && (iteration - patient) % every == 0;
    if (friction_ && (unsettled || cycles) &&
        tangential_scale_ > 1.001e-3 * scene_.contact.tangential_scale)
      {
        tangential_scale_ *= 0.3;
        return true;
      }
    return false;
  }

  bool ContactProblem::collect_slipping()
  {
    slipping_.clear();
    slipping_dof_.clear();
    if (friction_)
      for (unsigned int i = 0; i < nodes_.size(); ++i)
        if (nodes_[i].candidate && nodes_[i].active && !nodes_[i].stick)
          {
            slipping_.push_back(i);
            for (const auto d : nodes_[i].dofs)
              slipping_dof_[d] = i;
          }
    nonsymmetric_ = Utilities::MPI::max(slipping_.empty() ? 0u : 1u, comm_) > 0;
    return nonsymmetric_;
  }

  bool ContactProblem::choose_constrained_component(ContactNode &cn, const Tensor<1, dim> &n) const
  {
    std::array<unsigned int, dim> order = {0, 1, 2};
    std::sort(order.begin(), order.end(),
              [&](unsigned a, unsigned b) { return std::abs(n[a]) > std::abs(n[b]); });
    for (const unsigned int c : order)
      if (std::abs(n[c]) > 0.3 && !dofs_.fixed().is_constrained(cn.dofs[c]))
        {
          cn.constrained_component = c;
          return true;
        }
    return false;
  }

  double ContactProblem::largest_normal_force(const double c, const double band) const
  {
    double largest = 0.0;
    for (const auto &cn : nodes_)
      if (cn.candidate && cn.owned && cn.lambda - c * cn.gap > band)
        largest = std::max(largest, cn.lambda);
    return Utilities::MPI::max(largest, comm_);
  }

  ContactProblem::Change ContactProblem::update_active_set(const double c, const double eps_g)
  {
    // Normal: with ξ = λ − c·ĝ, active where ξ > 0 (the primal–dual active set, step-41).
    // Friction, with t the tangential contact force and s_T the slip in this increment,
    // w = t − c·s_T: stick where |w| ≤ μξ, else slip with the friction force μξ·w/|w|, whose
    // linearisation about this iterate (direction ŵ = w/|w|, κ = μξ/|w| < 1) the next solve
    // uses (contact_rows.cc). Nothing is frozen or relaxed: once the sets settle, the slip law's
    // residual |t − μλŵ| falls quadratically.
    unsigned int n_changed = 0;
    double slip_residual = 0.0;
    std::string changed;
    const double mu = scene_.contact.mu;
    const double band = c * eps_g;  // the round-off band of contact/coulomb_ssn.h's law
    // At the edge of Coulomb's cone (|w| = μξ) stick and slip are the same state: a node
    // there keeps its label. Without this a node whose |w| − μξ alternates between +1.3e-6
    // and +2e-7 N flipped stick ↔ slip for all 100 iterations of an impact's step at the
    // journal's reversal (its largest nodal force 1.09 N, the slip law settled to 1e-13 N;
    // docs/benchmarks.md "Adaptive meshes for the impact"). Within 1e-5 of the largest nodal
    // force, Coulomb's inequality holds to that at the few nodes on the edge either way.
    const double force_scale = largest_normal_force(c, band);
    const double edge = friction_ ? edge_tolerance * force_scale : 0.0;
    for (auto &cn : nodes_)
      {
        if (!cn.candidate)
          continue;
        // the node's class by contact/coulomb_ssn.h's law, within the round-off band c·ε_g
        const double xi = cn.lambda - c * cn.gap;
        const bool now = coulomb_state(xi, 0.0, 0.0, band) != FrictionState::inactive;
        bool stick = cn.stick;
        double margin = 0.0;  // [N] |w| − μξ: how far the node is from Coulomb's cone's edge
        if (friction_ && now)
          {
            const Tensor<1, dim> t = tangential(traction(cn), cn.n);
            const Tensor<1, dim> w = t - tangential_scale_ * c * slip_increment(cn);
            margin = w.norm() - mu * xi;
            stick = cn.active ? keeps_or_decides_stick(xi, w.norm(), mu, band, cn.stick, edge) :
                                coulomb_state(xi, w.norm(), mu, band) == FrictionState::stick;
            if (!stick)
              {
                if (cn.owned && cn.active && !cn.stick)
                  slip_residual =
                    std::max(slip_residual, (t - (mu * cn.lambda / w.norm()) * w).norm());
                cn.slip_direction = w / w.norm();
                cn.kappa = mu * xi / w.norm();
              }
          }
        if (cn.owned && (now != cn.active || (friction_ && now && stick != cn.stick)))
          {
            ++n_changed;
            // name the first few (contact chatter is read off these, in mm)
            if (n_changed <= 4)
              {
                auto state = [&](const bool active, const bool sticks) {
                  return !active ? "open" : !friction_ ? "closed" : sticks ? "stick" : "slip";
                };
                char where[96];
                std::snprintf(where, sizeof where, "(%.4g, %.4g, %.4g) mm ", 1e3 * cn.X[0],
                              1e3 * cn.X[1], 1e3 * cn.X[2]);
                changed += (changed.empty() ? "" : ", ") + std::string(where) +
                           state(cn.active, cn.stick) + " -> " + state(now, stick);
                if (friction_ && now && cn.active)  // a stick/slip change: how near the edge
                  {
                    char edge[64];
                    std::snprintf(edge, sizeof edge, " (|w| - mu xi %.3g N of mu xi %.3g N)",
                                  margin, mu * xi);
                    changed += edge;
                  }
              }
          }
        cn.active = now;
        cn.stick = stick;
      }
    return {Utilities::MPI::sum(n_changed, comm_), Utilities::MPI::max(slip_residual, comm_),
            force_scale, changed};
  }
}  // namespace clearjoint::fe::detail
