// VTU/PVTU/PVD fields for ParaView: displacement, stress, strain, von Mises, principal strains,
// plastic_zone (the yield check), contact pressure/gap/status/shear/slip as Abaqus's
// CPRESS/COPEN/CSTATUS/CSHEAR/CSLIP, subdomain.
#include "fe_stage/contact_model.h"
#include "fe_stage/material/strain_measure.h"
#include "fe_stage/results/vtu_files.h"

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

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

  void ContactModel::write_fields(const unsigned int counter, const double delta)
  {
    const std::string dir = options_.output_dir + "/fields";
    // contact fields at the nodes, in the x/y/z slots of a system vector
    TrilinosWrappers::MPI::Vector cf_owned(dofs_.owned(), comm_), ff_owned(dofs_.owned(), comm_);
    for (const auto &cn : contact_.nodes())
      if (cn.owned)
        {
          cf_owned[cn.dofs[0]] = cn.active && cn.weight > 0.0 ? cn.lambda / cn.weight : 0.0;
          cf_owned[cn.dofs[1]] = cn.gap;
          cf_owned[cn.dofs[2]] = cn.active ? 1.0 : 0.0;
          // As Abaqus's CSTATUS, CSHEAR, CSLIP: status 0 open, 1 slip, 2 stick (frictionless
          // contact slides freely: slip); shear = the friction traction |t_T|/w, zero without
          // friction and off contact; slip = the tangential displacement against the other
          // body since the start, where in contact.
          const double shear = tangential(contact_.traction(cn), cn.n).norm();
          ff_owned[cn.dofs[0]] = !cn.active ? 0.0 : (contact_.friction() && cn.stick ? 2.0 : 1.0);
          ff_owned[cn.dofs[1]] =
            contact_.friction() && cn.active && cn.weight > 0.0 ? shear / cn.weight : 0.0;
          ff_owned[cn.dofs[2]] = cn.active ? tangential(cn.relative, cn.n).norm() : 0.0;
        }
    cf_owned.compress(VectorOperation::insert);
    ff_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector cf(dofs_.owned(), dofs_.relevant(), comm_),
      ff(dofs_.owned(), dofs_.relevant(), comm_);
    cf = cf_owned;
    ff = ff_owned;

    std::vector<SymmetricTensor<2, dim>> mean_eps_p;
    Vector<float> alpha_max, vm_max;
    if (elastoplastic())
      plastic_cell_fields(mean_eps_p, alpha_max, vm_max);
    StressPostprocessor post(material_->elastic(),
                             scene_.material.kinematics == Material::Kinematics::finite,
                             elastoplastic() ? &mean_eps_p : nullptr);
    DataOut<dim> out;
    out.attach_dof_handler(dofs_.handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
      dim, DataComponentInterpretation::component_is_part_of_vector);
    out.add_data_vector(state_.u(), std::vector<std::string>(dim, "displacement"),
                        DataOut<dim>::type_dof_data, vec);
    out.add_data_vector(state_.u(), post);
    std::vector<DataComponentInterpretation::DataComponentInterpretation> sc(
      dim, DataComponentInterpretation::component_is_scalar);
    out.add_data_vector(cf,
                        std::vector<std::string>{"contact_pressure", "contact_gap",
                                                 "contact_active"},
                        DataOut<dim>::type_dof_data, sc);
    out.add_data_vector(ff,
                        std::vector<std::string>{"contact_status", "contact_shear", "contact_slip"},
                        DataOut<dim>::type_dof_data, sc);
    Vector<float> subdomain(bodies_.triangulation().n_active_cells());
    for (auto &s : subdomain)
      s = static_cast<float>(bodies_.triangulation().locally_owned_subdomain());
    out.add_data_vector(subdomain, "subdomain");
    Vector<float> plastic_zone(
      bodies_.triangulation().n_active_cells());  // volume fraction above yield
    if (elastoplastic())
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
    out.build_patches(bodies_.mapping(), dofs_.fe().degree, DataOut<dim>::curved_inner_cells);
    // A full disk: WriteError naming the file and the reason, on every rank (vtu_files.h).
    const std::string pvtu = write_vtu_pieces(out, dir, counter, comm_);
    if (rank_ == 0)
      {
        pvd_records_.emplace_back(delta, pvtu);
        field_files_.push_back(dir + "/" + pvtu);
      }
    write_pvd(dir, pvd_records_, comm_);
  }
}  // namespace clearjoint::fe::detail
