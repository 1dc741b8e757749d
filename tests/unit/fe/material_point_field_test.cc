// The material points' values on the cells' output points, behind the VTU `stress` of a body with
// a plastic history (fe_stage/results/material_point_field.h): each output point shows the
// material point nearest it, one-to-one, so that every value ParaView shows is a material
// point's own and none lies beyond them (the polynomial through the points, tried first,
// overshot the yield stress 2.1× at the nodes of a steep plastic zone).
#include "fe_stage/results/material_point_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using clearjoint::fe::detail::MaterialPointField;

TEST(MaterialPointField, EachOutputPointShowsItsNearestMaterialPointOneToOne)
{
  for (const unsigned int p : {1u, 2u, 3u})
    {
      const MaterialPointField field(p);
      const auto &nodes = field.fe().get_unit_support_points();
      const auto &points = field.points();
      ASSERT_EQ(nodes.size(), points.size()) << "Q" << p;
      std::set<unsigned int> used;
      // the outermost Gauss abscissa on [0, 1]: the farthest a value is shown from its point is
      // that distance from the cell's face in each direction
      double outermost = 0.0;
      for (unsigned int q = 0; q < points.size(); ++q)
        outermost = std::max(outermost, points.point(q)[0]);
      const double farthest = std::sqrt(3.0) * (1.0 - outermost);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const unsigned int q = field.point_of_node(i);
          used.insert(q);
          EXPECT_LE(nodes[i].distance(points.point(q)), farthest * (1.0 + 1e-12))
            << "Q" << p << " node " << i;
          for (unsigned int r = 0; r < points.size(); ++r)
            EXPECT_LE(nodes[i].distance(points.point(q)), nodes[i].distance(points.point(r)))
              << "Q" << p << " node " << i << ": point " << r << " is nearer than " << q;
        }
      EXPECT_EQ(used.size(), points.size()) << "Q" << p << ": every point shown once";
    }
}

TEST(MaterialPointField, ShowsThePointsOwnValuesAndNothingBeyondThem)
{
  // a steep field, as across a plastic zone's edge: the nodes carry exactly the points' values
  // (as a set), so the field's extremes are the points' (the Q2 polynomial through the same
  // points reaches far beyond them at the vertices)
  const MaterialPointField field(2);
  const auto &points = field.points();
  dealii::Vector<double> at_points(points.size()), at_nodes;
  for (unsigned int q = 0; q < points.size(); ++q)
    at_points[q] = std::exp(8.0 * points.point(q)[0]) * std::cos(5.0 * points.point(q)[2]);
  field.place(at_points, at_nodes);
  ASSERT_EQ(at_nodes.size(), at_points.size());
  std::vector<double> a(at_points.begin(), at_points.end()), b(at_nodes.begin(), at_nodes.end());
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // the middle point of a Q2 cell is its middle output point: shown where it is
  const dealii::Point<3> middle(0.5, 0.5, 0.5);
  for (unsigned int i = 0; i < at_nodes.size(); ++i)
    if (field.fe().get_unit_support_points()[i].distance(middle) < 1e-12)
      {
        EXPECT_LT(points.point(field.point_of_node(i)).distance(middle), 1e-12);
        EXPECT_EQ(at_nodes[i], at_points[field.point_of_node(i)]);
      }
}
