// Where the rolling study's journal is, as the contact sees it: a value the spin stepper sets
// (solve/spin_stepper.cc) and the pairing and contact rows read. The model is computed in the
// bearing's co-rotating frame (turned to φ = ω_B t); the journal's axis sits at `centre` in that
// frame, and a deformable journal — computed in its own frame, turned by ψ = γ − φ relative
// to the bearing's frame about its axis, its core clamped there — places its point X (as
// meshed, axis through `axis_mesh`) with displacement u at c + Q(ψ)(X − a + u).
//
// Outside the rolling study `turning` is false and the frame is the identity: every partner's
// displacement is seen unrotated.
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/core/dim.h"

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <cmath>

namespace clearjoint::fe::detail
{
  struct JournalFrame
  {
    bool turning = false;  // the rolling study
    double phi = 0.0;      // [rad] the bearing's frame angle now
    /// [m] the journal's axis point in the bearing's frame at the last converged step, now
    std::array<double, 3> centre_previous{}, centre{};
    /// [rad] the deformable journal's turn ψ relative to the frame at the last converged
    /// step, and its change since then: ψ now = psi_converged + delta_psi
    double psi_converged = 0.0, delta_psi = 0.0;
    /// [m] the deformable journal's axis point as meshed
    Tensor<1, dim> axis_mesh;
    /// Q: every partner's displacement as a slave node sees it is Q u_p (identity unless the
    /// rolling study's deformable journal turns; its partners are all journal nodes).
    Tensor<2, dim> partner_rotation = Tensor<2, dim>(unit_symmetric_tensor<dim>());

    /// [rad] the deformable journal's turn relative to the bearing's frame now.
    double psi() const { return psi_converged + delta_psi; }

    static Tensor<2, dim> rotation_z(const double angle)
    {
      const double cs = std::cos(angle), sn = std::sin(angle);
      return Tensor<2, dim>({{cs, -sn, 0.0}, {sn, cs, 0.0}, {0.0, 0.0, 1.0}});
    }

    /// Where the deformable journal's point X (as meshed) with displacement u sits in the
    /// bearing's frame now.
    Point<dim> place(const Point<dim> &X, const Tensor<1, dim> &u) const
    {
      const Point<dim> c(centre[0], centre[1], centre[2]);
      return c + rotation_z(psi()) * (X - Point<dim>(axis_mesh) + u);
    }

    /// Σ_p w_p Q u_p: the node's partners' displacement v as the slave node sees it (ghosted
    /// v; Q the partners' turn now unless given).
    Tensor<1, dim> partner_displacement(const ContactNode &cn,
                                        const TrilinosWrappers::MPI::Vector &v,
                                        const Tensor<2, dim> *Q = nullptr) const
    {
      Tensor<1, dim> s;
      for (const auto &p : cn.partners)
        for (unsigned int c = 0; c < dim; ++c)
          s[c] += p.weight * v[p.dofs[c]];
      return (Q ? *Q : partner_rotation) * s;
    }

    /// How the journal's frame at centre c and turn ψ moves the node's partner combination
    /// from where it was meshed: (Σ w) c + Q(ψ)(P − (Σ w) a) − P.
    Tensor<1, dim> partner_motion(const ContactNode &cn, const std::array<double, 3> &c,
                                  const double psi_at) const
    {
      const Tensor<1, dim> P = cn.partner_X;
      return cn.partner_weight * Tensor<1, dim>({c[0], c[1], c[2]}) +
             rotation_z(psi_at) * (P - cn.partner_weight * axis_mesh) - P;
    }
  };
}  // namespace clearjoint::fe::detail
