// The impact study (paper §3.2): the rigid journal launched into the bearing ring held as in the
// radial study. The same bodies, supports and first-touch placement as the thickness study; what
// differs is the time integration (solve/impact_run.cc): the journal's position is an
// unknown of each time step, found from its equation of motion, not a prescribed push.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan impact_study(const FeScene &scene)
  {
    StudyPlan p = joint_study(scene, "impact");
    p.obstacle.kind = RigidObstacle::Kind::cylinder;
    p.obstacle.offset = scene.geometry.c_r;  // first touch at the bore's bottom
    p.dynamic = true;
    p.must_touch = false;  // the journal leaves the bearing at the end of the impact
    return p;
  }
}  // namespace clearjoint::fe
