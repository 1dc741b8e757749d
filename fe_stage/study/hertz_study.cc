// Verification against Hertz (SPEC §5): a rigid sphere — or a deformable body of the same
// material whose bottom is Hertz's profile r²/2R, coupled by dual mortar — pressed into the
// block (quarter model).
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan hertz_study(const FeScene &scene)
  {
    StudyPlan p = block_study(scene, "hertz");
    // the sphere's centre at y = R − δ: it touches the block's top (y = 0) at δ = 0
    p.obstacle.kind = RigidObstacle::Kind::sphere;
    p.obstacle.radius = scene.verification.sphere_radius;
    p.hertz = true;
    return p;
  }
}  // namespace clearjoint::fe
