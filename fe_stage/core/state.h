// The current iterate of the discrete problem: the displacement u and the nodal forces it
// leaves, r = K u − b with the hanging nodes' shares on their masters (the contact tractions
// and the reactions are read from r). u is kept twice: owned (the solves write it) and with
// the ghost layer (assembly, evaluation and output read it); publish() brings the second up to
// date. What a failed attempt goes back to (u with the contact nodes) is the model's Snapshot.
#pragma once

#include "fe_stage/core/dof_space.h"

#include <deal.II/lac/trilinos_vector.h>

namespace clearjoint::fe::detail
{
  class State
  {
  public:
    /// Zero vectors on the DoF space (after every change of the mesh or its ghost layer).
    void reinit(const DofSpace &dofs, MPI_Comm comm)
    {
      reinit(dofs.owned(), dofs.relevant(), comm);
    }
    /// The same on a layout given by its owned and locally relevant DoFs.
    void reinit(const IndexSet &owned, const IndexSet &relevant, MPI_Comm comm)
    {
      u_.reinit(owned, comm);
      u_ghosted_.reinit(owned, relevant, comm);
      forces_.reinit(owned, comm);
    }
    /// u at the owned DoFs: what a solve writes (publish() afterwards).
    TrilinosWrappers::MPI::Vector &u_owned() { return u_; }
    const TrilinosWrappers::MPI::Vector &u_owned() const { return u_; }
    /// u with the ghost layer, as of the last publish().
    const TrilinosWrappers::MPI::Vector &u() const { return u_ghosted_; }
    void publish() { u_ghosted_ = u_; }
    void set(const TrilinosWrappers::MPI::Vector &u)
    {
      u_ = u;
      publish();
    }
    void set_zero()
    {
      u_ = 0.0;
      u_ghosted_ = 0.0;
    }
    /// r = K u − b at the owned DoFs (evaluate_contact writes it).
    TrilinosWrappers::MPI::Vector &forces() { return forces_; }
    const TrilinosWrappers::MPI::Vector &forces() const { return forces_; }

  private:
    TrilinosWrappers::MPI::Vector u_, u_ghosted_, forces_;
  };
}  // namespace clearjoint::fe::detail
