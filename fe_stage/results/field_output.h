// What the model leaves for the user to look at, besides the CSV tables: the fields a ParaView
// user opens (VTU pieces per rank, a PVTU per written state, one PVD indexing them) and the
// yield check (von Mises of the linear-elastic stress against the yield stress, per body and
// per cell). FieldOutput owns the PVD records and the list of files written; it reads the
// model's parts and changes none of them.
#pragma once

#include "fe_stage/contact/contact_problem.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/results/material_point_field.h"
#include "fe_stage/scene.h"
#include "fe_stage/study_plan.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <string>
#include <utility>
#include <vector>

namespace clearjoint::fe::detail
{
  class FieldOutput
  {
  public:
    /// The parts the output reads.
    struct Parts
    {
      const FeScene &scene;
      const StudyPlan &plan;  // the bodies' names
      const Bodies &bodies;
      const DofSpace &dofs;
      const State &state;
      const ContactProblem &contact;
      const MaterialLaw &material;
      MPI_Comm comm;
    };

    /// Fields are written to <output_dir>/fields when `write_fields` and an output directory
    /// are given; otherwise write() is never called and files() is empty.
    FieldOutput(const Parts &parts, const std::string &output_dir, bool write_fields);

    bool enabled() const { return enabled_; }
    /// <output_dir>/fields made (rank 0) before the first write.
    void create_directory() const;
    /// The fields of the current state as state `counter` at time (or push) `t`, and the PVD
    /// written again to index it. Collective. Displacement, strain, principal strains, stress
    /// and von Mises; contact pressure/gap/status/shear/slip as Abaqus's CPRESS/COPEN/CSTATUS/
    /// CSHEAR/CSLIP; subdomain. With a material history (the law's has_history()) the stress is
    /// the material points' own, each output point the nearest's (results/
    /// material_point_field.h), and the
    /// cells carry the points' largest equivalent plastic strain and von Mises stress; without
    /// one the stress comes from the displacement and the cells carry the yield check's
    /// plastic_zone.
    void write(unsigned int counter, double t);
    /// The files written so far (rank 0's list); `with_pvd`: the PVD that indexes them too
    /// (a run that completed).
    std::vector<std::string> files(bool with_pvd) const;

    /// Von Mises against scene.material.yield_stress at every quadrature point (collective);
    /// optionally each cell's volume fraction above yield (the plastic_zone field).
    YieldCheck check_yield(dealii::Vector<float> *cell_fraction_above) const;
    /// One log line per body (rank 0): a warning where the linear-elastic result is not valid.
    void log_yield_check(const YieldCheck &check) const;

  private:
    /// The material points' stresses, each with its own plastic strain, on the cells' output
    /// points (`stress`, on `stress_dofs`); per cell, the points' largest equivalent plastic strain and
    /// largest von Mises stress.
    void plastic_cell_fields(const dealii::DoFHandler<3> &stress_dofs,
                             const MaterialPointField &point_field,
                             dealii::TrilinosWrappers::MPI::Vector &stress,
                             dealii::Vector<float> &alpha_max, dealii::Vector<float> &vm_max) const;

    Parts parts_;
    std::string dir_;  // <output_dir>/fields
    bool enabled_;
    unsigned int rank_;
    std::vector<std::pair<double, std::string>> pvd_records_;  // (t, PVTU file) per state
    std::vector<std::string> files_;
  };
}  // namespace clearjoint::fe::detail
