// Dual-mortar pairing of non-matching surfaces (mortar.h) for the verification block and its
// deformable indenter.
#include "fe_stage/core/contact_model.h"
#include "fe_stage/core/face_dofs.h"
#include "fe_stage/mortar.h"

namespace clearjoint::fe::detail
{
  /// Two non-matching bodies (the verification block and a deformable indenter): dual mortar
  /// (mortar.h). Each slave node of the block's top face (the plane y = 0, normal −e_y into
  /// the block) gets ĝ = g̃0 + n·(u − Σ_m C_sm u_m) with the weighted gap g̃0 and the mortar
  /// coefficients C_sm of the indenter's bottom nodes; an active node's constraint is then the
  /// same kind of line as node-to-node contact, with several partners.
  void ContactModel::find_mortar_contact_nodes(
    const std::map<types::global_dof_index, Point<dim>> &support,
    std::map<types::global_dof_index, ContactNode> &by_x_dof)
  {
    std::vector<types::global_dof_index> face_dofs(fe_->n_dofs_per_face());
    using NodeDofs = std::array<types::global_dof_index, dim>;
    // Master faces from every rank (the face facing a slave node is often on no cell this
    // rank sees): per face its node count, then per node 3 DoFs and the position.
    std::vector<double> mine;
    for (const auto &cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == bid_indenter_surface)
            {
              const auto nodes = face_node_dofs(cell, f, face_dofs);
              mine.push_back(double(nodes.size()));
              for (const auto &d : nodes)
                {
                  const Point<dim> &X = support.at(d[0]);
                  mine.insert(mine.end(), {double(d[0]), double(d[1]), double(d[2]), X[0],
                                           X[1], X[2]});
                }
            }
    std::vector<mortar::Face> master;
    std::map<long, NodeDofs> master_dofs;
    for (const auto &part : Utilities::MPI::all_gather(comm_, mine))
      for (std::size_t i = 0; i < part.size();)
        {
          const unsigned int nn = static_cast<unsigned int>(part[i++]);
          mortar::Face face;
          for (unsigned int k = 0; k < nn; ++k, i += 6)
            {
              NodeDofs d;
              for (unsigned int c = 0; c < dim; ++c)
                d[c] = static_cast<types::global_dof_index>(part[i + c]);
              face.nodes.push_back(static_cast<long>(d[0]));
              face.X.push_back({part[i + 3], part[i + 4], part[i + 5]});
              master_dofs[static_cast<long>(d[0])] = d;
            }
          master.push_back(std::move(face));
        }
    // Slave faces: this rank's owned and ghost cells (every cell holding a DoF of an owned
    // cell is among them, so owned and ghost nodes of owned cells see all their faces).
    std::vector<mortar::Face> slave;
    std::map<long, NodeDofs> slave_dofs;
    for (const auto &cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_contact)
            {
              mortar::Face face;
              for (const auto &d : face_node_dofs(cell, f, face_dofs))
                {
                  const Point<dim> &X = support.at(d[0]);
                  face.nodes.push_back(static_cast<long>(d[0]));
                  face.X.push_back({X[0], X[1], X[2]});
                  slave_dofs[static_cast<long>(d[0])] = d;
                }
              slave.push_back(std::move(face));
            }
    std::vector<mortar::SlaveNode> slave_nodes;
    for (const auto &[id, d] : slave_dofs)
      slave_nodes.push_back({id, {0.0, -1.0, 0.0}});
    mortar::Options options;
    // 8 × 3 Gauss points per direction of each slave face: the mortar integrals have kinks
    // where master faces end; their error (≈ 2e-3 of a master nodal force at 8 sub-intervals,
    // 8e-3 at 4, mortar_test) shows up as non-uniform pressure in the patch test.
    options.subdivisions = 8;
    // Quadrature points farther apart than this cannot close under a push of δ_max; their
    // nodes come out incomplete and are left out (they cannot touch).
    options.max_distance = 4.0 * scene_.loading.delta_max;
    const double window_gap = 2.0 * scene_.loading.delta_max;
    for (const auto &cp : mortar::couple(slave, slave_nodes, master, options))
      {
        const NodeDofs &dofs = slave_dofs.at(cp.node);
        if (!cp.complete || cp.weight <= 0.0 || fixed_constraints_.is_constrained(dofs[1]))
          continue;  // out of reach, or hanging (it follows its masters)
        ContactNode cn;
        cn.dofs = dofs;
        cn.X = support.at(dofs[0]);
        cn.owned = owned_.is_element(dofs[0]);
        cn.n = Tensor<1, dim>({0.0, -1.0, 0.0});
        cn.g0 = cp.gap;
        cn.two_body = true;
        cn.constrained_component = 1;
        cn.candidate = cp.gap <= window_gap;
        for (const auto &[m, w] : cp.masters)
          cn.partners.push_back({master_dofs.at(m), w, false});
        by_x_dof.emplace(dofs[0], cn);
      }
  }
} // namespace clearjoint::fe::detail
