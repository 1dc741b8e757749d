// Material-point values as a field ParaView can show: the plastic history (and so the stress)
// lives at the cell's Gauss points, but a VTU carries values at the points of each cell's output
// patch. A Q_p cell has (p+1)³ Gauss points and is written as a patch of (p+1)³ points (p
// subdivisions a direction, the nodes of FE_DGQ(p)), one-to-one in the same grid positions:
// each output point gets the values of the material point nearest it. So every value shown is
// a material point's own — its von Mises stress at most its yield stress, the field's largest
// the points' largest — placed up to (1 − x_p)·h of the cell size h outwards from where the point
// sits (x_p the outermost Gauss abscissa on [0, 1]: 0.887 for Q2, so 0.11 h; the middle
// point of a Q2 cell sits exactly on its output point). Extrapolating the points to the nodes
// by the cell's polynomial, as Abaqus does before averaging, was tried first: in a steep plastic
// zone it put nodal von Mises values at 2.1× the yield stress (362 against 168.9 MPa on the
// pipeline's reduced rolling scene with the deformable journal; 2.6× the cell's largest point's
// with the rigid journal).
#pragma once

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace clearjoint::fe::detail
{
  class MaterialPointField
  {
  public:
    /// The cells' Q_degree output points (FE_DGQ(degree)'s nodes) and their QGauss(degree + 1)
    /// material points.
    explicit MaterialPointField(unsigned int degree);

    const dealii::FE_DGQ<3> &fe() const { return fe_; }
    const dealii::QGauss<3> &points() const { return points_; }
    /// The material point (its index in points()) whose values node i of fe() shows.
    unsigned int point_of_node(const unsigned int i) const { return point_of_node_[i]; }
    /// fe()'s nodal values from the values at points(), in the quadrature's order.
    void place(const dealii::Vector<double> &at_points, dealii::Vector<double> &at_nodes) const;

  private:
    dealii::FE_DGQ<3> fe_;
    dealii::QGauss<3> points_;
    std::vector<unsigned int> point_of_node_;
  };
}  // namespace clearjoint::fe::detail
