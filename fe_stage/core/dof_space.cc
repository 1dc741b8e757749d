// The DoF space (core/dof_space.h): DoFs, index sets and the fixed constraints — hanging
// nodes, symmetry planes, supports and the journal load (at δ = 1, scaled).
#include "fe_stage/core/dof_space.h"

#include "fe_stage/mesh/boundary_ids.h"

#include "common/error.h"

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <map>
#include <set>

namespace clearjoint::fe::detail
{
  DofSpace::DofSpace(const FeScene &scene, const StudyPlan &plan, const Bodies &bodies,
                     MPI_Comm comm)
    : scene_(scene)
    , plan_(plan)
    , bodies_(bodies)
    , comm_(comm)
    , fe_(std::make_unique<FESystem<dim>>(FE_Q<dim>(plan.degree), dim))
    , handler_(bodies.triangulation())
  {}

  void DofSpace::distribute(const bool journal_driven)
  {
    handler_.distribute_dofs(*fe_);
    owned_ = handler_.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(handler_, relevant_);
    journal_driven_ = journal_driven;
    build_fixed_constraints();

    support_y_.clear();
    const FEValuesExtractors::Scalar uy(1);
    const IndexSet sy =
      DoFTools::extract_boundary_dofs(handler_, fe_->component_mask(uy), {bid_fixed});
    for (const auto i : sy)
      if (owned_.is_element(i))
        support_y_.push_back(i);
  }

  void DofSpace::add_relevant(const IndexSet &extra)
  {
    relevant_.add_indices(extra);
    relevant_.compress();
    build_fixed_constraints();
  }

  /// Hanging nodes, symmetry planes, supports and the journal load at δ = 1 on the locally
  /// relevant DoFs. With several ranks the lines are made consistent across ranks, so a rank
  /// also knows the constraints of the journal DoFs it was given as contact partners.
  void DofSpace::build_fixed_constraints()
  {
    const bool joint = plan_.mesh == StudyPlan::Mesh::joint;
    loaded_y_.clear();
    const FEValuesExtractors::Scalar ux(0), uy(1), uz(2);
    fixed_.clear();
    fixed_.reinit(relevant_);
    DoFTools::make_hanging_node_constraints(handler_, fixed_);
    hanging_.clear();
    hanging_.reinit(relevant_);
    DoFTools::make_hanging_node_constraints(handler_, hanging_);
    if (Utilities::MPI::n_mpi_processes(comm_) > 1)
      hanging_.make_consistent_in_parallel(owned_, relevant_, comm_);
    hanging_.close();
    const Functions::ZeroFunction<dim> zero(dim);
    VectorTools::interpolate_boundary_values(bodies_.mapping(), handler_, bid_sym_x, zero, fixed_,
                                             fe_->component_mask(ux));
    VectorTools::interpolate_boundary_values(bodies_.mapping(), handler_, bid_sym_z, zero, fixed_,
                                             fe_->component_mask(uz));
    if (joint)
      VectorTools::interpolate_boundary_values(bodies_.mapping(), handler_, bid_fixed, zero,
                                               fixed_);
    else
      VectorTools::interpolate_boundary_values(bodies_.mapping(), handler_, bid_fixed, zero, fixed_,
                                               fe_->component_mask(uy));
    // Journal load at δ = 1 (u_y = −1 m); every inhomogeneity is then scaled by δ. (Not for the
    // impact study's time steps: its deformable journal is free.)
    if (plan_.deformable_partner && journal_driven_)
      {
        std::map<types::global_dof_index, Point<dim>> support;
        DoFTools::map_dofs_to_support_points(bodies_.mapping(), handler_, support);
        Vector<double> down(dim);
        down[1] = -1.0;
        const Functions::ConstantFunction<dim> unit_push(down);
        if (!joint || scene_.loading.journal == JournalLoading::end_faces)
          {
            // the journal's end face, or the top of a deformable indenter
            AffineConstraints<double> load(relevant_);
            VectorTools::interpolate_boundary_values(bodies_.mapping(), handler_,
                                                     joint ? bid_journal_end : bid_indenter_top,
                                                     unit_push, load, fe_->component_mask(uy));
            for (const auto &line : load.get_lines())
              {
                // the reaction sums over every DoF of the set, hanging ones included (their
                // share would otherwise be lost); only the free ones get the load line
                if (owned_.is_element(line.index))
                  loaded_y_.push_back(line.index);
                if (!fixed_.is_constrained(line.index))
                  {
                    fixed_.add_line(line.index);
                    fixed_.set_inhomogeneity(line.index, -1.0);
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
              const Point<dim> p = bodies_.journal_local(X);  // from the (tilted) journal's axis
              const double r = std::hypot(p[0], p[1] + scene_.geometry.c_r);
              return core ? r <= r_core + tol : r < tol;
            };
            std::vector<types::global_dof_index> dofs(fe_->n_dofs_per_cell());
            std::set<types::global_dof_index> seen;
            for (const auto &cell : handler_.active_cell_iterators())
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
                        loaded_y_.push_back(dofs[i]);
                      if (!fixed_.is_constrained(dofs[i]))
                        {
                          fixed_.add_line(dofs[i]);
                          // per unit δ: −1 along y; along z the axial slide's share.
                          // The rolling study's journal is computed in its own frame, which
                          // carries the push and the spin: its core is clamped there (u = 0).
                          const double slide =
                            scene_.loading.axial_slide / scene_.loading.delta_max;
                          fixed_.set_inhomogeneity(dofs[i], plan_.rolling  ? 0.0 :
                                                            component == 1 ? -1.0 :
                                                            component == 2 ? slide :
                                                                             0.0);
                        }
                    }
                }
          }
        loaded_sorted_ = loaded_y_;
        std::sort(loaded_sorted_.begin(), loaded_sorted_.end());
        if (Utilities::MPI::sum(loaded_y_.size(), comm_) == 0)
          throw NumericalError(joint ? "fe_stage: no journal DoFs found for the loading " +
                                         to_string(scene_.loading.journal) :
                                       std::string("fe_stage: the indenter has no top face"));
      }
    if (Utilities::MPI::n_mpi_processes(comm_) > 1)
      fixed_.make_consistent_in_parallel(owned_, relevant_, comm_);
    fixed_.close();
  }

  /// The fixed constraints are linear in δ (supports and symmetry are homogeneous, the journal
  /// load is u_y = −δ, hanging nodes are linear): scale every inhomogeneity of the δ = 1 set.
  void DofSpace::set_delta(const double delta)
  {
    fixed_delta_.clear();
    fixed_delta_.copy_from(fixed_);
    for (const auto &line : fixed_.get_lines())
      if (line.inhomogeneity != 0.0)
        fixed_delta_.set_inhomogeneity(line.index, delta * line.inhomogeneity);
  }

  void DofSpace::condense_hanging(TrilinosWrappers::MPI::Vector &r) const
  {
    r += moved_to_masters(hanging_, r);
  }

  TrilinosWrappers::MPI::Vector DofSpace::moved_to_masters(
    const AffineConstraints<double> &constraints, const TrilinosWrappers::MPI::Vector &b) const
  {
    // ghosted copy: the constrained DoF's value on whichever rank owns its line
    TrilinosWrappers::MPI::Vector ghosted(owned_, relevant_, comm_);
    ghosted = b;
    TrilinosWrappers::MPI::Vector moved;
    moved.reinit(owned_, relevant_, comm_, true);  // writable: entries of masters elsewhere
    for (const auto &line : constraints.get_lines())
      if (owned_.is_element(line.index))
        {
          const double bi = ghosted[line.index];
          for (const auto &[m, c] : line.entries)
            moved[m] += c * bi;
          moved[line.index] -= bi;
        }
    moved.compress(VectorOperation::add);
    return moved;
  }
}  // namespace clearjoint::fe::detail
