// The contact pattern: the contact nodes placed on the DoF space and the sparsity pattern every
// active set condenses into, and finite sliding, which pairs the nodes again at the deformed
// surfaces and keeps or rebuilds that pattern. It owns which couplings the pattern was built
// for (each candidate node's constraint component and partners) and how many times finite
// sliding (or the rolling study's turning journal) needed a new one; it works on the parts it
// is given (the DoF space's ghosts, the contact nodes, the assembler's contact cells and
// matrices, u) and asks the model, through MeshPreparation, to make everything that depends on
// the mesh again when new couplings do not fit.
//
// Files: contact/contact_pattern.cc (the nodes, their partners' ghosts, the contact cells, the
// pattern and the matrices on it), contact/sliding.cc (finite sliding).
#pragma once

#include "fe_stage/contact/contact_pairing.h"
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dim.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>

#include <map>
#include <set>

namespace clearjoint::fe::detail
{
  /// What the pattern asks of the model when finite sliding's new couplings do not fit it:
  /// everything that depends on the mesh made again (Model::prepare_mesh), the contact nodes
  /// searched between the surfaces displaced by `search_displacement` (ghosted).
  class MeshPreparation
  {
  public:
    virtual void prepare_mesh(const TrilinosWrappers::MPI::Vector *search_displacement) = 0;

  protected:
    ~MeshPreparation() = default;
  };

  /// What finite sliding asks of the contact solve (solve/contact_solve.h) once the nodes are
  /// paired again: the turning journal's partners placed at the frame's pose now, and every
  /// node's force, gap and relative displacement at the current u.
  class ContactEvaluation
  {
  public:
    virtual void set_obstacle_position(double delta) = 0;
    virtual void evaluate_contact(double delta) = 0;

  protected:
    ~ContactEvaluation() = default;
  };

  class ContactPattern
  {
  public:
    /// The model's parts the pattern works on: it adds the partners' ghosts to the DoF space,
    /// fills and re-pairs the contact nodes, gives the assembler its contact cells and
    /// pattern, and (finite sliding) evaluates the contact at u through the contact solve
    /// (`evaluation`).
    struct Parts
    {
      const FeScene &scene;
      const StudyPlan &plan;
      const Bodies &bodies;
      DofSpace &dofs;
      ContactProblem &contact;
      const ContactPairing &pairing;
      const JournalFrame &frame;
      Assembler &system;
      State &state;
      ContactEvaluation &evaluation;
      MPI_Comm comm;
    };

    ContactPattern(MeshPreparation &mesh, const Parts &parts);

    /// The pairing's contact nodes, their partners' ghosts and the contact cells; searched
    /// between the surfaces displaced by `search_displacement` when given (ghosted; finite
    /// sliding's rebuild).
    void find_contact_nodes(const TrilinosWrappers::MPI::Vector *search_displacement);
    /// The sparsity pattern with every candidate's contact line, and the assembler's matrices
    /// on it.
    void make_matrices();

    /// contact.sliding finite (scene.cc admits it only for two bodies paired by mortar)
    bool finite_sliding() const { return scene_.contact.sliding == Contact::Sliding::finite; }
    /// contact.sliding finite, or the rolling study's turning journal: the mortar search again
    /// at the converged deformed surfaces; slip then counts from u_start. Returns how far the
    /// coupling moved. `rebuild` forces a new pattern.
    double follow_sliding(const TrilinosWrappers::MPI::Vector &u_start, bool rebuild = false);
    /// A failed attempt's state restored (u, the contact nodes): finite sliding rebuilt the
    /// pattern for couplings of that attempt when the count of rebuilds moved since
    /// `rebuilds_saved`, so the restored state is paired again to put its partners back in it.
    void pair_restored(const TrilinosWrappers::MPI::Vector &u, unsigned int rebuilds_saved);
    /// New sparsity patterns so far (follow_sliding).
    unsigned int rebuilds() const { return n_rebuilds_; }

  private:
    MeshPreparation &mesh_;
    // the parts (Parts), by the names the pattern's files use
    const FeScene &scene_;
    const StudyPlan &plan_;
    const Bodies &bodies_;
    DofSpace &dofs_;
    ContactProblem &contact_;
    const ContactPairing &pairing_;
    const JournalFrame &frame_;
    Assembler &system_;
    State &state_;
    ContactEvaluation &evaluation_;
    MPI_Comm comm_;
    const unsigned int n_ranks_;

    /// The partner combinations' sparsity: per candidate node (by its x-DoF) the component of
    /// its normal line and its partners' x-DoFs, as make_matrices built the pattern for them
    /// (follow_sliding: whether new couplings fit it).
    struct PatternEntry
    {
      unsigned int component = 0;
      std::set<types::global_dof_index> partners;
    };
    std::map<types::global_dof_index, PatternEntry> pattern_partners_;
    unsigned int n_rebuilds_ = 0;  // follow_sliding: new sparsity patterns
  };
}  // namespace clearjoint::fe::detail
