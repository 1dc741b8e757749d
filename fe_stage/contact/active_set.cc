// The active-set decisions after a solve: which nodes are in contact, which of them stick or
// slip (Coulomb), and the slip directions of the next solve — the semi-smooth complementarity
// of Hüeber–Stadler–Wohlmuth with the cycle breakers and relaxation described below.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  ContactModel::ActiveSetChange ContactModel::update_active_set(const double c,
                                                                const double eps_g,
                                                                double &omega,
                                                                bool &relaxation_history)
  {
    // Normal: active where λ − c·ĝ > 0. Friction (the same semi-smooth complementarity,
    // Hüeber–Stadler–Wohlmuth): with t_T the tangential contact force and Δs_T the slip in
    // this increment, z = t_T − c·Δs_T; stick where |z| ≤ μ(λ − c·ĝ), else slip in the
    // direction e = z/|z| (the friction force μλ·e of the next solve; iterated until the
    // sets settle and no direction changes by more than 1e-5).
    unsigned int n_changed = 0;
    double max_direction_change = 0.0;
    double relax_num = 0.0, relax_den = 0.0;  // Σ r_old·(r − r_old), Σ |r − r_old|²
    std::vector<Tensor<1, dim>> direction_target(nodes_.size());
    for (unsigned int i = 0; i < nodes_.size(); ++i)
      {
        auto &cn = nodes_[i];
        if (!cn.candidate)
          continue;
        const double lambda_trial = cn.lambda - c * cn.gap;
        bool now = lambda_trial > c * eps_g;
        // With friction a node at the edge of the contact zone can cycle: active it pulls
        // (λ < 0, a fraction of a percent of the largest nodal force), released it
        // penetrates by ~1e-4 δ_max. After two flips it stays active (exact
        // non-penetration; the small pull stays in the force). Frictionless contact
        // does not cycle and is left as it is.
        if (friction_ && cn.candidate && now != cn.active && ++cn.contact_flips > 2)
          now = true;
        bool stick = cn.stick;
        if (friction_ && now)
          {
            // (c ×0.01 … ×100 here converged slower or not at all)
            const Tensor<1, dim> z =
              tangential(cn.traction, cn.n) -
              c * tangential(cn.relative - cn.relative_converged, cn.n);
            const double bound = scene_.contact.mu * lambda_trial;
            stick = z.norm() <= bound + c * eps_g;
            // A node on the stick/slip boundary (|t_T| = μλ with no slip) can flip
            // between the two every iteration; after two flips it stays slipping with
            // its direction frozen: its force is μλ (Coulomb's bound) and its slip in
            // this increment ~0 — both states' answer — and a direction that follows a
            // ~0 slip would only oscillate.
            if (cn.active && stick != cn.stick && ++cn.stick_slip_flips > 2)
              stick = false;
            const bool frozen = cn.stick_slip_flips > 2 && cn.active && !cn.stick;
            if (!stick && !frozen)
              {
                const Tensor<1, dim> e = z / z.norm();
                if (cn.active && !cn.stick)
                  {
                    direction_target[i] = e;
                    const Tensor<1, dim> r = e - cn.slip_direction;
                    if (cn.owned)
                      {
                        max_direction_change = std::max(max_direction_change, r.norm());
                        const Tensor<1, dim> d = r - cn.direction_update;
                        relax_num += cn.direction_update * d;
                        relax_den += d * d;
                      }
                  }
                else
                  {
                    cn.slip_direction = e;  // starts slipping: no history
                    cn.direction_update = Tensor<1, dim>();
                  }
              }
          }
        if (cn.owned && (now != cn.active || (friction_ && now && stick != cn.stick)))
          ++n_changed;
        cn.active = now;
        cn.stick = stick;
      }
    n_changed = Utilities::MPI::sum(n_changed, comm_);
    if (friction_)
      {
        // The slip directions converge linearly (ratio ≈ 0.45 on the radial study):
        // relax their update e ← e + ω (e_target − e), ω from the last two updates
        // (Irons–Tuck), kept in [0.1, 4] and restarted at 1 when the sets change.
        relax_num = Utilities::MPI::sum(relax_num, comm_);
        relax_den = Utilities::MPI::sum(relax_den, comm_);
        if (n_changed != 0 || !relaxation_history || relax_den <= 0.0)
          omega = 1.0;
        else
          omega = std::clamp(-omega * relax_num / relax_den, 0.1, 4.0);
        relaxation_history = n_changed == 0;
        for (unsigned int i = 0; i < nodes_.size(); ++i)
          if (direction_target[i].norm() > 0.0)
            {
              auto &cn = nodes_[i];
              const Tensor<1, dim> r = direction_target[i] - cn.slip_direction;
              const Tensor<1, dim> e = tangential(cn.slip_direction + omega * r, cn.n);
              cn.slip_direction = e / e.norm();
              cn.direction_update = r;
            }
      }
    return {n_changed, max_direction_change};
  }
} // namespace clearjoint::fe::detail
