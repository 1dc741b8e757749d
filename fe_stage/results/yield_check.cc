// The yield check: von Mises of the linear-elastic stress against the scene's yield stress at
// every quadrature point — per body the volume above yield and the largest stress with its
// place, and per cell the volume fraction above yield (the plastic_zone field). The model stays
// elastic; this tells the user where that is no longer true.
#include "fe_stage/results/field_output.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <array>

namespace clearjoint::fe::detail
{
  YieldCheck FieldOutput::check_yield(Vector<float> *cell_fraction_above) const
  {
    const QGauss<dim> quadrature(parts_.dofs.fe().degree + 1);
    FEValues<dim> fv(parts_.bodies.mapping(), parts_.dofs.fe(), quadrature,
                     update_gradients | update_JxW_values | update_quadrature_points);
    const FEValuesExtractors::Vector u(0);
    std::vector<SymmetricTensor<2, dim>> eps(quadrature.size());
    const double yield = parts_.scene.material.yield_stress;
    // bodies by material id: 0 the bearing (or the verification block), 1 the journal (or
    // the indenter)
    constexpr unsigned int n_bodies = 2;
    std::array<double, n_bodies> volume{}, above{}, max_vm{};
    std::array<Point<dim>, n_bodies> where;
    for (const auto &cell : parts_.dofs.handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[u].get_function_symmetric_gradients(parts_.state.u(), eps);
          const unsigned int b = cell->material_id() == 1 ? 1 : 0;
          double cell_volume = 0.0, cell_above = 0.0;
          for (const unsigned int q : fv.quadrature_point_indices())
            {
              const double vm = von_mises(parts_.material.elastic().stress(eps[q]));
              cell_volume += fv.JxW(q);
              if (vm > yield)
                cell_above += fv.JxW(q);
              if (vm > max_vm[b])
                {
                  max_vm[b] = vm;
                  where[b] = fv.quadrature_point(q);
                }
            }
          volume[b] += cell_volume;
          above[b] += cell_above;
          if (cell_fraction_above)
            (*cell_fraction_above)[cell->active_cell_index()] =
              static_cast<float>(cell_above / cell_volume);
        }

    YieldCheck check;
    check.yield_stress = yield;
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const double v = Utilities::MPI::sum(volume[b], parts_.comm);
        // the largest stress and its place: every rank's candidate, the first largest wins
        std::vector<double> mine = {max_vm[b], where[b][0], where[b][1], where[b][2]};
        const auto all = Utilities::MPI::all_gather(parts_.comm, mine);
        if (v <= 0.0)
          continue;  // no such body (a rigid journal or indenter)
        YieldCheck::Body body;
        body.name = parts_.plan.body_names[b];
        body.volume = parts_.bodies.symmetry_factor() * v;
        body.volume_above_yield =
          parts_.bodies.symmetry_factor() * Utilities::MPI::sum(above[b], parts_.comm);
        for (const auto &r : all)
          if (r[0] > body.max_von_mises)
            {
              body.max_von_mises = r[0];
              body.max_location = {r[1], r[2], r[3]};
            }
        check.bodies.push_back(body);
      }
    return check;
  }

  void FieldOutput::log_yield_check(const YieldCheck &check) const
  {
    if (rank_ != 0)
      return;
    for (const auto &b : check.bodies)
      {
        const auto &x = b.max_location;
        const std::string where = "(" + format_value(x[0] * 1e3) + ", " + format_value(x[1] * 1e3) +
                                  ", " + format_value(x[2] * 1e3) + ") mm";
        if (b.volume_above_yield > 0.0)
          log::warning(
            "fe_stage: yield check: von Mises reaches " + format_value(b.max_von_mises * 1e-6) +
            " MPa in the " + b.name + " at " + where + ", above the yield stress " +
            format_value(check.yield_stress * 1e-6) + " MPa in " +
            format_value(b.volume_above_yield * 1e9) + " mm^3 (" +
            format_value(100.0 * b.volume_above_yield / b.volume) + " % of the " + b.name +
            "): the linear-elastic result is not valid there "
            "(field plastic_zone; material.yield_stress sets the limit)");
        else
          log::info("fe_stage: yield check: von Mises at most " +
                    format_value(b.max_von_mises * 1e-6) + " MPa in the " + b.name + " (at " +
                    where + "), below the yield stress " + format_value(check.yield_stress * 1e-6) +
                    " MPa");
      }
  }
}  // namespace clearjoint::fe::detail
