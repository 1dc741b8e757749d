#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan joint_study(const FeScene &scene, const std::string &name)
  {
    StudyPlan p;
    p.name = name;
    p.mesh = StudyPlan::Mesh::joint;
    p.degree = scene.mesh.degree;
    p.deformable_partner = scene.loading.journal != JournalLoading::rigid;
    p.obstacle.radius = scene.geometry.R_J();
    p.obstacle.half_length = 0.5 * scene.geometry.L_J();
    // a deformable journal meets the bore by dual mortar (any two meshes); node_to_node on
    // the generated meshes' common rays is kept as an option: measured no faster on the
    // default mesh at three levels, same F within 1.5e-4 (docs/benchmarks.md)
    if (!p.deformable_partner)
      p.pairing = StudyPlan::Pairing::obstacle;
    else
      p.pairing = scene.contact.pairing == Contact::Pairing::node_to_node ?
                    StudyPlan::Pairing::common_rays :
                    StudyPlan::Pairing::mortar;
    p.body_names = {"bearing", "journal"};
    p.journal_pose.aligned_centre_y = p.journal_pose.centre_y = -scene.geometry.c_r;
    p.journal_is_slave = scene.contact.mortar_slave == Contact::MortarSlave::journal;
    return p;
  }

  StudyPlan block_study(const FeScene &scene, const std::string &name)
  {
    StudyPlan p;
    p.name = name;
    p.mesh = StudyPlan::Mesh::block;
    p.degree = 2;
    p.deformable_partner = scene.verification.deformable_indenter;
    p.pairing = p.deformable_partner ? StudyPlan::Pairing::mortar : StudyPlan::Pairing::obstacle;
    p.must_touch = false;  // the first increments of a small push may touch at no node
    p.body_names = {"block", "indenter"};
    return p;
  }

  StudyPlan plan_study(const FeScene &scene)
  {
    switch (scene.study)
      {
        case Study::radial:
          return radial_study(scene);
        case Study::misalignment:
          return misalignment_study(scene);
        case Study::hertz:
          return hertz_study(scene);
        case Study::patch:
          return patch_study(scene);
        case Study::impact:
          return impact_study(scene);
        case Study::rolling:
          return rolling_study(scene);
      }
    return radial_study(scene);
  }
}  // namespace clearjoint::fe
