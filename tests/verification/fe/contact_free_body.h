// The model's owners for a scene's bodies without contact, set up as the model sets them up
// (mesh, DoFs, the assembler's sparsity, no contact cells, the elastoplastic law sized to the
// quadrature points): for tests that drive the assembly with their own Newton loop and their
// own boundary values — finite_assembly_test's patch block, plastic_locking_test's cylinder.
#pragma once

#include "fe_stage/core/assembler.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"
#include "fe_stage/study/study.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <memory>
#include <utility>
#include <vector>

namespace clearjoint::fe::test
{
  struct ContactFreeBody
  {
    FeScene scene;
    StudyPlan plan;
    MPI_Comm comm = MPI_COMM_WORLD;
    detail::Bodies bodies;
    detail::DofSpace dofs;
    detail::Assembler system;
    std::unique_ptr<detail::MaterialLaw> law;

    explicit ContactFreeBody(FeScene s)
      : scene(std::move(s))
      , plan(plan_study(scene))
      , bodies(scene, plan, comm)
      , dofs(scene, plan, bodies, comm)
      , system(scene, bodies, dofs, comm)
    {
      bodies.build();
      dofs.distribute(true);
      dealii::DynamicSparsityPattern dsp(dofs.relevant());
      dealii::DoFTools::make_sparsity_pattern(dofs.handler(), dsp);
      dealii::SparsityTools::distribute_sparsity_pattern(dsp, dofs.owned(), comm, dofs.relevant());
      system.reinit(dsp);
      const unsigned int n_cells = bodies.triangulation().n_active_cells();
      system.set_contact_cells(std::vector<int>(n_cells, -1), 0);  // no contact cells
      law = detail::make_material(scene, true);
      law->resize(std::size_t(n_cells) * system.n_q_points());
    }
  };
}  // namespace clearjoint::fe::test
