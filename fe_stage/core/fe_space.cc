// The finite-element space: FE_Q(p)^3 with a curved mapping, DoFs and index sets, the sparsity
// pattern that every active set condenses into, matrices, vectors and the solver choice.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  void ContactModel::setup_system()
  {
    const unsigned int p = plan_.degree;
    fe_ = std::make_unique<FESystem<dim>>(FE_Q<dim>(p), dim);
    mapping_ = std::make_unique<MappingQ<dim>>(std::max(2u, p));
    dof_handler_.distribute_dofs(*fe_);
    owned_ = dof_handler_.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant_);

    two_body_ = plan_.deformable_partner;
    build_fixed_constraints();

    support_y_dofs_.clear();
    {
      const FEValuesExtractors::Scalar uy(1);
      const IndexSet sy =
        DoFTools::extract_boundary_dofs(dof_handler_, fe_->component_mask(uy), {bid_fixed});
      for (const auto i : sy)
        if (owned_.is_element(i))
          support_y_dofs_.push_back(i);
    }
  }

  /// Matrices and vectors. The sparsity pattern is built with every candidate's contact line
  /// present, so any active set condenses into it (the two-body lines couple journal DoFs).
  void ContactModel::make_matrices()
  {
    AffineConstraints<double> worst(relevant_);
    pattern_partners_.clear();
    for (const auto &cn : nodes_)
      if (cn.candidate)
        {
          auto &entry = pattern_partners_[cn.dofs[0]];
          entry.component = cn.constrained_component;
          for (const auto &p : cn.partners)
            entry.partners.insert(p.dofs[0]);
          const auto d = cn.dofs[cn.constrained_component];
          worst.add_line(d);
          for (unsigned int k = 0; k < dim; ++k)
            {
              if (k != cn.constrained_component)
                worst.add_entry(d, cn.dofs[k], 1.0);
              for (const auto &p : cn.partners)
                worst.add_entry(d, p.dofs[k], 1.0);
            }
          // a sticking node constrains its other free components to its partners too
          if (friction_)
            for (unsigned int k = 0; k < dim; ++k)
              if (k != cn.constrained_component && !fixed_constraints_.is_constrained(cn.dofs[k]))
                {
                  worst.add_line(cn.dofs[k]);
                  // (the rolling study's turning journal: its partners' x and y mix)
                  for (const auto &p : cn.partners)
                    for (unsigned int m = 0; m < dim; ++m)
                      if (m == k || rolling_deformable_journal())
                        worst.add_entry(cn.dofs[k], p.dofs[m], 1.0);
                }
        }
    worst.merge(fixed_constraints_, AffineConstraints<double>::left_object_wins, true);
    worst.close();
    // The union of the patterns with and without the contact lines: a master of a hanging node
    // may be a contact DoF, whose line is active in some iterations and not in others.
    DynamicSparsityPattern dsp(relevant_);
    DoFTools::make_sparsity_pattern(dof_handler_, dsp, fixed_constraints_, true);
    DoFTools::make_sparsity_pattern(dof_handler_, dsp, worst, true);
    // Any mix of active and inactive candidates must fit the pattern, not only "none" and
    // "all": condensing the contact line of a candidate d moves entries K(i, d) and K(d, j) of
    // every cell holding d — or holding a hanging DoF that hangs from d — to the DoFs of d's
    // line (its node's other components, the journal partner's components and their
    // masters). A free candidate's row in such a cell then couples to them too. Add these
    // couplings for every such cell explicitly.
    {
      std::map<types::global_dof_index, std::vector<types::global_dof_index>> line_dofs;
      for (const auto &cn : nodes_)
        if (cn.candidate)
          {
            std::vector<types::global_dof_index> v;
            for (unsigned int l = 0; l < dim; ++l)
              {
                v.push_back(cn.dofs[l]);
                for (const auto &p : cn.partners)
                  {
                    v.push_back(p.dofs[l]);
                    if (const auto *e = worst.get_constraint_entries(p.dofs[l]))
                      for (const auto &entry : *e)
                        v.push_back(entry.first);
                  }
              }
            for (unsigned int l = 0; l < dim; ++l)
              if (l == cn.constrained_component || friction_)
                {
                  auto &target = line_dofs[cn.dofs[l]];
                  target.insert(target.end(), v.begin(), v.end());
                }
          }
      std::vector<types::global_dof_index> cell_dofs(fe_->n_dofs_per_cell());
      for (const auto &cell : dof_handler_.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          {
            cell->get_dof_indices(cell_dofs);
            std::vector<types::global_dof_index> ps;
            auto collect = [&](const types::global_dof_index d) {
              const auto it = line_dofs.find(d);
              if (it != line_dofs.end())
                ps.insert(ps.end(), it->second.begin(), it->second.end());
            };
            for (const auto d : cell_dofs)
              {
                collect(d);
                if (const auto *e = fixed_constraints_.get_constraint_entries(d))
                  for (const auto &entry : *e)
                    collect(entry.first);
              }
            if (ps.empty())
              continue;
            std::vector<types::global_dof_index> all = cell_dofs;
            all.insert(all.end(), ps.begin(), ps.end());
            std::sort(all.begin(), all.end());
            all.erase(std::unique(all.begin(), all.end()), all.end());
            for (const auto i : all)
              if (relevant_.is_element(i))
                for (const auto j : all)
                  dsp.add(i, j);
          }
    }
    SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
    K_.reinit(owned_, owned_, dsp, comm_);
    A_static_.reinit(owned_, owned_, dsp, comm_);
    A_.reinit(owned_, owned_, dsp, comm_);

    solution_owned_.reinit(owned_, comm_);
    rhs_.reinit(owned_, comm_);
    rhs_static_unit_.reinit(owned_, comm_);
    residual_owned_.reinit(owned_, comm_);
    solution_.reinit(owned_, relevant_, comm_);
    residual_.reinit(owned_, relevant_, comm_);

    const auto n_dofs = dof_handler_.n_dofs();
    bool direct = false;
    switch (scene_.solver.linear)
      {
        case LinearSolver::direct:
          direct = true;
          break;
        case LinearSolver::cg_amg:
          direct = false;
          break;
        case LinearSolver::automatic:
          direct = n_dofs < scene_.solver.direct_below_dofs;
          break;
      }
    solver_.configure(direct, scene_.solver.tolerance, scene_.solver.max_linear_iterations);
  }
}  // namespace clearjoint::fe::detail
