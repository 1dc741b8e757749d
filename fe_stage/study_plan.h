// What each study sets up — which mesh and bodies, what the other body is (a rigid obstacle
// placed where it first touches, or a deformable body), how contact is paired, and what a
// converged increment must satisfy — decided once from the scene (study/: one file per study
// fills it). The model's parts read the plan instead of asking which study runs: like the
// scene, it is an input at the bottom of the include graph. No deal.II.
#pragma once

#include "fe_stage/contact/rigid_obstacle.h"
#include "fe_stage/mesh/journal_pose.h"

#include <array>
#include <string>

namespace clearjoint::fe
{
  struct StudyPlan
  {
    std::string name;
    /// joint: the bearing ring (generated or Gmsh) and the journal; block: the verification
    /// block [0,W]×[−H,0]×[0,W] and its indenter.
    enum class Mesh
    {
      joint,
      block
    } mesh = Mesh::joint;
    unsigned int degree = 2;  // FE_Q degree
    /// The other body (journal or indenter) is meshed and pushed at its loaded set (two-body
    /// contact); otherwise it is `obstacle`.
    bool deformable_partner = false;
    /// The rigid journal, sphere or plane at δ = 0 (first touch) — for a deformable partner,
    /// where its surface lies (the candidate search and the refinement toward the contact).
    RigidObstacle obstacle;
    enum class Pairing
    {
      obstacle,
      common_rays,
      mortar
    } pairing = Pairing::obstacle;
    /// Mortar on the joint: the journal's surface is the slave side (its nodes carry the
    /// constraints) and the bore the master. Needed where the journal bears on the bore with
    /// its rim: a bore face around the rim's trace is only partly covered by the journal, its
    /// dual basis then has no partner on part of the face and its nodes would be dropped; the
    /// journal's surface lies wholly over the (longer) bore. Otherwise the bore is the slave.
    bool journal_is_slave = false;
    /// Where a deformable generated journal sits (identity: aligned, as meshed).
    JournalPose journal_pose;
    /// Joint: the journal tilted by obstacle.tilt (the whole length is modelled, an axial
    /// slice goes through the first touch point, the contact refinement follows the gap).
    bool tilted = false;
    /// The whole length is modelled (no z = 0 symmetry plane): the tilted journal, or one
    /// moved axially (loading.axial_offset / axial_slide).
    bool full_length = false;
    /// Block: the deformable indenter's bottom is Hertz's profile; the refinement is graded
    /// toward the contact point (patch: uniform).
    bool hertz = false;
    /// Every converged increment must have a contact point (a pushed joint touches
    /// somewhere; zero active nodes means the mesh is too coarse for the contact patch).
    bool must_touch = true;
    /// Implicit dynamics (mass matrix, HHT-α time steps) instead of quasi-static increments.
    bool dynamic = false;
    /// The rolling study: the bearing turns (computed in its co-rotating frame, the whole ring
    /// meshed), elastoplastic, the journal's spin found from its torque balance.
    bool rolling = false;
    std::array<std::string, 2> body_names;  // material ids 0 and 1

    /// The rolling study's deformable journal, turning over the bore in its own frame: its
    /// partners move with it (the pairing places them by the journal's pose, the contact
    /// rows turn their displacements, every torque evaluation searches again).
    bool journal_turns_deformable() const { return rolling && deformable_partner; }
  };
}  // namespace clearjoint::fe
