// The meshed bodies (mesh/bodies.h): which mesh a scene gets (Gmsh, generated joint,
// verification block), the refinement a study marks, the smallest cell size.
#include "fe_stage/mesh/bodies.h"

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/grid_refinement.h>

#include <algorithm>
#include <limits>

namespace clearjoint::fe::detail
{
  Bodies::Bodies(const FeScene &scene, const StudyPlan &plan, MPI_Comm comm)
    : scene_(scene)
    , plan_(plan)
    , comm_(comm)
    , tria_(comm, Triangulation<dim>::limit_level_difference_at_vertices)
    , mapping_(std::max(2u, plan.degree))
  {}

  void Bodies::build()
  {
    if (!scene_.geometry.mesh.empty())
      make_gmsh_grid();
    else if (plan_.mesh == StudyPlan::Mesh::joint)
      make_radial_grid();
    else
      make_block_grid();
    update_h_min();
  }

  void Bodies::refine_largest(const Vector<float> &indicator, const double fraction)
  {
    parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(tria_, indicator,
                                                                           fraction, 0.0);
    tria_.execute_coarsening_and_refinement();
    update_h_min();
  }

  void Bodies::update_h_min()
  {
    double h = std::numeric_limits<double>::max();
    for (const auto &cell : tria_.active_cell_iterators())
      if (cell->is_locally_owned())
        h = std::min(h, cell->minimum_vertex_distance());
    h_min_ = Utilities::MPI::min(h, comm_);
  }

  Point<dim> Bodies::journal_local(const Point<dim> &X) const
  {
    const auto l = plan_.journal_pose.to_local({X[0], X[1], X[2]});
    return Point<dim>(l[0], l[1], l[2]);
  }

  Point<dim> Bodies::journal_world(const Point<dim> &x) const
  {
    const auto X = plan_.journal_pose.to_world({x[0], x[1], x[2]});
    return Point<dim>(X[0], X[1], X[2]);
  }
}  // namespace clearjoint::fe::detail
