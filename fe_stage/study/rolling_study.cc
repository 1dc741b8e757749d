// The rolling study (paper §3.4): the elastoplastic bearing ring, turning at ω_B, computed in its
// co-rotating frame; the rigid journal pushed radially from first touch and turned by friction
// alone. The whole ring is meshed (the contact zone travels round the bore as the bearing turns),
// the axial mid-plane is a symmetry plane. solve/rolling_run.cc runs it.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan rolling_study(const FeScene &scene)
  {
    StudyPlan p = joint_study(scene, "rolling");
    p.obstacle.kind = RigidObstacle::Kind::cylinder;
    p.obstacle.offset = scene.geometry.c_r;  // first touch at the bore's bottom
    p.rolling = true;
    // The push starts from first touch while the bearing turns its nodes past the journal: in
    // the first nanometres the journal can sit between two bore nodes (measured: δ = 42 nm at
    // 1.06 ms, coarse ring, 50 steps to 0.25 s), so a step with no node in contact is the
    // mesh's answer there (no force, no torque: the journal's spin carries on), not a failure.
    // As a failure it cut the step without end, each cut making δ smaller still.
    p.must_touch = false;
    return p;
  }
}  // namespace clearjoint::fe
