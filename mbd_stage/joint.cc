#include "mbd_stage/joint.h"

#include "common/error.h"

#include <cmath>

namespace clearjoint::mbd
{
  JointType parse_joint_type(const std::string &name)
  {
    if (name == "revolute")
      return JointType::revolute;
    if (name == "translational")
      return JointType::translational;
    if (name == "spherical")
      return JointType::spherical;
    if (name == "fixed")
      return JointType::fixed;
    throw InputError("", "type", name, "one of revolute|translational|spherical|fixed");
  }

  std::string to_string(const JointType type)
  {
    switch (type)
    {
      case JointType::revolute:
        return "revolute";
      case JointType::translational:
        return "translational";
      case JointType::spherical:
        return "spherical";
      case JointType::fixed:
        return "fixed";
    }
    return "?";
  }

  void make_perpendiculars(const Vector3 &axis, Vector3 &h1, Vector3 &h2)
  {
    const Vector3 a = axis.normalized();
    // Start from the ground axis least aligned with a (ties to the lower index), so an axis
    // along x gives h1 = y, h2 = z.
    int i_min = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(a[i]) < std::abs(a[i_min]) - 1e-12)
        i_min = i;
    if (i_min == 0 && std::abs(a[0]) > 1.0 - 1e-12)
      i_min = 1;
    const Vector3 t = Vector3::Unit(i_min);
    h1 = (t - t.dot(a) * a).normalized();
    h2 = a.cross(h1);
  }

  Joint::Joint(std::string name, const JointType type, const int body_i, const int body_j,
               const Vector3 &point_G, const Vector3 &axis_G, const KinematicsView &k0)
    : name_(std::move(name))
    , type_(type)
    , body_i_(body_i)
    , body_j_(body_j)
  {
    Vector3 h1, h2;
    const Vector3 a = axis_G.normalized();
    make_perpendiculars(a, h1, h2);
    const BodyKinematics &bi = k0[body_i], &bj = k0[body_j];
    axis_i = bi.A.transpose() * a;
    axis_j = bj.A.transpose() * a;
    h1_i = bi.A.transpose() * h1;
    h1_j = bj.A.transpose() * h1;
    h2_i = bi.A.transpose() * h2;
    h2_j = bj.A.transpose() * h2;
    s_i = bi.A.transpose() * (point_G - bi.r);
    s_j = bj.A.transpose() * (point_G - bj.r);
  }

  int Joint::n_equations() const
  {
    switch (type_)
    {
      case JointType::revolute:
        return 5;
      case JointType::translational:
        return 5;
      case JointType::spherical:
        return 3;
      case JointType::fixed:
        return 6;
    }
    return 0;
  }

  namespace
  {
    ConstraintRow to_row(KinScalar &&s)
    {
      ConstraintRow r;
      r.phi = s.value;
      r.phi_t = 0.0;
      r.gamma = -s.quad;
      r.D = std::move(s.row);  // the row is a temporary: no copy
      return r;
    }
  } // namespace

  void Joint::evaluate(const KinematicsView &k, std::vector<ConstraintRow> &rows) const
  {
    const int n = k.n_bodies();
    const bool has_point = type_ != JointType::translational;
    if (has_point)
    {
      const KinVec d = body_point(k, body_i_, s_i) - body_point(k, body_j_, s_j);
      for (int c = 0; c < 3; ++c)
        rows.push_back(to_row(component(d, c, n)));
    }
    if (type_ == JointType::revolute)
    {
      const KinVec a = body_vector(k, body_i_, axis_i);
      rows.push_back(to_row(dot(a, body_vector(k, body_j_, h1_j), n)));
      rows.push_back(to_row(dot(a, body_vector(k, body_j_, h2_j), n)));
    }
    if (type_ == JointType::translational || type_ == JointType::fixed)
    {
      const KinVec a_j = body_vector(k, body_j_, axis_j);
      const KinVec g1 = body_vector(k, body_i_, h1_i), g2 = body_vector(k, body_i_, h2_i);
      rows.push_back(to_row(dot(g1, a_j, n)));
      rows.push_back(to_row(dot(g2, a_j, n)));
      rows.push_back(to_row(dot(g1, body_vector(k, body_j_, h2_j), n)));
      if (type_ == JointType::translational)
      {
        const KinVec d = body_point(k, body_j_, s_j) - body_point(k, body_i_, s_i);
        rows.push_back(to_row(dot(g1, d, n)));
        rows.push_back(to_row(dot(g2, d, n)));
      }
    }
  }

  Driver::Driver(std::string name, const Joint &joint, const double speed)
    : name_(std::move(name))
    , joint_(&joint)
    , speed_(speed)
  {
    if (joint.type() != JointType::revolute)
      throw InputError("", "drivers.joint", joint.name(), "a revolute joint",
                       "a rotational driver acts about a revolute joint's axis");
  }

  void Driver::evaluate(const KinematicsView &k, const double t,
                        std::vector<ConstraintRow> &rows) const
  {
    const int n = k.n_bodies();
    const Joint &J = *joint_;
    const KinVec u_j = body_vector(k, J.body_j(), J.h1_j);
    const KinScalar A = dot(u_j, body_vector(k, J.body_i(), J.h2_i), n);  // sin θ_rel
    const KinScalar B = dot(u_j, body_vector(k, J.body_i(), J.h1_i), n);  // cos θ_rel
    const double w = speed_, th = w * t, c = std::cos(th), s = std::sin(th);
    ConstraintRow r;
    r.phi = A.value * c - B.value * s;
    r.D = c * A.row - s * B.row;
    r.phi_t = -w * (A.value * s + B.value * c);
    // Φ̈ = D·u̇ + c·A_quad − s·B_quad − 2ω(Ȧ s + Ḃ c) − ω²(A c − B s)
    r.gamma = -(c * A.quad - s * B.quad - 2.0 * w * (A.rate * s + B.rate * c) -
                w * w * (A.value * c - B.value * s));
    rows.push_back(r);
  }
} // namespace clearjoint::mbd
