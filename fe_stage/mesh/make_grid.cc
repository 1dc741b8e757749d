// Which mesh a scene gets (Gmsh, generated joint, verification block).
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  void ContactModel::make_grid()
  {
    if (!scene_.geometry.mesh.empty())
      make_gmsh_grid();
    else if (plan_.mesh == StudyPlan::Mesh::joint)
      make_radial_grid();
    else
      make_block_grid();
  }
}  // namespace clearjoint::fe::detail
