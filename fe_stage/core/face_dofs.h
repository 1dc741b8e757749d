// The displacement DoFs of a face, grouped per node: what contact pairing hands to mortar and
// to the node lists.
#pragma once

#include <deal.II/base/types.h>

#include <array>
#include <vector>

namespace clearjoint::fe::detail
{
  /// The DoFs of each node of a face, grouped per node (x, y, z), in face order.
  template <typename CellIterator>
  std::vector<std::array<dealii::types::global_dof_index, 3>> face_node_dofs(
    const CellIterator &cell, const unsigned int f,
    std::vector<dealii::types::global_dof_index> &face_dofs)
  {
    const auto &fe = cell->get_fe();
    face_dofs.resize(fe.n_dofs_per_face());
    cell->face(f)->get_dof_indices(face_dofs);
    std::vector<std::array<dealii::types::global_dof_index, 3>> nodes(fe.n_dofs_per_face() / 3);
    for (unsigned int k = 0; k < face_dofs.size(); ++k)
      {
        const auto ci = fe.face_system_to_component_index(k);
        nodes[ci.second][ci.first] = face_dofs[k];
      }
    return nodes;
  }
}  // namespace clearjoint::fe::detail
