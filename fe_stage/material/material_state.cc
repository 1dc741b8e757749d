// MaterialState (material/material_state.h): the bodies' law with its quadrature-point history
// on the mesh — sizing it, committing a converged state (with the step's energies: the rolling
// study's balance), and the strain profile at the contact's mid-plane.
#include "fe_stage/material/material_state.h"

#include "fe_stage/core/step_failure.h"
#include "fe_stage/material/strain_measure.h"
#include "fe_stage/mesh/boundary_ids.h"

#include "common/error.h"
#include "common/units.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/fe_values_extractors.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace clearjoint::fe::detail
{
  MaterialState::MaterialState(const Parts &parts)
    : scene_(parts.scene)
    , bodies_(parts.bodies)
    , dofs_(parts.dofs)
    , state_(parts.state)
    , comm_(parts.comm)
    , law_(make_material(parts.scene, parts.scene.material.model == Material::Model::elastoplastic))
  {}

  void MaterialState::init_history(const unsigned int n_q_points)
  {
    if (!law_->has_history())
      throw NumericalError("fe_stage: the elastoplastic assembly needs a material law with "
                           "history (make_material)");
    n_q_points_ = n_q_points;
    law_->resize(std::size_t(bodies_.triangulation().n_active_cells()) * n_q_points);
  }

  /// Trial → committed at every quadrature point (after a converged step), and the step's
  /// energies from the committed states.
  PlasticEnergies MaterialState::commit_with_energies()
  {
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    const unsigned int n_q = quadrature.size();
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature,
                     update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<SymmetricTensor<2, dim>> eps(n_q);
    const bool finite = scene_.material.kinematics == Material::Kinematics::finite;
    PlasticEnergies e;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(state_.u(), grad_u);
          for (unsigned int q = 0; q < n_q; ++q)
            eps[q] = strain_measure(grad_u[q], finite);  // the Hencky strain if finite
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
          double cell_plastic_volume = 0.0;
          const bool bearing = cell->material_id() == 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const std::size_t point = first + q;
              // the trial state at the converged u (the same return map as the assembly's)
              const double plastic_work = finite ?
                                            law_->evaluate_finite(point, grad_u[q]).plastic_work :
                                            law_->evaluate(point, eps[q]).plastic_work;
              e.plastic_work_step += plastic_work * fv.JxW(q);
              law_->commit(point);
              const double elastic = law_->elastic_energy(point, eps[q]) * fv.JxW(q);
              e.elastic_energy += elastic;
              if (bearing)
                {
                  e.bearing_plastic_work_step += plastic_work * fv.JxW(q);
                  e.bearing_elastic_energy += elastic;
                }
              const double alpha = law_->equivalent_plastic_strain(point);
              e.max_plastic_strain = std::max(e.max_plastic_strain, alpha);
              if (alpha > 0.0)
                cell_plastic_volume += fv.JxW(q);
              const auto ev = eigenvalues(eps[q]);
              e.max_strain = std::max({e.max_strain, std::abs(ev[0]), std::abs(ev[2])});
            }
          e.plastic_volume += cell_plastic_volume;
        }
    e.plastic_work_step =
      bodies_.symmetry_factor() * Utilities::MPI::sum(e.plastic_work_step, comm_);
    e.elastic_energy = bodies_.symmetry_factor() * Utilities::MPI::sum(e.elastic_energy, comm_);
    e.bearing_plastic_work_step =
      bodies_.symmetry_factor() * Utilities::MPI::sum(e.bearing_plastic_work_step, comm_);
    e.bearing_elastic_energy =
      bodies_.symmetry_factor() * Utilities::MPI::sum(e.bearing_elastic_energy, comm_);
    e.plastic_volume = bodies_.symmetry_factor() * Utilities::MPI::sum(e.plastic_volume, comm_);
    e.max_plastic_strain = Utilities::MPI::max(e.max_plastic_strain, comm_);
    e.max_strain = Utilities::MPI::max(e.max_strain, comm_);
    return e;
  }

  /// A body's strains at the axial mid-plane within ±half_angle of the contact point, which
  /// sits at the body's frame angle −turn (the fixed-frame bottom; turn = φ for the bearing,
  /// γ for the deformable journal, angles about the body's own axis): the face quadrature
  /// points of the contact-surface faces that touch z = 0, nearest row to the plane.
  /// Collective; every rank gets the sorted profile.
  std::vector<StrainProfilePoint> MaterialState::strain_profile(const unsigned int body,
                                                                const double turn,
                                                                const double half_angle) const
  {
    const QGauss<dim - 1> fq(dofs_.fe().degree + 2);
    FEFaceValues<dim> fv(bodies_.mapping(), dofs_.fe(), fq,
                         update_gradients | update_quadrature_points);
    // the cell's material points (their own plastic strains: the stress is C (ε − ε_p) there)
    const QGauss<dim> cell_quadrature(dofs_.fe().degree + 1);
    FEValues<dim> cv(bodies_.mapping(), dofs_.fe(), cell_quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(fq.size()), grad_u_cell(cell_quadrature.size());
    std::vector<SymmetricTensor<2, dim>> eps(fq.size());
    const bool finite = scene_.material.kinematics == Material::Kinematics::finite;
    std::vector<double> mine;
    const unsigned int n_q = n_q_points_;  // the material points of a cell
    const double R = body == 0 ? scene_.geometry.R_B : scene_.geometry.R_J();
    const double axis_y = body == 0 ? 0.0 : -scene_.geometry.c_r;  // the body's axis (x = 0)
    const types::boundary_id surface = body == 0 ? bid_contact : bid_journal_surface;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == body)
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == surface)
            {
              double z_min = std::numeric_limits<double>::max();
              for (const auto v : cell->face(f)->vertex_indices())
                z_min = std::min(z_min, std::abs(cell->face(f)->vertex(v)[2]));
              if (z_min > 1e-9 * R)
                continue;  // not at the mid-plane
              fv.reinit(cell, f);
              fv[u].get_function_gradients(state_.u(), grad_u);
              for (const unsigned int q : fv.quadrature_point_indices())
                eps[q] = strain_measure(grad_u[q], finite);
              double z_row = std::numeric_limits<double>::max();
              for (const unsigned int q : fv.quadrature_point_indices())
                z_row = std::min(z_row, std::abs(fv.quadrature_point(q)[2]));
              // the cell's largest equivalent plastic strain and von Mises stress over its
              // material points. (A stress from the sample point's strain and the cell's mean
              // plastic strain, as this column was until 2026-11-29, mixes points whose plastic
              // strains differ by ~0.1 in the rolling study's coarse cells: 4–20 GPa.)
              const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
              cv.reinit(cell);
              cv[u].get_function_gradients(state_.u(), grad_u_cell);
              double alpha = 0.0, vm = 0.0;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  alpha = std::max(alpha, law_->equivalent_plastic_strain(first + q));
                  vm = std::max(vm, von_mises(law_->elastic().stress(
                                      strain_measure(grad_u_cell[q], finite) -
                                      law_->plastic_strain(first + q))));
                }
              for (const unsigned int q : fv.quadrature_point_indices())
                {
                  Point<dim> p = fv.quadrature_point(q);
                  if (std::abs(p[2]) > z_row + 1e-12 * R)
                    continue;
                  p[1] -= axis_y;
                  double a = std::atan2(p[0], -p[1]) + turn;  // from the contact point
                  a = std::remainder(a, 2.0 * units::pi);
                  if (std::abs(a) > half_angle)
                    continue;
                  const double r = std::hypot(p[0], p[1]);
                  const Tensor<1, dim> er({p[0] / r, p[1] / r, 0.0});
                  const Tensor<1, dim> et({-p[1] / r, p[0] / r, 0.0});
                  mine.insert(mine.end(),
                              {a, er * (eps[q] * er), et * (eps[q] * et), eps[q][2][2], alpha, vm});
                }
            }
    std::vector<StrainProfilePoint> profile;
    for (const auto &part : Utilities::MPI::all_gather(comm_, mine))
      for (std::size_t i = 0; i + 6 <= part.size(); i += 6)
        {
          StrainProfilePoint s;
          s.angle = part[i];
          s.arc = R * part[i];
          s.strain_radial = part[i + 1];
          s.strain_tangential = part[i + 2];
          s.strain_axial = part[i + 3];
          s.plastic_strain = part[i + 4];
          s.von_mises = part[i + 5];
          s.body = body;
          profile.push_back(s);
        }
    std::sort(profile.begin(), profile.end(),
              [](const auto &a, const auto &b) { return a.angle < b.angle; });
    return profile;
  }

  /// The last assembly left trial states at the last Newton iterate, not at the converged
  /// displacement: evaluate every point there again, then make it the point's history.
  void MaterialState::commit()
  {
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    const unsigned int n_q = quadrature.size();
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    const bool finite = scene_.material.kinematics == Material::Kinematics::finite;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(state_.u(), grad_u);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const bool converged = finite ?
                                       law_->evaluate_finite(first + q, grad_u[q]).converged :
                                       law_->evaluate(first + q, symmetrize(grad_u[q])).converged;
              if (!converged)  // (nothing committed yet: the step can still be cut)
                throw StepFailure{"the material law failed at a quadrature point of the "
                                  "converged state"};
            }
        }
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int q = 0; q < n_q; ++q)
          law_->commit(std::size_t(cell->active_cell_index()) * n_q + q);
  }
}  // namespace clearjoint::fe::detail
