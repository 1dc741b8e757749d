// Material-point values as a field on each cell: the plastic history lives at the quadrature
// points, but ParaView reads values at the cell's vertices and patch points. The local L2
// projection of the points' values onto the discontinuous Q_p polynomials of the cell, with the
// same p+1 Gauss points per direction as the history, is their interpolation: the field equals
// each point's value at that point (the space and the points are unisolvent), and between and
// beyond the points it is the polynomial through them — what Abaqus calls extrapolating
// integration-point values to the nodes, before any averaging between cells.
#pragma once

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

namespace clearjoint::fe::detail
{
  class PointProjection
  {
  public:
    /// The Q_degree cell polynomials and the QGauss(degree + 1) points of the material history.
    explicit PointProjection(unsigned int degree);

    const dealii::FE_DGQ<3> &fe() const { return fe_; }
    const dealii::QGauss<3> &points() const { return points_; }
    /// The cell polynomial's coefficients (fe()'s nodal values) from its values at points(),
    /// in the quadrature's order.
    void project(const dealii::Vector<double> &at_points,
                 dealii::Vector<double> &coefficients) const;

  private:
    dealii::FE_DGQ<3> fe_;
    dealii::QGauss<3> points_;
    dealii::FullMatrix<double> matrix_;  // fe_.n_dofs_per_cell() × points_.size()
  };
}  // namespace clearjoint::fe::detail
