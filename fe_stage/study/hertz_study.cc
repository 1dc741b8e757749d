// Verification against Hertz (SPEC §5): a rigid sphere — or a deformable body of the same
// material whose bottom is Hertz's profile r²/2R, coupled by dual mortar — pressed into the
// block (quarter model).
#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan hertz_study(const FeScene &scene)
  {
    StudyPlan p;
    p.name = "hertz";
    p.mesh = StudyPlan::Mesh::block;
    p.degree = 2;
    p.deformable_partner = scene.verification.deformable_indenter;
    // the sphere's centre at y = R − δ: it touches the block's top (y = 0) at δ = 0
    p.obstacle.kind = RigidObstacle::Kind::sphere;
    p.obstacle.radius = scene.verification.sphere_radius;
    p.pairing = p.deformable_partner ? StudyPlan::Pairing::mortar : StudyPlan::Pairing::obstacle;
    p.hertz = true;
    p.must_touch = false;  // the first increments of a small push may touch at no node
    p.body_names = {"block", "indenter"};
    p.records = "contact force against the indentation, for F = (4/3) E* √R δ^(3/2)";
    return p;
  }
} // namespace clearjoint::fe
