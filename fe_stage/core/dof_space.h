// The displacement field's DoF space on the meshed bodies: FE_Q(p)^3, its DoFs and the index
// sets of this rank, and the constraints that do not depend on contact — hanging nodes,
// symmetry planes, supports and the journal's load (a driven journal: its loaded set moves
// by δ; they are built at δ = 1 and scaled, being linear in δ). Also the loaded and support
// DoFs whose reactions are the forces the studies record.
//
// Rebuilt (distribute) after every change of the mesh; the contact rows, matrices and vectors
// are built on it by their owners.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>
#include <memory>
#include <vector>

namespace clearjoint::fe::detail
{
  class DofSpace
  {
  public:
    DofSpace(const FeScene &scene, const StudyPlan &plan, const Bodies &bodies, MPI_Comm comm);

    /// DoFs on the bodies' current mesh and the fixed constraints. `journal_driven`: a
    /// deformable journal's loaded set is driven by δ (false: it is free, the impact study's
    /// time steps). Throws NumericalError when a driven journal has no loaded DoF.
    void distribute(bool journal_driven);
    /// Makes the DoFs `extra` locally relevant too (contact partners owned by other ranks)
    /// and builds the fixed constraints again on the enlarged set (collective).
    void add_relevant(const IndexSet &extra);
    /// The fixed constraints at the push δ [m] (fixed_at_delta()).
    void set_delta(double delta);
    /// Moves the nodal forces of hanging DoFs in r (owned) to their masters (r_m += c_hm r_h,
    /// r_h = 0), as the condensed equations see them: a hanging node inside the contact zone
    /// passes its share of the contact force to the contact nodes it hangs from, and supports
    /// count the share of hanging support nodes. Without it the contact force misses those
    /// shares. Collective.
    void condense_hanging(TrilinosWrappers::MPI::Vector &r) const;
    /// C^T b − b for `constraints` on this space: each owned constrained DoF's entry of b moved
    /// to its masters with the line's coefficients, and taken off the DoF itself (as
    /// distribute_local_to_global does with a cell vector). Collective.
    TrilinosWrappers::MPI::Vector moved_to_masters(const AffineConstraints<double> &constraints,
                                                   const TrilinosWrappers::MPI::Vector &b) const;

    const FESystem<dim> &fe() const { return *fe_; }
    const DoFHandler<dim> &handler() const { return handler_; }
    const IndexSet &owned() const { return owned_; }
    const IndexSet &relevant() const { return relevant_; }
    /// Hanging nodes only (condensing residuals onto their masters).
    const AffineConstraints<double> &hanging() const { return hanging_; }
    /// Hanging nodes, symmetry, supports and the journal's load at δ = 1.
    const AffineConstraints<double> &fixed() const { return fixed_; }
    /// The same at the δ of the last set_delta.
    const AffineConstraints<double> &fixed_at_delta() const { return fixed_delta_; }
    /// Owned journal (or indenter) y-DoFs driven by δ: their reactions are the load.
    const std::vector<types::global_dof_index> &loaded_y_dofs() const { return loaded_y_; }
    bool is_loaded_y_dof(const types::global_dof_index d) const
    {
      return std::binary_search(loaded_sorted_.begin(), loaded_sorted_.end(), d);
    }
    /// Owned y-DoFs of the supports: their reactions are the support force.
    const std::vector<types::global_dof_index> &support_y_dofs() const { return support_y_; }

  private:
    void build_fixed_constraints();

    const FeScene &scene_;
    const StudyPlan &plan_;
    const Bodies &bodies_;
    MPI_Comm comm_;
    bool journal_driven_ = true;
    std::unique_ptr<FESystem<dim>> fe_;
    DoFHandler<dim> handler_;
    IndexSet owned_, relevant_;
    AffineConstraints<double> hanging_, fixed_, fixed_delta_;
    std::vector<types::global_dof_index> loaded_y_, loaded_sorted_, support_y_;
  };
}  // namespace clearjoint::fe::detail
