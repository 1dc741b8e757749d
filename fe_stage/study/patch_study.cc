// The contact patch test (SPEC §5): a rigid flat — or a second block on non-matching meshes,
// coupled by dual mortar — pushed uniformly into the block: uniform pressure Eδ/H.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan patch_study(const FeScene &scene)
  {
    StudyPlan p;
    p.name = "patch";
    p.mesh = StudyPlan::Mesh::block;
    p.degree = 2;
    p.deformable_partner = scene.verification.deformable_indenter;
    p.obstacle.kind = RigidObstacle::Kind::plane;  // the plane y = −δ
    p.pairing = p.deformable_partner ? StudyPlan::Pairing::mortar : StudyPlan::Pairing::obstacle;
    p.must_touch = false;
    p.body_names = {"block", "indenter"};
    p.records = "contact force against the push, for F = E δ A / H (uniform pressure)";
    return p;
  }
} // namespace clearjoint::fe
