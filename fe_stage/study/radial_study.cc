// The thickness study (paper §3.1): the aligned journal pushed radially (−y) into the bearing
// ring held at its outer half; rigid, or deformable and pushed at its end faces or its axis.
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan radial_study(const FeScene &scene)
  {
    StudyPlan p;
    p.name = "radial";
    p.mesh = StudyPlan::Mesh::joint;
    p.degree = scene.mesh.degree;
    p.deformable_partner = scene.loading.journal != JournalLoading::rigid;
    // first touch at the bore's bottom (0, −R_B): the journal's axis at y = −c_r
    p.obstacle.kind = RigidObstacle::Kind::cylinder;
    p.obstacle.radius = scene.geometry.R_J();
    p.obstacle.half_length = 0.5 * scene.geometry.L_J();
    p.obstacle.offset = scene.geometry.c_r;
    // the bearing's and the journal's surface nodes lie on common rays (mesh/charts.h)
    p.pairing = p.deformable_partner ? StudyPlan::Pairing::common_rays :
                                       StudyPlan::Pairing::obstacle;
    p.body_names = {"bearing", "journal"};
    p.records = "contact force on the bearing against the journal's push beyond first touch";
    return p;
  }
} // namespace clearjoint::fe
