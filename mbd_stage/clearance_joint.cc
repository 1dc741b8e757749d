#include "mbd_stage/clearance_joint.h"

#include "common/error.h"
#include "mbd_stage/joint.h"

#include <algorithm>
#include <cmath>

namespace clearjoint::mbd
{
  ClearanceJoint::ClearanceJoint(std::string name, const int bearing_body, const int journal_body,
                                 const Vector3 &bearing_center_G, const Vector3 &bearing_axis_G,
                                 const Vector3 &journal_center_G, const Vector3 &journal_axis_G,
                                 ClearanceGeometry geometry, ContactForceModel radial,
                                 ContactForceModel axial, CoulombFriction friction,
                                 const KinematicsView &k0)
    : name_(std::move(name))
    , bearing_(bearing_body)
    , journal_(journal_body)
    , geometry_(geometry)
    , radial_(std::move(radial))
    , axial_(std::move(axial))
    , friction_(friction)
  {
    const BodyKinematics &kb = k0[bearing_body], &kj = k0[journal_body];
    const Vector3 b = bearing_axis_G.normalized(), j = journal_axis_G.normalized();
    s_B_ = kb.A.transpose() * (bearing_center_G - kb.r);
    b_B_ = kb.A.transpose() * b;
    s_J_ = kj.A.transpose() * (journal_center_G - kj.r);
    j_J_ = kj.A.transpose() * j;
    Vector3 h1, h2;
    make_perpendiculars(b, h1, h2);
    h1_B_ = kb.A.transpose() * h1;
    h2_B_ = kb.A.transpose() * h2;
    // Start in contact if the initial configuration already penetrates (δ̇⁻ = the floor).
    const auto g = gaps(k0);
    for (int c = 0; c < n_contacts; ++c)
      states_[c].active = g[c] > 0.0;
  }

  ClearanceJoint::Placement ClearanceJoint::place(const KinematicsView &k) const
  {
    const BodyKinematics &kb = k[bearing_], &kj = k[journal_];
    const ClearanceGeometry &G = geometry_;
    Placement p;
    p.C_B = kb.r + kb.A * s_B_;
    p.b = kb.A * b_B_;
    p.C_J = kj.r + kj.A * s_J_;
    p.j = kj.A * j_J_;
    if (p.j.dot(p.b) < 0.0)
      p.j = -p.j;  // the journal has no preferred direction
    const double cos_t = std::min(1.0, p.j.dot(p.b));
    const Vector3 m = p.b - cos_t * p.j;  // in the rim plane, toward +b; |m| = sin θ
    const double sin_t = m.norm();
    p.theta = std::atan2(sin_t, cos_t);

    // Radial: rims at E− (s = 0) and E+ (s = L_J).
    const auto radial_offset = [&](const Vector3 &X, Vector3 &n) {
      const Vector3 w = X - p.C_B;
      const Vector3 e = w - w.dot(p.b) * p.b;
      const double d = e.norm();
      if (d > 1e-300)
        n = e / d;
      else
      {
        Vector3 h2;
        make_perpendiculars(p.b, n, h2);
      }
      return d;
    };
    const Vector3 E_minus = p.C_J - 0.5 * G.L_J * p.j;
    std::array<double, 2> d_end;
    for (int end = 0; end < 2; ++end)
    {
      Vector3 n;
      const double d = radial_offset(E_minus + end * G.L_J * p.j, n);
      const double nj = n.dot(p.j);
      d_end[end] = d + G.R_J * std::sqrt(std::max(0.0, 1.0 - nj * nj)) - G.R_B;
    }
    const double d1 = d_end[0], d2 = d_end[1], L = G.L_J;
    double s_bar;
    if (d1 > 0.0 && d2 > 0.0)
      s_bar = L * (d1 + 2.0 * d2) / (3.0 * (d1 + d2));  // trapezoid centroid
    else if (d1 > 0.0)
      s_bar = (L * d1 / (d1 - d2)) / 3.0;                // triangle at the E− rim
    else if (d2 > 0.0)
      s_bar = L - (L - L * d1 / (d1 - d2)) / 3.0;        // triangle at the E+ rim
    else
      s_bar = d1 >= d2 ? 0.0 : L;
    p.delta[0] = std::max(d1, d2);
    {
      Vector3 n;
      const Vector3 A = E_minus + s_bar * p.j;
      radial_offset(A, n);
      p.normal[0] = n;
      p.point[0] = p.C_B + (A - p.C_B).dot(p.b) * p.b + G.R_B * n;
    }

    // Axial walls.
    const double u = (p.C_J - p.C_B).dot(p.b);
    const double h = 0.5 * G.L_J * cos_t + G.R_J * sin_t;
    const Vector3 m_hat = m / std::max(sin_t, std::sin(aligned_angle));
    for (int side = 0; side < 2; ++side)
    {
      const double sgn = side == 0 ? 1.0 : -1.0;
      p.delta[1 + side] = sgn * u + h - 0.5 * G.L_B;
      p.normal[1 + side] = sgn * p.b;
      p.point[1 + side] = p.C_J + sgn * (0.5 * G.L_J * p.j + G.R_J * m_hat);
    }
    return p;
  }

  std::array<double, 3> ClearanceJoint::gaps(const KinematicsView &k) const
  {
    return place(k).delta;
  }

  std::array<double, 3> ClearanceJoint::rates(const KinematicsView &k) const
  {
    const Placement p = place(k);
    std::array<double, 3> r;
    for (int c = 0; c < n_contacts; ++c)
      r[c] = (k[journal_].point_velocity(p.point[c]) - k[bearing_].point_velocity(p.point[c]))
               .dot(p.normal[c]);
    return r;
  }

  ContactResult ClearanceJoint::evaluate_contact(const KinematicsView &k, const int c,
                                                 const Placement &p, Eigen::VectorXd &Q) const
  {
    ContactResult r;
    r.delta = p.delta[c];
    r.point = p.point[c];
    r.normal = p.normal[c];
    const BodyKinematics &kb = k[bearing_], &kj = k[journal_];
    const Vector3 v_rel = kj.point_velocity(r.point) - kb.point_velocity(r.point);
    r.delta_dot = v_rel.dot(r.normal);
    if (!states_[c].active || r.delta <= 0.0)
      return r;
    const ContactForceModel &model = c == 0 ? radial_ : axial_;
    const ContactForce f =
      model.force(r.delta, r.delta_dot, states_[c].delta_dot_impact, c == 0 ? p.theta : 0.0);
    r.F_n = f.total;
    r.F_el = f.elastic;
    r.E_el = model.elastic_energy(r.delta, c == 0 ? p.theta : 0.0);
    const Vector3 v_T = v_rel - r.delta_dot * r.normal;
    const Vector3 F_f = friction_.force(r.F_n, v_T);
    r.F_t = F_f.norm();
    r.P_friction = F_f.dot(v_T);
    r.P_damping = -(r.F_n - r.F_el) * r.delta_dot;
    r.force_on_journal = -r.F_n * r.normal + F_f;
    const auto add = [&](const int body, const Vector3 &f_G) {
      if (body == ground_index)
        return;
      const BodyKinematics &kk = k[body];
      Q.segment<3>(6 * body) += f_G;
      Q.segment<3>(6 * body + 3) += kk.A.transpose() * (r.point - kk.r).cross(f_G);
    };
    add(journal_, r.force_on_journal);
    add(bearing_, -r.force_on_journal);
    return r;
  }

  void ClearanceJoint::apply(const KinematicsView &k, Eigen::VectorXd &Q,
                             ClearanceOutput *out) const
  {
    const Placement p = place(k);
    std::array<ContactResult, 3> results;
    for (int c = 0; c < n_contacts; ++c)
      results[c] = evaluate_contact(k, c, p, Q);
    if (out)
    {
      out->contacts = results;
      const BodyKinematics &kb = k[bearing_];
      const Vector3 w = p.C_J - p.C_B;
      const Vector3 e = w - w.dot(p.b) * p.b;
      out->ecc_1 = e.dot(kb.A * h1_B_);
      out->ecc_2 = e.dot(kb.A * h2_B_);
      out->theta = p.theta;
    }
  }
} // namespace clearjoint::mbd
