// The thickness study (paper §3.1): the aligned journal pushed radially (−y) into the bearing
// ring held at its outer half; rigid, or deformable and pushed at its end faces or its axis.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan radial_study(const FeScene &scene)
  {
    StudyPlan p = joint_study(scene, "radial");
    // first touch at the bore's bottom (0, −R_B): the journal's axis at y = −c_r
    p.obstacle.kind = RigidObstacle::Kind::cylinder;
    p.obstacle.offset = scene.geometry.c_r;
    return p;
  }
} // namespace clearjoint::fe
