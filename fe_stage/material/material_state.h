// The bodies' material on the mesh (step-44's quadrature-point history, as one object): it owns
// the material law with its history (MaterialLaw, material/material_law.h; make_material chooses
// J2 with its hardening table for material.model elastoplastic, else linear elastic) and does
// what needs the law at every quadrature point of the mesh at once: size the history, commit a
// converged state (and with the step's energies, for the rolling study's balance), and the
// strain profile at the contact's mid-plane. It reads the bodies, the DoF space and u; the
// assembler evaluates the law itself (core/assembler.h), the fields read it through law().
//
// A material point is active_cell_index · n_q + q, n_q the assembler's points per cell
// (init_history).
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/core/dof_space.h"
#include "fe_stage/core/state.h"
#include "fe_stage/fe_model.h"
#include "fe_stage/material/material_law.h"
#include "fe_stage/mesh/bodies.h"
#include "fe_stage/scene.h"

#include <deal.II/base/mpi.h>

#include <memory>
#include <vector>

namespace clearjoint::fe::detail
{
  /// A converged elastoplastic step committed to the points' history: its energies and the
  /// extremes of the committed states.
  struct PlasticEnergies
  {
    double plastic_work_step = 0.0;  // [J] full body
    double elastic_energy = 0.0;     // [J]
    double plastic_volume = 0.0;     // [m^3]
    double max_plastic_strain = 0.0, max_strain = 0.0;
    // the bearing's own (material 0): its balance in its frame
    double bearing_plastic_work_step = 0.0, bearing_elastic_energy = 0.0;  // [J]
  };

  class MaterialState
  {
  public:
    /// The parts the material reads (u at the quadrature points).
    struct Parts
    {
      const FeScene &scene;
      const Bodies &bodies;
      const DofSpace &dofs;
      const State &state;
      MPI_Comm comm;
    };

    /// The scene's law (make_material), its history not yet sized.
    explicit MaterialState(const Parts &parts);

    /// The law at a point: the assembler evaluates it, the fields read it; law().elastic() is
    /// the law of the static operator.
    MaterialLaw &law() { return *law_; }
    const MaterialLaw &law() const { return *law_; }

    /// The history sized for the mesh, `n_q_points` per cell, every point virgin. Throws
    /// NumericalError when the law has no history.
    void init_history(unsigned int n_q_points);
    /// Every point evaluated again at the converged u (the last assembly left its trial states
    /// at the last Newton iterate), then made its history. Throws StepFailure, nothing
    /// committed, when the law fails at a point.
    void commit();
    /// Trial → committed at every point at the converged u, with the step's energies from the
    /// committed states (collective).
    PlasticEnergies commit_with_energies();
    /// A body's strains at the axial mid-plane within ±half_angle [rad] of the contact point,
    /// which sits at the body's frame angle −turn (collective; every rank gets the sorted
    /// profile).
    std::vector<StrainProfilePoint> strain_profile(unsigned int body, double turn,
                                                   double half_angle) const;

  private:
    const FeScene &scene_;
    const Bodies &bodies_;
    const DofSpace &dofs_;
    const State &state_;
    MPI_Comm comm_;
    std::unique_ptr<MaterialLaw> law_;
    unsigned int n_q_points_ = 0;  // per cell (init_history)
  };
}  // namespace clearjoint::fe::detail
