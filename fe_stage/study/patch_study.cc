// The contact patch test (SPEC §5): a rigid flat — or a second block on non-matching meshes,
// coupled by dual mortar — pushed uniformly into the block: uniform pressure Eδ/H.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan patch_study(const FeScene &scene)
  {
    StudyPlan p = block_study(scene, "patch");
    p.obstacle.kind = RigidObstacle::Kind::plane;  // the plane y = −δ
    return p;
  }
}  // namespace clearjoint::fe
