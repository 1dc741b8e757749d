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
    // a core-loaded journal placed off the axial centre, or slid along z over the push: the
    // whole length, and the journal's surface as the mortar slave (its ends leave the bore's
    // mesh planes; scene.cc rejects the bore as slave then)
    p.journal_pose.centre_z = scene.loading.axial_offset;
    if (scene.loading.axial_offset != 0.0 || scene.loading.axial_slide != 0.0)
      {
        p.full_length = true;
        p.journal_is_slave = true;
      }
    return p;
  }
}  // namespace clearjoint::fe
