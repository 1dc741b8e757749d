// Material-point values placed on the cells' output points (results/material_point_field.h).
#include "fe_stage/results/material_point_field.h"

#include <limits>
#include <stdexcept>
#include <string>

namespace clearjoint::fe::detail
{
  MaterialPointField::MaterialPointField(const unsigned int degree)
    : fe_(degree)
    , points_(degree + 1)
  {
    const auto &nodes = fe_.get_unit_support_points();
    if (nodes.size() != points_.size())
      throw std::logic_error("fe_stage: the Q" + std::to_string(degree) + " cell has " +
                             std::to_string(nodes.size()) + " output points for " +
                             std::to_string(points_.size()) + " material points");
    std::vector<bool> taken(points_.size(), false);
    for (const auto &node : nodes)
      {
        unsigned int nearest = 0;
        double d_min = std::numeric_limits<double>::infinity();
        for (unsigned int q = 0; q < points_.size(); ++q)
          if (const double d = node.distance(points_.point(q)); d < d_min)
            d_min = d, nearest = q;
        // the two grids match position by position, so no point is the nearest of two nodes
        if (taken[nearest])
          throw std::logic_error("fe_stage: two output points of a Q" + std::to_string(degree) +
                                 " cell share their nearest material point");
        taken[nearest] = true;
        point_of_node_.push_back(nearest);
      }
  }

  void MaterialPointField::place(const dealii::Vector<double> &at_points,
                                 dealii::Vector<double> &at_nodes) const
  {
    at_nodes.reinit(point_of_node_.size());
    for (unsigned int i = 0; i < point_of_node_.size(); ++i)
      at_nodes[i] = at_points[point_of_node_[i]];
  }
}  // namespace clearjoint::fe::detail
