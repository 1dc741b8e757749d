// VTU/PVTU/PVD fields for ParaView (results/field_output.h): displacement, stress, strain, von
// Mises, principal strains, plastic_zone (the yield check) or the plastic history's fields,
// contact pressure/gap/status/shear/slip as Abaqus's CPRESS/COPEN/CSTATUS/CSHEAR/CSLIP,
// subdomain.
#include "fe_stage/results/field_output.h"

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/material/strain_measure.h"
#include "fe_stage/results/vtu_files.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <algorithm>
#include <filesystem>

namespace clearjoint::fe::detail
{
  /// Stress, strain, von Mises stress and principal strains from the displacement gradient.
  /// The strain is the material law's (material/strain_measure.h): ε = sym ∇u, or with finite
  /// kinematics the Hencky strain E = ½ ln C, whose stress C (E − ε̄_p) is the rotated
  /// Kirchhoff stress of the J2 law in the logarithmic strain space.
  class StressPostprocessor : public DataPostprocessor<dim>
  {
  public:
    /// mean_eps_p (elastoplastic, by active cell index): the stress is C (ε − ε̄_p), ε̄_p the
    /// cell's mean plastic strain over its quadrature points; nullptr: elastic, C ε.
    StressPostprocessor(const LinearElastic &material, const bool finite,
                        const std::vector<SymmetricTensor<2, dim>> *mean_eps_p = nullptr)
      : material_(material)
      , finite_(finite)
      , mean_eps_p_(mean_eps_p)
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
          SymmetricTensor<2, dim> elastic = eps;
          if (mean_eps_p_)
            elastic -= (*mean_eps_p_)[in.template get_cell<dim>()->active_cell_index()];
          const SymmetricTensor<2, dim> sig = material_.stress(elastic);
          unsigned int k = 0;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              out[q][k++] = sig[i][j];
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              out[q][k++] = eps[i][j];
          out[q][k++] = von_mises(sig);
          const auto ev = eigenvalues(eps);  // descending
          for (unsigned int i = 0; i < dim; ++i)
            out[q][k++] = ev[i];
        }
    }

    std::vector<std::string> get_names() const override
    {
      std::vector<std::string> names(9, "stress");
      names.resize(18, "strain");
      names.push_back("von_mises_stress");
      names.push_back("principal_strain_1");
      names.push_back("principal_strain_2");
      names.push_back("principal_strain_3");
      return names;
    }

    std::vector<DataComponentInterpretation::DataComponentInterpretation>
    get_data_component_interpretation() const override
    {
      std::vector<DataComponentInterpretation::DataComponentInterpretation> v(
        18, DataComponentInterpretation::component_is_part_of_tensor);
      v.resize(22, DataComponentInterpretation::component_is_scalar);
      return v;
    }

    UpdateFlags get_needed_update_flags() const override { return update_gradients; }

  private:
    LinearElastic material_;
    bool finite_;
    const std::vector<SymmetricTensor<2, dim>> *mean_eps_p_;
  };

  /// Per cell: the quadrature points' mean plastic strain tensor (the fields' stress is
  /// C (ε − ε̄_p)), their largest equivalent plastic strain, and the largest von Mises stress of
  /// the committed states.
  void FieldOutput::plastic_cell_fields(std::vector<SymmetricTensor<2, dim>> &mean_eps_p,
                                        Vector<float> &alpha_max, Vector<float> &vm_max) const
  {
    const QGauss<dim> quadrature(parts_.dofs.fe().degree + 1);
    FEValues<dim> fv(parts_.bodies.mapping(), parts_.dofs.fe(), quadrature, update_gradients);
    const unsigned int n_q = quadrature.size();
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<SymmetricTensor<2, dim>> eps(n_q);
    const bool finite = parts_.scene.material.kinematics == Material::Kinematics::finite;
    mean_eps_p.assign(parts_.bodies.triangulation().n_active_cells(), SymmetricTensor<2, dim>());
    alpha_max.reinit(parts_.bodies.triangulation().n_active_cells());
    vm_max.reinit(parts_.bodies.triangulation().n_active_cells());
    const LinearElastic &C = parts_.material.elastic();
    for (const auto &cell : parts_.dofs.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_gradients(parts_.state.u(), grad_u);
          for (unsigned int q = 0; q < n_q; ++q)
            eps[q] = strain_measure(grad_u[q], finite);
          const unsigned int c = cell->active_cell_index();
          const std::size_t first = std::size_t(c) * n_q;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const SymmetricTensor<2, dim> ep = parts_.material.plastic_strain(first + q);
              mean_eps_p[c] += ep / double(n_q);
              alpha_max[c] =
                std::max(alpha_max[c], float(parts_.material.equivalent_plastic_strain(first + q)));
              vm_max[c] = std::max(vm_max[c], float(von_mises(C.stress(eps[q] - ep))));
            }
        }
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
    // zone; else the yield check's
    const bool plastic = parts_.material.has_history();
    std::vector<SymmetricTensor<2, dim>> mean_eps_p;
    Vector<float> alpha_max, vm_max;
    if (plastic)
      plastic_cell_fields(mean_eps_p, alpha_max, vm_max);
    StressPostprocessor post(parts_.material.elastic(),
                             parts_.scene.material.kinematics == Material::Kinematics::finite,
                             plastic ? &mean_eps_p : nullptr);
    DataOut<dim> out;
    out.attach_dof_handler(dofs.handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
      dim, DataComponentInterpretation::component_is_part_of_vector);
    out.add_data_vector(parts_.state.u(), std::vector<std::string>(dim, "displacement"),
                        DataOut<dim>::type_dof_data, vec);
    out.add_data_vector(parts_.state.u(), post);
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
