// Which mesh a scene gets (Gmsh, generated joint, verification block), and its smallest cell.
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
    h_min_ = Utilities::MPI::min(
      [&] {
        double h = std::numeric_limits<double>::max();
        for (const auto &cell : tria_.active_cell_iterators())
          if (cell->is_locally_owned())
            h = std::min(h, cell->minimum_vertex_distance());
        return h;
      }(),
      comm_);
  }
} // namespace clearjoint::fe::detail
