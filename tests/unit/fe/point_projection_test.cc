// The projection of material-point values onto each cell's polynomials, behind the VTU
// `stress` of a body with a plastic history (fe_stage/results/point_projection.h): it must give
// back every polynomial of the cell's space exactly — at the points, and at the vertices and
// patch points where ParaView reads it — so that a field is the points' own values wherever
// the points determine it.
#include "fe_stage/results/point_projection.h"

#include <gtest/gtest.h>

#include <cmath>

using clearjoint::fe::detail::PointProjection;

namespace
{
  /// A polynomial of degree `p` in each reference coordinate, with every power present.
  double tensor_polynomial(const dealii::Point<3> &x, const unsigned int p)
  {
    double v = 0.0;
    for (unsigned int a = 0; a <= p; ++a)
      for (unsigned int b = 0; b <= p; ++b)
        for (unsigned int c = 0; c <= p; ++c)
          v += (1.0 + a + 2.0 * b + 3.0 * c) * std::pow(x[0], a) * std::pow(x[1], b) *
               std::pow(x[2], c);
    return v;
  }
}  // namespace

TEST(PointProjection, ReproducesTheCellPolynomialsAtTheirNodes)
{
  for (const unsigned int p : {1u, 2u})
    {
      const PointProjection projection(p);
      const auto &points = projection.points();
      ASSERT_EQ(points.size(), projection.fe().n_dofs_per_cell()) << "unisolvent: interpolation";
      dealii::Vector<double> at_points(points.size()), coefficients;
      for (unsigned int q = 0; q < points.size(); ++q)
        at_points[q] = tensor_polynomial(points.point(q), p);
      projection.project(at_points, coefficients);
      // FE_DGQ's coefficients are its values at its support points, the cell's vertices among
      // them; 1e-12 relative: the projection matrix is a small dense solve (27 × 27 for Q2)
      const auto &nodes = projection.fe().get_unit_support_points();
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const double exact = tensor_polynomial(nodes[i], p);
          EXPECT_NEAR(coefficients[i], exact, 1e-12 * std::abs(exact))
            << "p " << p << " node " << i;
        }
    }
}

TEST(PointProjection, AFieldBeyondTheSpaceStillMatchesEveryPoint)
{
  // A steep plastic zone is not a polynomial: the cell's field must still pass through each
  // material point's own value (the old fields took one mean per cell and missed them).
  const PointProjection projection(2);
  const auto &points = projection.points();
  dealii::Vector<double> at_points(points.size()), coefficients;
  for (unsigned int q = 0; q < points.size(); ++q)
    at_points[q] = std::exp(8.0 * points.point(q)[0]) * std::cos(5.0 * points.point(q)[2]);
  projection.project(at_points, coefficients);
  for (unsigned int q = 0; q < points.size(); ++q)
    {
      double value = 0.0;
      for (unsigned int i = 0; i < projection.fe().n_dofs_per_cell(); ++i)
        value += coefficients[i] * projection.fe().shape_value(i, points.point(q));
      EXPECT_NEAR(value, at_points[q], 1e-10 * std::abs(at_points.linfty_norm())) << "point " << q;
    }
}
