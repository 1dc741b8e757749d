// Elastoplastic bodies (study rolling): the material law with history (material/material_law.h;
// J2 with its hardening table) at every quadrature point, inside the contact model's linear
// machinery. Each
// material Newton iteration linearises the internal force about the current displacement u_k,
//     f_int(u) ≈ f_int(u_k) + K_t (u − u_k) = K_t u − b_k,   b_k = K_t u_k − f_int(u_k),
// so the operator K_ becomes the consistent tangent K_t and b_k the known load (the slot the
// impact study uses for its dynamic load): the active-set contact solve then runs unchanged on
// the linearised problem. K_t differs from the elastic stiffness only at the quadrature points
// that yield in this step, and b_k = (K_t − K_el) u_k + Σ Bᵀ C ε_p only in cells with plastic
// strain, so the elastic matrices are assembled once and only those cells are revisited.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  void ContactModel::init_plasticity()
  {
    if (!material_->has_history())
      throw NumericalError("fe_stage: the elastoplastic assembly needs a material law with "
                           "history (make_material)");
    plastic_ = true;
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    n_q_ = quadrature.size();
    material_->resize(std::size_t(bodies_.triangulation().n_active_cells()) * n_q_);
    keep_elastic_operator();
    dynamic_load_.reinit(dofs_.owned(), comm_);
    for (const auto &line : dofs_.fixed().get_lines())
      if (line.inhomogeneity != 0.0)
        throw NumericalError("fe_stage: the elastoplastic assembly needs homogeneous supports "
                             "(a rigid journal, or a deformable one clamped in its own frame); "
                             "DoF " +
                             std::to_string(line.index) + " is prescribed");
  }

  /// The elastic operator, kept: every assembly starts from it.
  void ContactModel::keep_elastic_operator()
  {
    elastic_.K.reinit(K_);
    elastic_.K.copy_from(K_);
    elastic_.A_static.reinit(A_static_);
    elastic_.A_static.copy_from(A_static_);
    elastic_.contact_cells = contact_cell_matrices_;
  }

  /// K_ = K_t(u), the condensed static part and the contact cells' matrices the same, and the
  /// load b = K_t u − f_int(u), at the ghosted solution_. Trial states are written (the
  /// committed ones are the last converged step's).
  ContactModel::PlasticAssembly ContactModel::assemble_plastic()
  {
    ScopedTimer timer(t_assemble_);
    PlasticAssembly info;
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature,
                     update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    const unsigned int n = dofs_.fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double> u_cell(n), b_cell(n);
    FullMatrix<double> D(n, n);
    std::vector<SymmetricTensor<2, dim>> eps(n_q_), B(n);
    const SymmetricTensor<4, dim> C_el = material_->elastic_tangent();

    K_.copy_from(elastic_.K);
    A_static_.copy_from(elastic_.A_static);
    contact_cell_matrices_ = elastic_.contact_cells;
    dynamic_load_ = 0.0;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_symmetric_gradients(solution_, eps);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q_;
          bool yields = false, has_plastic_strain = false;
          std::vector<MaterialResponse> resp(n_q_);
          for (unsigned int q = 0; q < n_q_; ++q)
            {
              resp[q] = material_->evaluate(first + q, eps[q]);
              if (!resp[q].converged)
                throw StepFailure{"the return mapping did not converge at a quadrature point"};
              yields = yields || resp[q].yielding;
              has_plastic_strain =
                has_plastic_strain || material_->equivalent_plastic_strain(first + q, true) > 0.0;
              info.n_plastic_points += resp[q].yielding ? 1 : 0;
            }
          if (!yields && !has_plastic_strain)
            continue;  // elastic: its share of K_el and of b (zero) is already there
          cell->get_dof_indices(dofs);
          cell->get_dof_values(solution_, u_cell);
          D = 0.0;
          b_cell = 0.0;
          for (unsigned int q = 0; q < n_q_; ++q)
            {
              for (unsigned int i = 0; i < n; ++i)
                B[i] = fv[u].symmetric_gradient(i, q);
              const double JxW = fv.JxW(q);
              // Σ Bᵀ C_el ε_p: the plastic strain's share of K_el u − f_int
              const SymmetricTensor<2, dim> s_p = C_el * material_->plastic_strain(first + q, true);
              for (unsigned int i = 0; i < n; ++i)
                b_cell(i) += (B[i] * s_p) * JxW;
              if (!resp[q].yielding)
                continue;
              const SymmetricTensor<4, dim> dC = resp[q].tangent - C_el;
              for (unsigned int j = 0; j < n; ++j)
                {
                  const SymmetricTensor<2, dim> dCB = dC * B[j];
                  for (unsigned int i = 0; i < n; ++i)
                    D(i, j) += (B[i] * dCB) * JxW;
                }
            }
          D.vmult_add(b_cell, u_cell);  // + (K_t − K_el) u
          dynamic_load_.add(dofs, b_cell);
          if (!yields)
            continue;
          K_.add(dofs, D);
          const int k = contact_cell_of_[cell->active_cell_index()];
          if (k >= 0)
            contact_cell_matrices_[k].add(1.0, D);
          else
            dofs_.fixed().distribute_local_to_global(D, dofs, A_static_);
        }
    K_.compress(VectorOperation::add);
    A_static_.compress(VectorOperation::add);
    dynamic_load_.compress(VectorOperation::add);
    info.n_plastic_points = Utilities::MPI::sum(info.n_plastic_points, comm_);

    set_contact_load_offsets();
    return info;
  }

  /// Trial → committed at every quadrature point (after a converged step), and the step's
  /// energies from the committed states.
  ContactModel::PlasticEnergies ContactModel::commit_plasticity()
  {
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature,
                     update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(n_q_);
    PlasticEnergies e;
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_symmetric_gradients(solution_, eps);
          const std::size_t first = std::size_t(cell->active_cell_index()) * n_q_;
          double cell_plastic_volume = 0.0;
          const bool bearing = cell->material_id() == 0;
          for (unsigned int q = 0; q < n_q_; ++q)
            {
              const std::size_t point = first + q;
              const MaterialResponse r = material_->evaluate(point, eps[q]);
              e.plastic_work_step += r.plastic_work * fv.JxW(q);
              material_->commit(point);
              const double elastic = material_->elastic_energy(point, eps[q]) * fv.JxW(q);
              e.elastic_energy += elastic;
              if (bearing)
                {
                  e.bearing_plastic_work_step += r.plastic_work * fv.JxW(q);
                  e.bearing_elastic_energy += elastic;
                }
              const double alpha = material_->equivalent_plastic_strain(point);
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

  /// Per cell: the quadrature points' mean plastic strain tensor (the fields' stress is
  /// C (ε − ε̄_p)), their largest equivalent plastic strain, and the largest von Mises stress of
  /// the committed states.
  void ContactModel::plastic_cell_fields(std::vector<SymmetricTensor<2, dim>> &mean_eps_p,
                                         Vector<float> &alpha_max, Vector<float> &vm_max) const
  {
    const QGauss<dim> quadrature(dofs_.fe().degree + 1);
    FEValues<dim> fv(bodies_.mapping(), dofs_.fe(), quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(n_q_);
    mean_eps_p.assign(bodies_.triangulation().n_active_cells(), SymmetricTensor<2, dim>());
    alpha_max.reinit(bodies_.triangulation().n_active_cells());
    vm_max.reinit(bodies_.triangulation().n_active_cells());
    const LinearElastic &C = material_->elastic();
    for (const auto &cell : dofs_.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_symmetric_gradients(solution_, eps);
          const unsigned int c = cell->active_cell_index();
          const std::size_t first = std::size_t(c) * n_q_;
          for (unsigned int q = 0; q < n_q_; ++q)
            {
              const SymmetricTensor<2, dim> ep = material_->plastic_strain(first + q);
              mean_eps_p[c] += ep / double(n_q_);
              alpha_max[c] =
                std::max(alpha_max[c], float(material_->equivalent_plastic_strain(first + q)));
              vm_max[c] = std::max(vm_max[c], float(von_mises(C.stress(eps[q] - ep))));
            }
        }
  }

  /// A body's strains at the axial mid-plane within ±half_angle of the contact point, which
  /// sits at the body's frame angle −turn (the fixed-frame bottom; turn = φ for the bearing,
  /// γ for the deformable journal, angles about the body's own axis): the face quadrature
  /// points of the contact-surface faces that touch z = 0, nearest row to the plane.
  /// Collective; every rank gets the sorted profile.
  std::vector<StrainProfilePoint> ContactModel::strain_profile(const unsigned int body,
                                                               const double turn,
                                                               const double half_angle) const
  {
    const QGauss<dim - 1> fq(dofs_.fe().degree + 2);
    FEFaceValues<dim> fv(bodies_.mapping(), dofs_.fe(), fq,
                         update_gradients | update_quadrature_points);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(fq.size());
    std::vector<double> mine;
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
              fv[u].get_function_symmetric_gradients(solution_, eps);
              double z_row = std::numeric_limits<double>::max();
              for (const unsigned int q : fv.quadrature_point_indices())
                z_row = std::min(z_row, std::abs(fv.quadrature_point(q)[2]));
              const std::size_t first = std::size_t(cell->active_cell_index()) * n_q_;
              double alpha = 0.0;
              SymmetricTensor<2, dim> mean_eps_p;
              for (unsigned int q = 0; q < n_q_; ++q)
                {
                  alpha = std::max(alpha, material_->equivalent_plastic_strain(first + q));
                  mean_eps_p += material_->plastic_strain(first + q) / double(n_q_);
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
                              {a, er * (eps[q] * er), et * (eps[q] * et), eps[q][2][2], alpha,
                               von_mises(material_->elastic().stress(eps[q] - mean_eps_p))});
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
}  // namespace clearjoint::fe::detail
