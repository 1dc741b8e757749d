// A user's bearing from a Gmsh mesh (docs/geometry.md): groups to boundary ids, symmetry planes.
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/mesh/charts.h"

#include "geometry/msh_check.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  /// The bearing of a user's Gmsh mesh (geometry.mesh, MSH 2.2 with the physical groups of
  /// docs/geometry.md). The mesh is read and checked without deal.II first (missing groups,
  /// non-hexahedra, inverted cells: an InputError listing every problem), then its bearing
  /// hexahedra become the coarse mesh on the bearing's polar chart, so Q2 curved faces follow
  /// the bore. Boundary ids come from the surface groups; boundary faces outside the groups
  /// that lie on x = 0 or z = 0 are symmetry planes, and set the symmetry factor. The journal
  /// is the scene's rigid cylinder (R_J, L_J from the geometry keys), or with a deformable
  /// journal loading the mesh's own journal (its volume, journal_contact surface on the
  /// journal chart, journal_loaded end faces), paired with the bore by dual mortar.
  void Bodies::make_gmsh_grid()
  {
    const auto &G = scene_.geometry;
    // validate_scene has checked the mesh against the scene (groups, cells, bore radius,
    // journal loading, length) before any output was written
    const geometry::MshMesh msh = geometry::read_joint_mesh(G.mesh);
    auto tag_of = [&](const std::string &name, const int group_dim) {
      for (const auto &g : msh.groups)
        if (g.name == name && g.dim == group_dim)
          return g.tag;
      throw InputError(G.mesh, name, "(missing)",
                       "a physical group of dimension " + std::to_string(group_dim));
    };
    const int bearing = tag_of("bearing", 3);
    const bool journal = scene_.loading.journal != JournalLoading::rigid;
    const int journal_tag = journal ? tag_of("journal", 3) : -1;

    // Gmsh numbers a hexahedron's corners counter-clockwise per face, deal.II
    // lexicographically: deal.II corner i is Gmsh corner gmsh_corner[i].
    constexpr std::array<unsigned int, 8> gmsh_corner = {0, 1, 3, 2, 4, 5, 7, 6};
    std::vector<int> vertex_of(msh.nodes.size(), -1);
    std::vector<Point<dim>> vertices;
    auto vertex = [&](const std::size_t node) {
      if (vertex_of[node] < 0)
        {
          vertex_of[node] = static_cast<int>(vertices.size());
          const auto &x = msh.nodes[node];
          vertices.emplace_back(x[0], x[1], x[2]);
        }
      return static_cast<unsigned int>(vertex_of[node]);
    };
    std::vector<CellData<dim>> cells;
    for (const auto &e : msh.elements)
      if (e.type == 5 && (e.physical == bearing || (journal && e.physical == journal_tag)))
        {
          CellData<dim> c;
          for (unsigned int i = 0; i < 8; ++i)
            c.vertices[i] = vertex(e.nodes[gmsh_corner[i]]);
          c.material_id = e.physical == bearing ? 0 : 1;
          c.manifold_id = e.physical == bearing ? 0 : numbers::flat_manifold_id;
          cells.push_back(c);
        }

    // Surface groups → boundary ids, keyed by the sorted corner vertices of each quad.
    std::map<std::array<unsigned int, 4>, types::boundary_id> face_id;
    std::vector<std::pair<std::string, types::boundary_id>> surfaces = {
      {"bearing_contact", bid_contact}, {"bearing_fixed", bid_fixed}};
    if (journal)
      {
        surfaces.emplace_back("journal_contact", bid_journal_surface);
        surfaces.emplace_back("journal_loaded", bid_journal_end);
      }
    for (const auto &[name, id] : surfaces)
      {
        const int tag = tag_of(name, 2);
        for (const auto &e : msh.elements)
          if (e.type == 3 && e.physical == tag)
            {
              std::array<unsigned int, 4> key;
              for (unsigned int i = 0; i < 4; ++i)
                key[i] = vertex(e.nodes[i]);
              std::sort(key.begin(), key.end());
              face_id[key] = id;
            }
      }

    Triangulation<dim> serial;
    try
      {
        GridTools::consistently_order_cells(cells);
      }
    catch (const std::exception &)
      {
        // deal.II handles non-standard face orientations in 3D; ordering only saves work
      }
    serial.create_triangulation(vertices, cells, SubCellData());
    // the bearing on its polar chart (faces and edges too: the curved bore for the Q2
    // mapping); the journal's cells flat, its cylindrical surface on the journal chart (below)
    for (const auto &cell : serial.active_cell_iterators())
      cell->set_all_manifold_ids(cell->material_id() == 0 ? 0 : numbers::flat_manifold_id);
    const double plane_tol = 1e-8 * G.R_B;
    bool sym_x = false, sym_z = false;
    unsigned int n_contact = 0, n_fixed = 0;
    for (const auto &cell : serial.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const auto face = cell->face(f);
            std::array<unsigned int, 4> key;
            bool on_x0 = true, on_z0 = true;
            for (unsigned int v = 0; v < 4; ++v)
              {
                key[v] = face->vertex_index(v);
                on_x0 = on_x0 && std::abs(face->vertex(v)[0]) < plane_tol;
                on_z0 = on_z0 && std::abs(face->vertex(v)[2]) < plane_tol;
              }
            std::sort(key.begin(), key.end());
            const auto it = face_id.find(key);
            types::boundary_id id = bid_free;
            if (it != face_id.end())
              id = it->second;
            else if (on_x0)
              id = bid_sym_x;
            else if (on_z0)
              id = bid_sym_z;
            n_contact += id == bid_contact;
            n_fixed += id == bid_fixed;
            sym_x = sym_x || id == bid_sym_x;
            sym_z = sym_z || id == bid_sym_z;
            face->set_boundary_id(id);
          }
    if (journal)
      for (const auto &cell : serial.active_cell_iterators())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bid_journal_surface)
            cell->face(f)->set_all_manifold_ids(1);
    if (n_contact == 0 || n_fixed == 0)
      throw InputError(G.mesh, n_contact == 0 ? "bearing_contact" : "bearing_fixed",
                       "(no boundary face of the bearing)", "boundary faces of the bearing");

    tria_.copy_triangulation(serial);
    tria_.set_manifold(0, RayChart(G.c_r, G.R_J(), false));
    if (journal)
      tria_.set_manifold(1, RayChart(G.c_r, G.R_J(), true));  // axis at y = −c_r
    refine_joint_mesh();
    symmetry_factor_ = (sym_x ? 2.0 : 1.0) * (sym_z ? 2.0 : 1.0);
    if (Utilities::MPI::this_mpi_process(comm_) == 0)
      log::info("fe_stage: " + G.mesh + ": " + std::to_string(cells.size()) +
                (journal ? " bearing and journal" : " bearing") + " hexahedra, symmetry planes" +
                (sym_x ? " x = 0" : "") + (sym_z ? " z = 0" : "") +
                (sym_x || sym_z ? "" : " none") + " (force factor " +
                format_value(symmetry_factor_) + ")");
  }
}  // namespace clearjoint::fe::detail
