// The local projection of material-point values onto the cell's polynomials
// (results/point_projection.h).
#include "fe_stage/results/point_projection.h"

#include <deal.II/fe/fe_tools.h>

namespace clearjoint::fe::detail
{
  PointProjection::PointProjection(const unsigned int degree)
    : fe_(degree)
    , points_(degree + 1)
  {
    matrix_.reinit(fe_.n_dofs_per_cell(), points_.size());
    dealii::FETools::compute_projection_from_quadrature_points_matrix(fe_, points_, points_,
                                                                      matrix_);
  }

  void PointProjection::project(const dealii::Vector<double> &at_points,
                                dealii::Vector<double> &coefficients) const
  {
    coefficients.reinit(fe_.n_dofs_per_cell());
    matrix_.vmult(coefficients, at_points);
  }
}  // namespace clearjoint::fe::detail
