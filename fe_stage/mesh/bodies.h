// The meshed bodies: the distributed triangulation (bearing = material 0, a deformable journal
// or indenter = material 1), the curved mapping, the symmetry factor from the modelled part
// to the full body, and the smallest cell size. It builds the mesh the scene asks for — a
// user's Gmsh bearing (gmsh_mesh.cc), the generated joint on common rays with its refinement
// toward the contact (joint_mesh.cc), or the verification block (block_mesh.cc) — and carries
// out the refinement a study marks (the adaptive cycles' indicator).
//
// It knows the scene and the study's plan, nothing of DoFs, contact or solvers: they are
// built on it.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/mesh/charts.h"
#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <deal.II/base/point.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/vector.h>

namespace clearjoint::fe::detail
{
  class Bodies
  {
  public:
    /// An empty triangulation on `comm`; the mapping MappingQ(max(2, plan.degree)) (at least
    /// quadratic: the bore and the journal are curved even for a Q1 field).
    Bodies(const FeScene &scene, const StudyPlan &plan, MPI_Comm comm);

    /// The scene's mesh (Gmsh, generated joint or block) with its refinements and symmetry
    /// factor.
    void build();

    /// Refines the cells with the largest `indicator` (one value per active cell), the
    /// fraction `fraction` of them (p4est keeps the 2:1 balance).
    void refine_largest(const Vector<float> &indicator, double fraction);

    parallel::distributed::Triangulation<dim> &triangulation() { return tria_; }
    const parallel::distributed::Triangulation<dim> &triangulation() const { return tria_; }
    const MappingQ<dim> &mapping() const { return mapping_; }
    /// The full bodies' force or energy over the modelled part's (2 per symmetry plane).
    double symmetry_factor() const { return symmetry_factor_; }
    /// [m] the smallest cell's shortest vertex distance (all ranks), after the last change.
    double h_min() const { return h_min_; }

    /// A point of the deformable journal where it sits → the aligned journal as meshed (its
    /// axis e_z through (0, −c_r, 0)) (plan.journal_pose; identity unless tilted).
    Point<dim> journal_local(const Point<dim> &X) const;

  private:
    /// The aligned journal's point x (as meshed) where the journal sits (journal_local's
    /// inverse).
    Point<dim> journal_world(const Point<dim> &x) const;
    void make_radial_grid();
    void set_joint_manifold_ids(Triangulation<dim> &serial, const RayChart &journal_chart) const;
    void set_joint_boundary_ids(Triangulation<dim> &serial, bool full, bool full_z) const;
    void make_gmsh_grid();
    void make_block_grid();
    void refine_joint_mesh();
    template <typename CellIterator>
    bool bore_gap_below(const CellIterator &cell, double limit) const;
    void update_h_min();

    const FeScene &scene_;
    const StudyPlan &plan_;
    MPI_Comm comm_;
    parallel::distributed::Triangulation<dim> tria_;
    const MappingQ<dim> mapping_;
    double symmetry_factor_ = 1.0;
    double h_min_ = 0.0;
  };

  /// Study rolling: the angle [rad] from a bore point at frame angle `angle` to the arc of
  /// frame angles the contact point passes over the run (0 on it): [−sweep, 0], the sweep the
  /// bearing's ω_B t_end unless given (a deformable journal's surface: its own turn).
  double rolling_path_distance(const FeScene &scene, double angle, double sweep = -1.0);
}  // namespace clearjoint::fe::detail
