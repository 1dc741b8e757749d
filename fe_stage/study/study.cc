#include "fe_stage/study/study.h"

namespace clearjoint::fe
{
  StudyPlan plan_study(const FeScene &scene)
  {
    switch (scene.study)
      {
        case Study::radial: return radial_study(scene);
        case Study::misalignment: return misalignment_study(scene);
        case Study::hertz: return hertz_study(scene);
        case Study::patch: return patch_study(scene);
      }
    return radial_study(scene);
  }
} // namespace clearjoint::fe
