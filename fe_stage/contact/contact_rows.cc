// What the active set adds to the system: the rigid obstacle's gaps at δ, nodal areas, the
// constraint lines of active nodes (normal, or all free components when sticking) and the
// friction rows of slipping nodes.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  /// Nodal areas w_i = ∫ φ_i dA over the contact surface: the contact pressure of node i is
  /// λ_i / w_i (exact for a uniform pressure; Q2 face weights are all positive).
  void ContactModel::compute_nodal_weights()
  {
    const QGauss<dim - 1> fq(fe_->degree + 1);
    FEFaceValues<dim> fv(*mapping_, *fe_, fq, update_values | update_JxW_values);
    TrilinosWrappers::MPI::Vector w(owned_, comm_);
    std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell());
    Vector<double> cell_w(fe_->n_dofs_per_cell());
    for (const auto &cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
            {
              fv.reinit(cell, f);
              cell_w = 0.0;
              for (unsigned int i = 0; i < fe_->n_dofs_per_cell(); ++i)
                for (const unsigned int q : fv.quadrature_point_indices())
                  cell_w(i) += fv.shape_value(i, q) * fv.JxW(q);
              cell->get_dof_indices(dofs);
              w.add(dofs, cell_w);
            }
    w.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector wg(owned_, relevant_, comm_);
    wg = w;
    for (auto &cn : nodes_)
      cn.weight = wg[cn.dofs[0]];
  }

  void ContactModel::set_obstacle_position(const double delta)
  {
    for (auto &cn : nodes_)
      if (!cn.two_body)
        obstacle_gap(cn.X, delta, cn.g0, cn.n);
  }

  /// A slipping node s carries the friction force μλ_s·e_s and its partners −w_p·μλ_s·e_s,
  /// with λ_s = n·(K u)_s its own normal contact force: rows (s,k) of the system get
  /// −μ e_k nᵀK_s and rows (p,k) +w_p μ e_k nᵀK_s (K_s: the rows of s's DoFs), cell by cell:
  /// the contact cell's matrix is extended by the partners' rows and condensed as a whole
  /// (so the constraints' inhomogeneities reach the right-hand side too). This makes A_
  /// non-symmetric (GMRES). Returns false if the cell holds no slipping node.
  bool ContactModel::friction_cell_matrix(const unsigned int k, FullMatrix<double> &M,
                                          std::vector<types::global_dof_index> &ext) const
  {
    const auto &dofs = contact_cell_dofs_[k];
    const auto &Kc = contact_cell_matrices_[k];
    ext = dofs;
    bool any = false;
    std::vector<std::pair<const ContactNode *, std::vector<double>>> rows_of;
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        const auto it = slipping_.find(dofs[i]);
        if (it == slipping_.end())
          continue;
        const ContactNode &cn = nodes_[it->second];
        any = true;
        // n·(K_cell u) over this node's rows: one row over the cell's columns
        std::vector<double> row(dofs.size(), 0.0);
        for (unsigned int c = 0; c < dim; ++c)
          {
            const auto li = std::find(dofs.begin(), dofs.end(), cn.dofs[c]) - dofs.begin();
            for (unsigned int j = 0; j < dofs.size(); ++j)
              row[j] += cn.n[c] * Kc(li, j);
          }
        rows_of.emplace_back(&cn, std::move(row));
        for (const auto &p : cn.partners)
          for (const auto d : p.dofs)
            if (std::find(ext.begin(), ext.end(), d) == ext.end())
              ext.push_back(d);
      }
    if (!any)
      return false;
    M.reinit(ext.size(), ext.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      for (unsigned int j = 0; j < dofs.size(); ++j)
        M(i, j) = Kc(i, j);
    const double mu = scene_.contact.mu;
    auto local = [&](const types::global_dof_index d) {
      return std::find(ext.begin(), ext.end(), d) - ext.begin();
    };
    for (const auto &[cn, row] : rows_of)
      for (unsigned int c = 0; c < dim; ++c)
        {
          const double f = mu * cn->slip_direction[c];
          const auto ls = local(cn->dofs[c]);
          for (unsigned int j = 0; j < dofs.size(); ++j)
            M(ls, j) -= f * row[j];
          for (const auto &p : cn->partners)
            {
              const auto lp = local(p.dofs[c]);
              for (unsigned int j = 0; j < dofs.size(); ++j)
                M(lp, j) += p.weight * f * row[j];
            }
        }
    return true;
  }

  /// The constraints of this iteration: the active nodes' lines (a sticking node: no new
  /// tangential slip, all its free components; otherwise its normal gap on the constrained
  /// component), then the fixed constraints at δ.
  void ContactModel::build_contact_constraints(const double delta)
  {
    constraints_.clear();
    constraints_.reinit(relevant_);
    for (const auto &cn : nodes_)
      if (cn.active && friction_ && cn.stick)
        {
          // No new slip: u = Σ w·u_partner + P_t(r_conv + u_obstacle) − g0·n, with r_conv
          // the relative displacement of the last converged increment and P_t = I − n nᵀ
          // (the normal part is ĝ = 0). Components fixed by symmetry stay as they are.
          Tensor<1, dim> target = cn.relative_converged;
          if (!cn.two_body)
            target[1] -= delta;
          target = tangential(target, cn.n) - cn.g0 * cn.n;  // (a rigid obstacle's g0 holds its motion already)
          for (unsigned int k = 0; k < dim; ++k)
            if (!fixed_delta_.is_constrained(cn.dofs[k]))
              {
                constraints_.add_line(cn.dofs[k]);
                for (const auto &p : cn.partners)
                  constraints_.add_entry(cn.dofs[k], p.dofs[k], p.weight);
                constraints_.set_inhomogeneity(cn.dofs[k], target[k]);
              }
        }
      else if (cn.active)
        {
          const unsigned int cc = cn.constrained_component;
          const auto d = cn.dofs[cc];
          constraints_.add_line(d);
          for (unsigned int k = 0; k < dim; ++k)
            {
              if (k != cc)
                constraints_.add_entry(d, cn.dofs[k], -cn.n[k] / cn.n[cc]);
              for (const auto &p : cn.partners)
                constraints_.add_entry(d, p.dofs[k], p.weight * cn.n[k] / cn.n[cc]);
            }
          constraints_.set_inhomogeneity(d, -cn.g0 / cn.n[cc]);
        }
    constraints_.merge(fixed_delta_, AffineConstraints<double>::left_object_wins, true);
    constraints_.close();
  }

} // namespace clearjoint::fe::detail
