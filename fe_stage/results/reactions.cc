// Nodal reactions K u (hanging shares moved to their masters), the contact state of every node,
// and the increment's forces and checks.
#include "fe_stage/solve/contact_solve.h"

#include "fe_stage/core/step_failure.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace clearjoint::fe::detail
{
  /// λ_i = (K u)_i · n_i and ĝ_i = g0_i + n_i · u_i for every candidate node (ghosted values,
  /// so every rank evaluates the same numbers for the nodes it shares).
  void ContactSolve::evaluate_contact(const double /*delta: in each node's g0, obstacle_u*/)
  {
    system_.operator_matrix().vmult(state_.forces(), state_.u_owned());
    // the constraint forces: dynamic (c_m M + c_k K) u − b; elastoplastic K_t u − b
    if (system_.has_load())
      state_.forces() -= system_.load();
    dofs_.condense_hanging(state_.forces());
    TrilinosWrappers::MPI::Vector forces(dofs_.owned(), dofs_.relevant(), comm_);
    forces = state_.forces();
    for (auto &cn : contact_.nodes())
      {
        for (unsigned int c = 0; c < dim; ++c)
          {
            cn.traction[c] = forces[cn.dofs[c]];
            cn.relative[c] = state_.u()[cn.dofs[c]];
          }
        // the partners (turned into the slave's frame), and the rigid motion of the obstacle's
        // surface point or of the partners' frame (0 for two bodies at rest)
        cn.relative -= frame_.partner_displacement(cn, state_.u()) + cn.obstacle_u;
        cn.lambda = cn.traction * cn.n;
        // ĝ = g0 + n·(u − Σ w Q u_p); the obstacle's (or the partners' frame's) motion is
        // already in g0
        cn.gap = cn.g0 + cn.n * (cn.relative + cn.obstacle_u);
      }
  }

  /// The increment's forces (contact, supports, loaded set; full body), active and slipping
  /// nodes, penetration and pressure range, and the checks that make a wrong answer a failure.
  void ContactSolve::record_forces(const double delta, IncrementRecord &rec)
  {
    // Forces and checks.
    double f_contact = 0.0, max_pen = 0.0;
    double p_min = std::numeric_limits<double>::max(), p_max = -p_min;
    unsigned int n_act = 0, n_slip = 0;
    // the y-force a node's contact passes on to the bearing: normal only, or with its friction
    // force (the force on the slave node; on the bearing the opposite when the journal is slave)
    auto contact_force_y = [&, sign = slave_sign()](const ContactNode &cn) {
      return sign * (contact_.friction() ? cn.traction[1] : cn.lambda * cn.n[1]);
    };
    Point<dim> deepest;
    for (const auto &cn : contact_.nodes())
      if (cn.owned)
        {
          if (-cn.gap > max_pen)
            max_pen = -cn.gap, deepest = cn.X;
          if (cn.active)
            {
              ++n_act;
              if (contact_.friction() && !cn.stick)
                ++n_slip;
              f_contact -= contact_force_y(cn);
              if (cn.weight > 0.0)
                {
                  p_min = std::min(p_min, cn.lambda / cn.weight);
                  p_max = std::max(p_max, cn.lambda / cn.weight);
                }
            }
        }
    double f_support = 0.0, f_load = 0.0;
    for (const auto d : dofs_.support_y_dofs())
      f_support += state_.forces()[d];
    for (const auto d : dofs_.loaded_y_dofs())
      f_load -= state_.forces()[d];
    // Where a contact partner's y-DoF is itself driven (the journal's rim on its end face),
    // the contact force reaches that DoF through the constraint, not through K u: add it.
    for (const auto &cn : contact_.nodes())
      if (cn.active && cn.owned)
        for (const auto &p : cn.partners)
          if (p.driven_y)
            f_load -= p.weight * contact_force_y(cn);
    rec.force_load = plan_.deformable_partner ?
                       bodies_.symmetry_factor() * Utilities::MPI::sum(f_load, comm_) :
                       bodies_.symmetry_factor() * Utilities::MPI::sum(f_contact, comm_);
    rec.force = bodies_.symmetry_factor() * Utilities::MPI::sum(f_contact, comm_);
    rec.force_support = bodies_.symmetry_factor() * Utilities::MPI::sum(f_support, comm_);
    rec.n_active = Utilities::MPI::sum(n_act, comm_);
    rec.n_slip = Utilities::MPI::sum(n_slip, comm_);
    rec.max_penetration = Utilities::MPI::max(max_pen, comm_);
    rec.pressure_min = Utilities::MPI::min(p_min, comm_);
    rec.pressure_max = Utilities::MPI::max(p_max, comm_);
    if (contact_.friction())
      record_coulomb_check(rec);
    if (!std::isfinite(rec.force) || !std::isfinite(rec.force_support))
      throw StepFailure{"non-finite contact force"};
    // A pushed joint must touch somewhere: no active node means the journal slipped between
    // the contact nodes (a rim patch smaller than the cells), and F = 0 would be a wrong answer.
    if (rec.n_active == 0 && plan_.must_touch)
      throw StepFailure{"no contact node touches the journal at delta = " + format_value(delta) +
                        " m: the mesh is too coarse where the journal touches (raise "
                        "mesh.contact_refinements or mesh.global_refinements)"};
    // Watched (non-candidate) nodes must not penetrate: if one does, the candidate window was
    // too small and the result would be wrong, so the run stops instead.
    if (rec.max_penetration > 1e-6 * scene_.loading.delta_max)
      {
        // the deepest node's position, from the rank that holds it
        const bool mine = max_pen == rec.max_penetration;
        std::array<double, dim> where{};
        for (unsigned int c = 0; c < dim; ++c)
          where[c] = Utilities::MPI::max(mine ? deepest[c] : -1e300, comm_);
        throw StepFailure{"penetration " + format_value(rec.max_penetration) +
                          " m at the contact-surface node at (" + format_value(where[0]) + ", " +
                          format_value(where[1]) + ", " + format_value(where[2]) +
                          ") m (candidate window too small)"};
      }
  }

  /// How well the converged state satisfies Coulomb's law at every node (IncrementRecord's
  /// contact_.friction()* fields): computed from K u and the displacements, independently of the
  /// stick/slip decisions that produced them.
  void ContactSolve::record_coulomb_check(IncrementRecord &rec) const
  {
    const double mu = scene_.contact.mu;
    double lambda_max = 0.0, cone = -std::numeric_limits<double>::max(), slip_law = 0.0,
           direction = 0.0;
    for (const auto &cn : contact_.nodes())
      if (cn.owned && cn.active)
        lambda_max = std::max(lambda_max, cn.lambda);
    lambda_max = Utilities::MPI::max(lambda_max, comm_);
    // slid: the tangential relative displacement in this increment exceeds 1e-6 of the
    // increment's push (a sticking node's is 0 to round-off)
    const double slid = 1e-6 * scene_.loading.delta_max / scene_.loading.n_increments;
    for (const auto &cn : contact_.nodes())
      if (cn.owned && cn.active)
        {
          const Tensor<1, dim> t = tangential(contact_.traction(cn), cn.n);
          cone = std::max(cone, t.norm() - mu * cn.lambda);
          if (!cn.stick)
            {
              slip_law = std::max(slip_law, std::abs(t.norm() - mu * cn.lambda));
              const Tensor<1, dim> s = contact_.slip_increment(cn);
              if (s.norm() > slid && t.norm() > 0.0)
                direction = std::max(direction, 1.0 + (t / t.norm()) * (s / s.norm()));
            }
        }
    const double scale = mu * lambda_max > 0.0 ? mu * lambda_max : 1.0;
    cone = Utilities::MPI::max(cone, comm_);
    // ≤ 0 when every node is inside or on its cone: reported as 0 (nothing exceeds it)
    rec.friction_cone_excess = lambda_max > 0.0 ? std::max(0.0, cone / scale) : 0.0;
    rec.friction_slip_law_error = Utilities::MPI::max(slip_law, comm_) / scale;
    rec.friction_direction_error = Utilities::MPI::max(direction, comm_);
  }
}  // namespace clearjoint::fe::detail
