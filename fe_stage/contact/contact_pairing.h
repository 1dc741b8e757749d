// How the contact nodes find what they touch (FE_DESIGN §4: the ContactPairing seam). A pairing
// turns the slave surface's nodes into contact nodes — each one's constrained component, normal,
// initial gap g0, and its partners on the other body (none against a rigid obstacle) — and says
// which of them can close within the push (candidates) and which are only watched for
// penetration. Three pairings, chosen once from the study's plan (StudyPlan::pairing):
//   - obstacle:    the bore (or the block's top) against the rigid journal, sphere or plane
//                  (contact/obstacle_pairing.cc);
//   - common rays: the bore against the deformable journal node on the same ray, the
//                  generated meshes' matching nodes (contact/obstacle_pairing.cc);
//   - mortar:      two non-matching deformable surfaces by dual mortar (contact/mortar.h,
//                  contact/mortar_pairing.cc); the only one that also searches between the
//                  surfaces as deformed (contact.sliding: finite, contact/sliding.cc).
// The model keeps the nodes it is given (ContactProblem) and builds their ghosts, pattern and
// contact cells from them; a pairing holds no state of its own, only what it reads.
#pragma once

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/contact/journal_frame.h"
#include "fe_stage/contact/rigid_obstacle.h"
#include "fe_stage/core/dim.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_vector.h>

#include <map>
#include <memory>

namespace clearjoint::fe::detail
{
  /// What a pairing reads, each part owned by the model: the scene and plan, the bodies and
  /// their DoFs, the contact problem (which component a node's constraint takes), the rigid
  /// obstacle as the steps place it, and the rolling study's journal frame (set per step).
  struct PairingContext
  {
    const FeScene &scene;
    const StudyPlan &plan;
    const Bodies &bodies;
    const DofSpace &dofs;
    const ContactProblem &contact;
    const RigidObstacle &obstacle;
    const JournalFrame &frame;
    MPI_Comm comm;
  };

  class ContactPairing
  {
  public:
    /// Contact nodes by their x-DoF (the order the model keeps them in).
    using Nodes = std::map<types::global_dof_index, ContactNode>;

    virtual ~ContactPairing() = default;

    /// The slave surface's locally relevant contact nodes, their positions X from `support`
    /// (every DoF's support point). With `u` (ghosted; contact.sliding finite, mortar only)
    /// the search is between the surfaces displaced by u, and each node's g0 makes its
    /// linearised gap at u the gap found there. Collective.
    virtual Nodes find(const std::map<types::global_dof_index, Point<dim>> &support,
                       const TrilinosWrappers::MPI::Vector *u) const = 0;
  };

  /// The plan's pairing over the model's parts (which it must outlive).
  std::unique_ptr<ContactPairing> make_contact_pairing(const PairingContext &context);
  std::unique_ptr<ContactPairing> make_obstacle_pairing(const PairingContext &context);
  std::unique_ptr<ContactPairing> make_common_ray_pairing(const PairingContext &context);
  std::unique_ptr<ContactPairing> make_mortar_pairing(const PairingContext &context);

  /// The boundary whose nodes carry the contact constraints: the bore (or the block's top),
  /// or the journal's surface when it is the mortar slave.
  inline types::boundary_id slave_surface(const StudyPlan &plan)
  {
    return plan.pairing == StudyPlan::Pairing::mortar && plan.journal_is_slave ?
             bid_journal_surface :
             bid_contact;
  }

  /// The rolling study: the journal passes under a bore point X when the frame angle −φ
  /// reaches it; its gap g0 [m] and normal n then, pushed to δ_max, decide whether X is a
  /// contact candidate (off the arc the journal travels: at the arc's nearer end).
  void rolling_gap_on_path(const FeScene &scene, const RigidObstacle &obstacle, const Point<dim> &X,
                           double &g0, Tensor<1, dim> &n);
}  // namespace clearjoint::fe::detail
