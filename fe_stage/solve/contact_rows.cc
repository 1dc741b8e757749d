// What the active set adds to the system (ContactSolve, solve/contact_solve.h): the rigid
// obstacle's gaps at δ, nodal areas, the constraint lines of active nodes (normal, or all free
// components when sticking) and the friction rows of slipping nodes.
#include "fe_stage/solve/contact_solve.h"

#include "fe_stage/solve/rolling_kinematics.h"

#include "common/error.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <set>

namespace clearjoint::fe::detail
{
  /// Nodal areas w_i = ∫ φ_i dA over the contact surface: the contact pressure of node i is
  /// λ_i / w_i (exact for a uniform pressure; Q2 face weights are all positive).
  void ContactSolve::compute_nodal_weights()
  {
    const QGauss<dim - 1> fq(dofs_.fe().degree + 1);
    FEFaceValues<dim> fv(bodies_.mapping(), dofs_.fe(), fq, update_values | update_JxW_values);
    TrilinosWrappers::MPI::Vector w(dofs_.owned(), comm_);
    std::vector<types::global_dof_index> dofs(dofs_.fe().n_dofs_per_cell());
    Vector<double> cell_w(dofs_.fe().n_dofs_per_cell());
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == slave_surface_id())
            {
              fv.reinit(cell, f);
              cell_w = 0.0;
              for (unsigned int i = 0; i < dofs_.fe().n_dofs_per_cell(); ++i)
                for (const unsigned int q : fv.quadrature_point_indices())
                  cell_w(i) += fv.shape_value(i, q) * fv.JxW(q);
              cell->get_dof_indices(dofs);
              w.add(dofs, cell_w);
            }
    w.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector wg(dofs_.owned(), dofs_.relevant(), comm_);
    wg = w;
    for (auto &cn : contact_.nodes())
      cn.weight = wg[cn.dofs[0]];
  }

  /// The rigid obstacle at δ: each node's gap g0, normal n and the displacement of the
  /// obstacle's surface point facing it (a translation by −δ e_y; the rolling study: the
  /// turning journal seen from the bearing's co-rotating frame, accumulated step by step).
  ///
  /// The gap is linear in u, ĝ = g0 + n·u. The studies with small displacements take g0 and n
  /// at the node's reference position X. The rolling study takes them at the current iterate
  /// x = X + u_k (each material Newton iteration calls this again), ĝ = g(x) + n(x)·(u − u_k):
  /// there the plastic wake drags the bore's nodes tens of µm along the surface, and a normal
  /// from X would no longer pass through the journal's axis — the frictionless contact would
  /// then exert a moment on the journal and do work, and the drive's torque came out 35 % low
  /// (measured; docs/fe.md "Rolling study").
  ///
  /// The rolling study's deformable journal: each bore node's partners are journal nodes, their
  /// combination placed at c + Q(ψ)(P − a) + Q Σ w u_p (P = Σ w X_p as meshed); the partners'
  /// frame moves it by obstacle_u = (Σ w) c + Q (P − (Σ w) a) − P, and the gap along the
  /// journal's radius through the node's current position (as for the rigid journal: no
  /// moment from the normal force) is ĝ = n·(X + u − P − obstacle_u − Σ w Q u_p).
  void ContactSolve::set_obstacle_position(const double delta)
  {
    if (frame_.turning)
      obstacle_.frame_angle = frame_.phi;
    if (plan_.journal_turns_deformable())
      {
        frame_.partner_rotation = JournalFrame::rotation_z(frame_.psi());
        for (auto &cn : contact_.nodes())
          {
            cn.obstacle_u = frame_.partner_motion(cn, frame_.centre, frame_.psi());
            Tensor<1, dim> r;  // from the journal's axis to the node, in the cross-section
            for (unsigned int k = 0; k + 1 < dim; ++k)
              r[k] = cn.X[k] + state_.u()[cn.dofs[k]] - frame_.centre[k];
            cn.n = r / r.norm();
            cn.g0 = cn.n * (cn.X - cn.partner_X - cn.obstacle_u);
          }
        return;
      }
    for (auto &cn : contact_.nodes())
      if (!cn.two_body)
        {
          if (!frame_.turning)
            obstacle_gap(cn.X, delta, cn.g0, cn.n);
          else
            {
              // in the cross-section only: whether a node faces the journal's length stays
              // decided by its reference z (a node on the journal's end plane would
              // otherwise leave it by its Poisson expansion)
              Tensor<1, dim> u;
              for (unsigned int c = 0; c + 1 < dim; ++c)
                u[c] = state_.u()[cn.dofs[c]];
              double g = 0.0;
              if (!obstacle_gap(cn.X + u, delta, g, cn.n))
                throw NumericalError("fe_stage: a contact-surface node left the rolling "
                                     "journal's length");
              cn.g0 = g - cn.n * u;
            }
          if (!frame_.turning)
            cn.obstacle_u = Tensor<1, dim>({0.0, -delta, 0.0});
          else
            {
              const auto d =
                rolling::journal_surface_step(frame_.centre_previous, frame_.centre,
                                              scene_.geometry.R_J(), {cn.n[0], cn.n[1], cn.n[2]},
                                              frame_.delta_psi);
              cn.obstacle_u = cn.obstacle_u_converged + Tensor<1, dim>({d[0], d[1], d[2]});
            }
        }
  }

  /// The load at each contact node, with the shares of the hanging nodes beside it (as the
  /// traction K u − b is read in evaluate_contact): the friction rows' constant part (below).
  void ContactSolve::set_contact_load_offsets()
  {
    TrilinosWrappers::MPI::Vector load = system_.load();
    dofs_.condense_hanging(load);
    TrilinosWrappers::MPI::Vector load_ghosted(dofs_.owned(), dofs_.relevant(), comm_);
    load_ghosted = load;
    for (auto &cn : contact_.nodes())
      for (unsigned int c = 0; c < dim; ++c)
        cn.load_offset[c] = load_ghosted[cn.dofs[c]];
  }

  /// The friction force on a slipping node s, linearised about the last iterate (semi-smooth
  /// Newton, docs/fe.md): with t = P_T M (K u)_s the node's tangential contact force (M leaves
  /// out DoFs fixed by a symmetry plane: their reaction is not friction), λ = n·(K u)_s, the
  /// slip increment s_T = P_T (D u + b) (D u = u_s − Σ w_p u_p; b the obstacle's motion minus
  /// the last converged relative displacement) and w = t − c s_T, Coulomb's slip law
  /// t = μλ ŵ(u) linearised at ŵ = w/|w| is
  ///     t = F(u) = μ ŵ λ(u) + κ Q (t(u) − c s_T(u)),   κ = μλ/|w| < 1,  Q = P_T − ŵ ŵᵀ,
  /// the second term the derivative of the direction (ŵ turns by Q dw/|w|). The node's rows
  /// get K_s u − F(u) (and its partners' rows + w_p F(u), the reaction): the terms in K_s here,
  /// cell by cell (K u is a sum over cells; (K u)_s includes the shares of hanging DoFs that
  /// hang from s, as the condensed equations and the evaluation see them), the c·Q·s_T term
  /// once per node in friction_node_matrix. The contact cell's matrix is extended by the
  /// partners' rows and condensed as a whole (so the constraints' inhomogeneities reach the
  /// right-hand side too). This makes the system non-symmetric (GMRES). Returns false if the cell
  /// holds no slipping node.
  bool ContactSolve::friction_cell_matrix(const unsigned int k, FullMatrix<double> &M,
                                          std::vector<types::global_dof_index> &ext) const
  {
    const auto &dofs = system_.contact_cell_dofs(k);
    const auto &Kc = system_.contact_cell_matrix(k);
    const unsigned int n = dofs.size();
    ext = dofs;
    // The slipping nodes whose force (K u)_s this cell adds to: those among its DoFs, and
    // those a hanging DoF of the cell hangs from. The second kind matters wherever hanging
    // nodes lie inside the contact zone (adaptive meshes): a cell beside a hanging node need
    // not hold the node's masters, yet its K(h, :) reaches them through condense_hanging, as
    // the evaluation reads the force. Without those terms the Newton matrix was not the
    // derivative of the slip law it is checked against, and the stick/slip iteration stalled
    // or cycled on Kelly-refined contact zones (docs/fe.md).
    std::set<unsigned int> touched;
    for (unsigned int i = 0; i < n; ++i)
      {
        if (const int node = contact_.slipping_node_of(dofs[i]); node >= 0)
          touched.insert(node);
        if (const auto *entries = dofs_.hanging().get_constraint_entries(dofs[i]))
          for (const auto &entry : *entries)
            if (const int node = contact_.slipping_node_of(entry.first); node >= 0)
              touched.insert(node);
      }
    // per slipping node: the rows F(u) over the cell's columns (3 × n)
    std::vector<std::pair<const ContactNode *, FullMatrix<double>>> rows_of;
    for (const unsigned int node : touched)
      {
        const ContactNode &cn = contact_.nodes()[node];
        // (K u)_s over the cell's columns, with the rows of hanging DoFs that hang from s
        FullMatrix<double> Ks(dim, n);
        for (unsigned int r = 0; r < n; ++r)
          for (unsigned int c = 0; c < dim; ++c)
            {
              double share = dofs[r] == cn.dofs[c] ? 1.0 : 0.0;
              if (share == 0.0 && dofs_.hanging().is_constrained(dofs[r]))
                for (const auto &[m, coefficient] :
                     *dofs_.hanging().get_constraint_entries(dofs[r]))
                  if (m == cn.dofs[c])
                    share += coefficient;
              if (share != 0.0)
                for (unsigned int j = 0; j < n; ++j)
                  Ks(c, j) += share * Kc(r, j);
            }
        const Tensor<2, dim> Q = ContactProblem::tangent_projection(cn) -
                                 outer_product(cn.slip_direction, cn.slip_direction);
        const double mu = scene_.contact.mu;
        FullMatrix<double> F(dim, n);
        for (unsigned int j = 0; j < n; ++j)
          {
            double lambda_j = 0.0;
            for (unsigned int c = 0; c < dim; ++c)
              lambda_j += cn.n[c] * Ks(c, j);
            for (unsigned int a = 0; a < dim; ++a)
              {
                double f = mu * cn.slip_direction[a] * lambda_j;
                for (unsigned int b = 0; b < dim; ++b)
                  if (contact_.holds(cn, b))
                    f += cn.kappa * Q[a][b] * Ks(b, j);
                F(a, j) = f;
              }
          }
        rows_of.emplace_back(&cn, std::move(F));
        for (const auto d : cn.dofs)  // the node itself, when only its hanging DoFs are here
          if (std::find(ext.begin(), ext.end(), d) == ext.end())
            ext.push_back(d);
        for (const auto &p : cn.partners)
          for (const auto d : p.dofs)
            if (std::find(ext.begin(), ext.end(), d) == ext.end())
              ext.push_back(d);
      }
    if (rows_of.empty())
      return false;
    M.reinit(ext.size(), ext.size());
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        M(i, j) = Kc(i, j);
    auto local = [&](const types::global_dof_index d) {
      return std::find(ext.begin(), ext.end(), d) - ext.begin();
    };
    // the reaction on the partners, turned into their frame: + w_p Qᵀ F(u)
    const Tensor<2, dim> &Q = frame_.partner_rotation;
    for (const auto &[cn, F] : rows_of)
      for (unsigned int a = 0; a < dim; ++a)
        {
          const auto ls = local(cn->dofs[a]);
          for (unsigned int j = 0; j < n; ++j)
            M(ls, j) -= F(a, j);
          for (const auto &p : cn->partners)
            for (unsigned int b = 0; b < dim; ++b)
              if (Q[a][b] != 0.0)
                {
                  const auto lp = local(p.dofs[b]);
                  for (unsigned int j = 0; j < n; ++j)
                    M(lp, j) += p.weight * Q[a][b] * F(a, j);
                }
        }
    return true;
  }

  /// The slip term of a slipping node's linearised friction force, −κ c Q s_T(u) with
  /// s_T = P_T M (D u + b) (M: the components the contact holds, as in
  /// contact_slip_increment): rows of the node +κ c Q M (D u + b) = 0 part, rows of its partners
  /// −w_p R_pᵀ κ c Q M (D u + b), with D u = u − Σ w_p R_p u_p (R_p = frame_.partner_rotation, the
  /// identity unless the rolling study's journal turns); the constant part goes to the
  /// right-hand side. Added once per node (by the rank that owns it).
  void ContactSolve::friction_node_matrix(const ContactNode &cn, const double c,
                                          const double /*delta*/, FullMatrix<double> &M,
                                          Vector<double> &rhs,
                                          std::vector<types::global_dof_index> &ext) const
  {
    // D as (DoF list, 3 × 3 block per body point): the node +I, each partner −w_p Q (its
    // displacement turned into the slave's frame)
    const Tensor<2, dim> I(unit_symmetric_tensor<dim>());
    std::vector<std::pair<const std::array<types::global_dof_index, dim> *, Tensor<2, dim>>> points;
    points.emplace_back(&cn.dofs, I);
    for (const auto &p : cn.partners)
      points.emplace_back(&p.dofs, -p.weight * frame_.partner_rotation);
    ext.clear();
    for (const auto &[d, B] : points)
      ext.insert(ext.end(), d->begin(), d->end());
    M.reinit(ext.size(), ext.size());
    rhs.reinit(ext.size());
    const Tensor<2, dim> Q =
      ContactProblem::tangent_projection(cn) - outer_product(cn.slip_direction, cn.slip_direction);
    // the obstacle's surface point (or the partners' frame) moved
    const Tensor<1, dim> b = -cn.relative_converged - cn.obstacle_u;
    // H = κc Q M: M keeps the components the contact holds
    Tensor<2, dim> H;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int bb = 0; bb < dim; ++bb)
        if (contact_.holds(cn, bb))
          H[a][bb] = cn.kappa * c * Q[a][bb];
    const Tensor<1, dim> Hb = H * b;
    // rows of body point r: B_rᵀ H (D u + b); the node's B is I, a partner's −w_p Q
    for (unsigned int r = 0; r < points.size(); ++r)
      {
        const Tensor<2, dim> BrH = transpose(points[r].second) * H;
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            const Tensor<2, dim> block = BrH * points[q].second;
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int bb = 0; bb < dim; ++bb)
                M(r * dim + a, q * dim + bb) += block[a][bb];
          }
        const Tensor<1, dim> f = transpose(points[r].second) * Hb;
        for (unsigned int a = 0; a < dim; ++a)
          rhs(r * dim + a) = -f[a];
      }
    // Dynamic and elastoplastic: the traction is K u − b, so F(u) has the constant part
    // F_b = −μŵ (n·b_s) − κ Q M b_s (b_s the load at the node), moved to the right-hand side
    // of the node's rows (+) and its partners' (−w_p Qᵀ).
    if (system_.has_load())
      {
        const Tensor<1, dim> Fb = -scene_.contact.mu * (cn.n * cn.load_offset) * cn.slip_direction -
                                  cn.kappa * (Q * contact_.held_components(cn, cn.load_offset));
        for (unsigned int r = 0; r < points.size(); ++r)
          {
            const Tensor<1, dim> f = transpose(points[r].second) * Fb;
            for (unsigned int a = 0; a < dim; ++a)
              rhs(r * dim + a) += f[a];
          }
      }
  }

  /// The constraints of this iteration: the active nodes' lines (a sticking node: no new
  /// tangential slip, all its free components; otherwise its normal gap on the constrained
  /// component), then the fixed constraints at δ.
  void ContactSolve::build_contact_constraints(
    const double /*delta: in each node's g0, obstacle_u*/)
  {
    constraints_.clear();
    constraints_.reinit(dofs_.relevant());
    for (const auto &cn : contact_.nodes())
      if (cn.active && contact_.friction() && cn.stick)
        {
          // No new slip: u = Σ w·u_partner + P_t(r_conv + u_obstacle) − g0·n, with r_conv
          // the relative displacement of the last converged increment and P_t = I − n nᵀ
          // (the normal part is ĝ = 0). Components fixed by symmetry stay as they are.
          // (the obstacle's — or the partners' frame's — motion: obstacle_u, 0 for two bodies
          // at rest; a rigid obstacle's g0 holds its motion already). The partners' turn Q.
          const Tensor<2, dim> &Q = frame_.partner_rotation;
          const Tensor<1, dim> target =
            tangential(cn.relative_converged + cn.obstacle_u, cn.n) - cn.g0 * cn.n;
          for (unsigned int k = 0; k < dim; ++k)
            if (!dofs_.fixed_at_delta().is_constrained(cn.dofs[k]))
              {
                constraints_.add_line(cn.dofs[k]);
                for (const auto &p : cn.partners)
                  for (unsigned int m = 0; m < dim; ++m)
                    if (Q[k][m] != 0.0)
                      constraints_.add_entry(cn.dofs[k], p.dofs[m], p.weight * Q[k][m]);
                constraints_.set_inhomogeneity(cn.dofs[k], target[k]);
              }
        }
      else if (cn.active)
        {
          const unsigned int cc = cn.constrained_component;
          const auto d = cn.dofs[cc];
          // n·(u − Σ w Q u_p) = −g0; on a partner's DoF m: w (Qᵀ n)_m
          const Tensor<1, dim> n_partner = transpose(frame_.partner_rotation) * cn.n;
          constraints_.add_line(d);
          for (unsigned int k = 0; k < dim; ++k)
            {
              if (k != cc)
                constraints_.add_entry(d, cn.dofs[k], -cn.n[k] / cn.n[cc]);
              for (const auto &p : cn.partners)
                if (n_partner[k] != 0.0)
                  constraints_.add_entry(d, p.dofs[k], p.weight * n_partner[k] / cn.n[cc]);
            }
          constraints_.set_inhomogeneity(d, -cn.g0 / cn.n[cc]);
        }
    constraints_.merge(dofs_.fixed_at_delta(), AffineConstraints<double>::left_object_wins, true);
    constraints_.close();
  }

}  // namespace clearjoint::fe::detail
