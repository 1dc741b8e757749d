// Fixed constraints: hanging nodes, symmetry planes, supports and the journal load (δ = 1, scaled).
#include "fe_stage/core/contact_model.h"

#include <cmath>
#include <set>

namespace clearjoint::fe::detail
{
  /// Hanging nodes, symmetry planes, supports and the journal load at δ = 1 on the locally
  /// relevant DoFs. With several ranks the lines are made consistent across ranks, so a rank
  /// also knows the constraints of the journal DoFs it was given as contact partners.
  void ContactModel::build_fixed_constraints()
  {
    const bool joint = plan_.mesh == StudyPlan::Mesh::joint;
    loaded_y_dofs_.clear();
    const FEValuesExtractors::Scalar ux(0), uy(1), uz(2);
    fixed_constraints_.clear();
    fixed_constraints_.reinit(relevant_);
    DoFTools::make_hanging_node_constraints(dof_handler_, fixed_constraints_);
    hanging_constraints_.clear();
    hanging_constraints_.reinit(relevant_);
    DoFTools::make_hanging_node_constraints(dof_handler_, hanging_constraints_);
    if (n_ranks_ > 1)
      hanging_constraints_.make_consistent_in_parallel(owned_, relevant_, comm_);
    hanging_constraints_.close();
    const Functions::ZeroFunction<dim> zero(dim);
    VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_sym_x, zero,
                                             fixed_constraints_, fe_->component_mask(ux));
    VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_sym_z, zero,
                                             fixed_constraints_, fe_->component_mask(uz));
    if (joint)
      VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_fixed, zero,
                                               fixed_constraints_);
    else
      VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, bid_fixed, zero,
                                               fixed_constraints_, fe_->component_mask(uy));
    // Journal load at δ = 1 (u_y = −1 m); every inhomogeneity is then scaled by δ. (Not for the
    // impact study's time steps: its deformable journal is free.)
    if (two_body_ && journal_driven_)
      {
        std::map<types::global_dof_index, Point<dim>> support;
        DoFTools::map_dofs_to_support_points(*mapping_, dof_handler_, support);
        Vector<double> down(dim);
        down[1] = -1.0;
        const Functions::ConstantFunction<dim> unit_push(down);
        if (!joint || scene_.loading.journal == JournalLoading::end_faces)
          {
            // the journal's end face, or the top of a deformable indenter
            AffineConstraints<double> load(relevant_);
            VectorTools::interpolate_boundary_values(*mapping_, dof_handler_,
                                                     joint ? bid_journal_end : bid_indenter_top,
                                                     unit_push, load, fe_->component_mask(uy));
            for (const auto &line : load.get_lines())
              {
                // the reaction sums over every DoF of the set, hanging ones included (their
                // share would otherwise be lost); only the free ones get the load line
                if (owned_.is_element(line.index))
                  loaded_y_dofs_.push_back(line.index);
                if (!fixed_constraints_.is_constrained(line.index))
                  {
                    fixed_constraints_.add_line(line.index);
                    fixed_constraints_.set_inhomogeneity(line.index, -1.0);
                  }
              }
          }
        else
          {
            // axis_line: the journal's y-DoFs on its axis x = 0, y = −c_r; core: every DoF of
            // the journal's points within R_J/2 of that axis (the tilted journal's: its own),
            // u = (0, −1, 0) (a rigid core translated, SPEC §2)
            const bool core = scene_.loading.journal == JournalLoading::core;
            const double tol = 1e-8 * scene_.geometry.R_B;
            const double r_core = 0.5 * scene_.geometry.R_J();
            auto driven = [&](const Point<dim> &X) {
              const Point<dim> p = journal_local(X);  // from the (tilted) journal's axis
              const double r = std::hypot(p[0], p[1] + scene_.geometry.c_r);
              return core ? r <= r_core + tol : r < tol;
            };
            std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell());
            std::set<types::global_dof_index> seen;
            for (const auto &cell : dof_handler_.active_cell_iterators())
              if ((cell->is_locally_owned() || cell->is_ghost()) && cell->material_id() == 1)
                {
                  cell->get_dof_indices(dofs);
                  for (unsigned int i = 0; i < dofs.size(); ++i)
                    {
                      const unsigned int component = fe_->system_to_component_index(i).first;
                      if ((component != 1 && !core) || !driven(support.at(dofs[i])) ||
                          !seen.insert(dofs[i]).second)
                        continue;
                      if (component == 1 && owned_.is_element(dofs[i]))
                        loaded_y_dofs_.push_back(dofs[i]);
                      if (!fixed_constraints_.is_constrained(dofs[i]))
                        {
                          fixed_constraints_.add_line(dofs[i]);
                          // per unit δ: −1 along y; along z the axial slide's share.
                          // The rolling study's journal is computed in its own frame, which
                          // carries the push and the spin: its core is clamped there (u = 0).
                          const double slide =
                            scene_.loading.axial_slide / scene_.loading.delta_max;
                          fixed_constraints_.set_inhomogeneity(dofs[i], plan_.rolling  ? 0.0 :
                                                                        component == 1 ? -1.0 :
                                                                        component == 2 ? slide :
                                                                                         0.0);
                        }
                    }
                }
          }
        loaded_sorted_ = loaded_y_dofs_;
        std::sort(loaded_sorted_.begin(), loaded_sorted_.end());
        if (Utilities::MPI::sum(loaded_y_dofs_.size(), comm_) == 0)
          throw NumericalError(joint ? "fe_stage: no journal DoFs found for the loading " +
                                         to_string(scene_.loading.journal) :
                                       std::string("fe_stage: the indenter has no top face"));
      }
    if (n_ranks_ > 1)
      fixed_constraints_.make_consistent_in_parallel(owned_, relevant_, comm_);
    fixed_constraints_.close();
  }

  /// The fixed constraints are linear in δ (supports and symmetry are homogeneous, the journal
  /// load is u_y = −δ, hanging nodes are linear): scale every inhomogeneity of the δ = 1 set.
  void ContactModel::set_fixed_constraints_for(const double delta)
  {
    fixed_delta_.clear();
    fixed_delta_.copy_from(fixed_constraints_);
    for (const auto &line : fixed_constraints_.get_lines())
      if (line.inhomogeneity != 0.0)
        fixed_delta_.set_inhomogeneity(line.index, delta * line.inhomogeneity);
  }
}  // namespace clearjoint::fe::detail
