// The verification block (patch test, Hertz) and its optional deformable indenter.
#include "fe_stage/mesh/append_body.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/mesh/boundary_ids.h"
#include "fe_stage/mesh/charts.h"

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
  /// The verification block [0,W]×[−H,0]×[0,W] (quarter model: symmetry planes x = 0, z = 0),
  /// roller support u_y = 0 at y = −H, contact on y = 0.
  void Bodies::make_block_grid()
  {
    const auto &V = scene_.verification;
    const unsigned int n = V.n_cells;
    const IndenterChart chart(V.sphere_radius, V.indenter_height);
    if (!plan_.deformable_partner)
      GridGenerator::subdivided_hyper_rectangle(tria_, {n, n, n},
                                                Point<dim>(0.0, -V.block_height, 0.0),
                                                Point<dim>(V.block_width, 0.0, V.block_width));
    else
      {
        // Two bodies in one triangulation that share no vertex (they touch at y = 0): the
        // block below (material 0) and the indenter above (material 1), meshed with
        // different cell counts so that their contact surfaces do not match.
        Triangulation<dim> lower, upper;
        const unsigned int m = V.indenter_n_cells;
        GridGenerator::subdivided_hyper_rectangle(lower, {n, n, n},
                                                  Point<dim>(0.0, -V.block_height, 0.0),
                                                  Point<dim>(V.block_width, 0.0, V.block_width));
        GridGenerator::subdivided_hyper_rectangle(upper, {m, m, m}, Point<dim>(0.0, 0.0, 0.0),
                                                  Point<dim>(V.block_width, V.indenter_height,
                                                             V.block_width));
        if (plan_.hertz)
          GridTools::transform([&](const Point<dim> &p) { return chart.push_forward(p); }, upper);
        std::vector<Point<dim>> vertices;
        std::vector<CellData<dim>> cells;
        append_body(lower, 0, vertices, cells);
        append_body(upper, 1, vertices, cells);
        tria_.create_triangulation(vertices, cells, SubCellData());
        if (plan_.hertz)
          {
            for (const auto &cell : tria_.active_cell_iterators())
              if (cell->material_id() == 1)
                cell->set_all_manifold_ids(1);
            tria_.set_manifold(1, chart);
          }
      }
    // Boundary ids from the face vertices (exact: they lie on the generating planes).
    const double tol = 1e-10 * V.block_width;
    for (const auto &cell : tria_.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            auto all = [&](auto &&pred) {
              for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                {
                  Point<dim> X = cell->face(f)->vertex(v);
                  if (cell->material_id() == 1 && plan_.hertz)
                    X = chart.pull_back(X);
                  if (!pred(X))
                    return false;
                }
              return true;
            };
            types::boundary_id id = bid_free;
            if (cell->material_id() == 1)
              {
                if (all([&](const Point<dim> &X) { return std::abs(X[1]) < tol; }))
                  id = bid_indenter_surface;
                else if (all([&](const Point<dim> &X) {
                           return std::abs(X[1] - V.indenter_height) < tol;
                         }))
                  id = bid_indenter_top;
              }
            else if (all([&](const Point<dim> &X) { return std::abs(X[1]) < tol; }))
              id = bid_contact;
            else if (all(
                       [&](const Point<dim> &X) { return std::abs(X[1] + V.block_height) < tol; }))
              id = bid_fixed;
            if (id == bid_free)
              {
                if (all([&](const Point<dim> &X) { return std::abs(X[0]) < tol; }))
                  id = bid_sym_x;
                else if (all([&](const Point<dim> &X) { return std::abs(X[2]) < tol; }))
                  id = bid_sym_z;
              }
            cell->face(f)->set_boundary_id(id);
          }
    if (!plan_.hertz)  // the patch test: uniformly fine
      tria_.refine_global(V.contact_refinements);
    else
      {
        // Graded: round k refines the cells within refine_radius·2^(n−1−k) of the contact
        // point, so the contact zone is uniformly fine and hanging nodes stay outside it.
        const unsigned int nr = V.contact_refinements;
        for (unsigned int k = 0; k < nr; ++k)
          {
            const double radius = V.refine_radius * std::pow(2.0, double(nr - 1 - k));
            for (const auto &cell : tria_.active_cell_iterators())
              if (cell->is_locally_owned())
                {
                  // distance from the origin to the cell's bounding box
                  const auto box = cell->bounding_box();
                  double d2 = 0.0;
                  for (unsigned int i = 0; i < dim; ++i)
                    {
                      const double lo = box.lower_bound(i), hi = box.upper_bound(i);
                      const double di = std::max({lo, 0.0 - hi, 0.0});
                      d2 += di * di;
                    }
                  if (std::sqrt(d2) < radius)
                    cell->set_refine_flag();
                }
            tria_.execute_coarsening_and_refinement();
          }
      }
    symmetry_factor_ = 4.0;
  }
}  // namespace clearjoint::fe::detail
