// Joining separately meshed bodies into one coarse mesh without gluing them together.
#pragma once

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <vector>

namespace clearjoint::fe::detail
{
  /// Appends the coarse cells of `body` to (vertices, cells) as a separate body with the given
  /// material id: its vertices are copied, never shared, so two bodies that touch stay apart
  /// (GridGenerator::merge_triangulations would glue their coincident vertices).
  inline void append_body(const dealii::Triangulation<3> &body,
                          const dealii::types::material_id material,
                          std::vector<dealii::Point<3>> &vertices,
                          std::vector<dealii::CellData<3>> &cells)
  {
    auto [body_vertices, body_cells, body_sub] =
      dealii::GridTools::get_coarse_mesh_description(body);
    (void)body_sub;
    const unsigned int offset = vertices.size();
    vertices.insert(vertices.end(), body_vertices.begin(), body_vertices.end());
    for (auto c : body_cells)
      {
        for (auto &v : c.vertices)
          v += offset;
        c.material_id = material;
        cells.push_back(c);
      }
  }
}  // namespace clearjoint::fe::detail
