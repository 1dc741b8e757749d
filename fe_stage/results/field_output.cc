// VTU/PVTU/PVD fields for ParaView (results/field_output.h): displacement, stress, strain, von
// Mises, principal strains, plastic_zone (the yield check) or the plastic history's fields (the
// stress then the material points' own, on the cells' output points:
// results/material_point_field.h),
// contact pressure/gap/status/shear/slip as Abaqus's CPRESS/COPEN/CSTATUS/CSHEAR/CSLIP,
// subdomain.
#include "fe_stage/results/field_output.h"

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/material/strain_measure.h"
#include "fe_stage/results/material_point_field.h"
#include "fe_stage/results/vtu_files.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <algorithm>
#include <array>
#include <filesystem>

namespace clearjoint::fe::detail
{
  /// Strain and principal strains from the displacement gradient, and — for an elastic body —
  /// the stress and its von Mises value. The strain is the material law's
  /// (material/strain_measure.h): ε = sym ∇u, or with finite kinematics the Hencky strain
  /// E = ½ ln C, whose stress C E is the rotated Kirchhoff stress in the logarithmic strain
  /// space. A body with a plastic history takes its stress from the material points instead
  /// (PointStressPostprocessor): the displacement alone does not know the plastic strain.
  class StrainPostprocessor : public DataPostprocessor<dim>
  {
  public:
    StrainPostprocessor(const LinearElastic &material, const bool finite, const bool with_stress)
      : material_(material)
      , finite_(finite)
      , with_stress_(with_stress)
    {}

    void evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &in,
                               std::vector<Vector<double>> &out) const override
    {
      for (unsigned int q = 0; q < in.solution_gradients.size(); ++q)
        {
          Tensor<2, dim> grad;
          for (unsigned int i = 0; i < dim; ++i)
            grad[i] = in.solution_gradients[q][i];
          const SymmetricTensor<2, dim> eps = strain_measure(grad, finite_);
          const SymmetricTensor<2, dim> sig =
            with_stress_ ? material_.stress(eps) : SymmetricTensor<2, dim>();
          unsigned int k = 0;
          if (with_stress_)
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                out[q][k++] = sig[i][j];
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              out[q][k++] = eps[i][j];
          if (with_stress_)
            out[q][k++] = von_mises(sig);
          const auto ev = eigenvalues(eps);  // descending
          for (unsigned int i = 0; i < dim; ++i)
            out[q][k++] = ev[i];
        }
    }

    std::vector<std::string> get_names() const override
    {
      std::vector<std::string> names;
      if (with_stress_)
        names.resize(9, "stress");
      names.resize(names.size() + 9, "strain");
      if (with_stress_)
        names.push_back("von_mises_stress");
      names.push_back("principal_strain_1");
      names.push_back("principal_strain_2");
      names.push_back("principal_strain_3");
      return names;
    }

    std::vector<DataComponentInterpretation::DataComponentInterpretation>
    get_data_component_interpretation() const override
    {
      const unsigned int tensors = with_stress_ ? 18 : 9;
      std::vector<DataComponentInterpretation::DataComponentInterpretation> v(
        tensors, DataComponentInterpretation::component_is_part_of_tensor);
      v.resize(tensors + (with_stress_ ? 4 : 3), DataComponentInterpretation::component_is_scalar);
      return v;
    }

    UpdateFlags get_needed_update_flags() const override { return update_gradients; }

  private:
    LinearElastic material_;
    bool finite_;
    bool with_stress_;
  };

  /// The six independent stress components, in this order, of the material-point stress field.
  constexpr std::array<std::pair<unsigned int, unsigned int>, 6> stress_components{
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};

  /// `stress` and `von_mises_stress` from the material points' stress field
  /// (results/material_point_field.h): at each output point the nearest material point's own
  /// stress, with its own plastic strain, and its von Mises value.
  class PointStressPostprocessor : public DataPostprocessor<dim>
  {
  public:
    void evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &in,
                               std::vector<Vector<double>> &out) const override
    {
      for (unsigned int q = 0; q < in.solution_values.size(); ++q)
        {
          SymmetricTensor<2, dim> sig;
          for (unsigned int k = 0; k < stress_components.size(); ++k)
            sig[stress_components[k].first][stress_components[k].second] = in.solution_values[q][k];
          unsigned int k = 0;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              out[q][k++] = sig[i][j];
          out[q][k++] = von_mises(sig);
        }
    }

    std::vector<std::string> get_names() const override
    {
      std::vector<std::string> names(9, "stress");
      names.push_back("von_mises_stress");
      return names;
    }

    std::vector<DataComponentInterpretation::DataComponentInterpretation>
    get_data_component_interpretation() const override
    {
      std::vector<DataComponentInterpretation::DataComponentInterpretation> v(
        9, DataComponentInterpretation::component_is_part_of_tensor);
      v.push_back(DataComponentInterpretation::component_is_scalar);
      return v;
    }

    UpdateFlags get_needed_update_flags() const override { return update_values; }
  };

  /// The material points' stresses C (ε − ε_p), each with its own plastic strain, on the cells'
  /// output points (the `stress` field of `stress_dofs`: six components, stress_components'
  /// order);
  /// per cell, the points' largest equivalent plastic strain and largest von Mises stress.
  void FieldOutput::plastic_cell_fields(const DoFHandler<dim> &stress_dofs,
                                        const MaterialPointField &point_field,
                                        TrilinosWrappers::MPI::Vector &stress,
                                        Vector<float> &alpha_max, Vector<float> &vm_max) const
  {
    const Quadrature<dim> &quadrature = point_field.points();
    FEValues<dim> fv(parts_.bodies.mapping(), parts_.dofs.fe(), quadrature, update_gradients);
    const unsigned int n_q = quadrature.size();
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<SymmetricTensor<2, dim>> sig(n_q);
    const bool finite = parts_.scene.material.kinematics == Material::Kinematics::finite;
    alpha_max.reinit(parts_.bodies.triangulation().n_active_cells());
    vm_max.reinit(parts_.bodies.triangulation().n_active_cells());
    const LinearElastic &C = parts_.material.elastic();
    const FiniteElement<dim> &stress_fe = stress_dofs.get_fe();
    std::vector<types::global_dof_index> stress_dof_indices(stress_fe.n_dofs_per_cell());
    Vector<double> at_points(n_q);
    std::array<Vector<double>, stress_components.size()> coefficients;
    for (const auto &cell : parts_.dofs.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(parts_.state.u(), grad_u);
          const unsigned int c = cell->active_cell_index();
          const std::size_t first = std::size_t(c) * n_q;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const SymmetricTensor<2, dim> eps = strain_measure(grad_u[q], finite);
              sig[q] = C.stress(eps - parts_.material.plastic_strain(first + q));
              alpha_max[c] =
                std::max(alpha_max[c], float(parts_.material.equivalent_plastic_strain(first + q)));
              vm_max[c] = std::max(vm_max[c], float(von_mises(sig[q])));
            }
          for (unsigned int k = 0; k < stress_components.size(); ++k)
            {
              for (unsigned int q = 0; q < n_q; ++q)
                at_points[q] = sig[q][stress_components[k].first][stress_components[k].second];
              point_field.place(at_points, coefficients[k]);
            }
          // the same cell of the stress field's DoFHandler (same triangulation)
          const typename DoFHandler<dim>::active_cell_iterator stress_cell(
            &parts_.bodies.triangulation(), cell->level(), cell->index(), &stress_dofs);
          stress_cell->get_dof_indices(stress_dof_indices);
          for (unsigned int i = 0; i < stress_fe.n_dofs_per_cell(); ++i)
            {
              const auto [component, base] = stress_fe.system_to_component_index(i);
              stress[stress_dof_indices[i]] = coefficients[component][base];
            }
        }
    stress.compress(VectorOperation::insert);
  }

  FieldOutput::FieldOutput(const Parts &parts, const std::string &output_dir,
                           const bool write_fields)
    : parts_(parts)
    , dir_(output_dir + "/fields")
    , enabled_(write_fields && !output_dir.empty())
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
  {}

  void FieldOutput::create_directory() const
  {
    if (enabled_ && rank_ == 0)
      std::filesystem::create_directories(dir_);
  }

  std::vector<std::string> FieldOutput::files(const bool with_pvd) const
  {
    std::vector<std::string> f = files_;
    if (rank_ == 0 && enabled_ && with_pvd)
      f.push_back(dir_ + "/solution.pvd");
    return f;
  }

  void FieldOutput::write(const unsigned int counter, const double t)
  {
    const auto &dofs = parts_.dofs;
    const auto &contact = parts_.contact;
    const auto &tria = parts_.bodies.triangulation();
    const MPI_Comm comm = parts_.comm;
    // contact fields at the nodes, in the x/y/z slots of a system vector
    TrilinosWrappers::MPI::Vector cf_owned(dofs.owned(), comm), ff_owned(dofs.owned(), comm);
    for (const auto &cn : contact.nodes())
      if (cn.owned)
        {
          cf_owned[cn.dofs[0]] = cn.active && cn.weight > 0.0 ? cn.lambda / cn.weight : 0.0;
          cf_owned[cn.dofs[1]] = cn.gap;
          cf_owned[cn.dofs[2]] = cn.active ? 1.0 : 0.0;
          // As Abaqus's CSTATUS, CSHEAR, CSLIP: status 0 open, 1 slip, 2 stick (frictionless
          // contact slides freely: slip); shear = the friction traction |t_T|/w, zero without
          // friction and off contact; slip = the tangential displacement against the other
          // body since the start, where in contact.
          const double shear = tangential(contact.traction(cn), cn.n).norm();
          ff_owned[cn.dofs[0]] = !cn.active ? 0.0 : (contact.friction() && cn.stick ? 2.0 : 1.0);
          ff_owned[cn.dofs[1]] =
            contact.friction() && cn.active && cn.weight > 0.0 ? shear / cn.weight : 0.0;
          ff_owned[cn.dofs[2]] = cn.active ? tangential(cn.relative, cn.n).norm() : 0.0;
        }
    cf_owned.compress(VectorOperation::insert);
    ff_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector cf(dofs.owned(), dofs.relevant(), comm),
      ff(dofs.owned(), dofs.relevant(), comm);
    cf = cf_owned;
    ff = ff_owned;

    // the law's history (the rolling study, the elastoplastic patch test): its own plastic
    // zone, and the stress of its material points; else the yield check's, and the stress from
    // the displacement
    const bool plastic = parts_.material.has_history();
    const MaterialPointField point_field(dofs.fe().degree);
    DoFHandler<dim> stress_dofs(tria);
    TrilinosWrappers::MPI::Vector stress;
    Vector<float> alpha_max, vm_max;
    if (plastic)
      {
        stress_dofs.distribute_dofs(FESystem<dim>(point_field.fe(), stress_components.size()));
        IndexSet relevant;
        DoFTools::extract_locally_relevant_dofs(stress_dofs, relevant);
        TrilinosWrappers::MPI::Vector stress_owned(stress_dofs.locally_owned_dofs(), comm);
        plastic_cell_fields(stress_dofs, point_field, stress_owned, alpha_max, vm_max);
        stress.reinit(stress_dofs.locally_owned_dofs(), relevant, comm);
        stress = stress_owned;
      }
    StrainPostprocessor strains(parts_.material.elastic(),
                                parts_.scene.material.kinematics == Material::Kinematics::finite,
                                !plastic);
    PointStressPostprocessor point_stress;
    DataOut<dim> out;
    out.attach_dof_handler(dofs.handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
      dim, DataComponentInterpretation::component_is_part_of_vector);
    out.add_data_vector(parts_.state.u(), std::vector<std::string>(dim, "displacement"),
                        DataOut<dim>::type_dof_data, vec);
    out.add_data_vector(parts_.state.u(), strains);
    if (plastic)
      out.add_data_vector(stress_dofs, stress, point_stress);
    std::vector<DataComponentInterpretation::DataComponentInterpretation> sc(
      dim, DataComponentInterpretation::component_is_scalar);
    out.add_data_vector(cf,
                        std::vector<std::string>{"contact_pressure", "contact_gap",
                                                 "contact_active"},
                        DataOut<dim>::type_dof_data, sc);
    out.add_data_vector(ff,
                        std::vector<std::string>{"contact_status", "contact_shear", "contact_slip"},
                        DataOut<dim>::type_dof_data, sc);
    Vector<float> subdomain(tria.n_active_cells());
    for (auto &s : subdomain)
      s = static_cast<float>(tria.locally_owned_subdomain());
    out.add_data_vector(subdomain, "subdomain");
    Vector<float> plastic_zone(tria.n_active_cells());  // volume fraction above yield
    if (plastic)
      {
        // the elastoplastic model's own plastic zone: its equivalent plastic strain
        out.add_data_vector(alpha_max, "equivalent_plastic_strain");
        out.add_data_vector(vm_max, "von_mises_stress_max");
      }
    else
      {
        check_yield(&plastic_zone);
        out.add_data_vector(plastic_zone, "plastic_zone");
      }
    out.build_patches(parts_.bodies.mapping(), dofs.fe().degree, DataOut<dim>::curved_inner_cells);
    // A full disk: WriteError naming the file and the reason, on every rank (vtu_files.h).
    const std::string pvtu = write_vtu_pieces(out, dir_, counter, comm);
    if (rank_ == 0)
      {
        pvd_records_.emplace_back(t, pvtu);
        files_.push_back(dir_ + "/" + pvtu);
      }
    write_pvd(dir_, pvd_records_, comm);
  }
}  // namespace clearjoint::fe::detail
