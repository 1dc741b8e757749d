// Each study's plan (fe_stage/study_plan.h) from the scene: the one place where the study is
// chosen; a new study is a new file here. No deal.II.
#pragma once

#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <string>

namespace clearjoint::fe
{
  /// What the joint studies share: the bearing ring and the journal (rigid, or deformable and
  /// paired on common rays), the journal's cylinder for the obstacle; the caller places it.
  StudyPlan joint_study(const FeScene &scene, const std::string &name);
  /// What the verification blocks share: Q2, a rigid indenter or a deformable one coupled by
  /// dual mortar, no contact required at every increment.
  StudyPlan block_study(const FeScene &scene, const std::string &name);

  StudyPlan radial_study(const FeScene &scene);
  StudyPlan misalignment_study(const FeScene &scene);
  StudyPlan hertz_study(const FeScene &scene);
  StudyPlan patch_study(const FeScene &scene);
  StudyPlan impact_study(const FeScene &scene);
  StudyPlan rolling_study(const FeScene &scene);

  /// The plan of scene.study.
  StudyPlan plan_study(const FeScene &scene);
}  // namespace clearjoint::fe
