#include "mbd_stage/clearance_joint.h"

#include "common/error.h"
#include "mbd_stage/joint.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
    {
      states_[c].active = g[c] > 0.0;
      const ContactForceModel &model = c == 0 ? radial_ : axial_;
      if (states_[c].active && model.chi() != 0.0)
        ++states_[c].n_impact_velocity_floored;
    }
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
      // The rim point X farthest from the bearing axis: X(φ) = E + R_J(cos φ u1 + sin φ u2)
      // on the rim circle (u1, u2 ⟂ j), f(φ) = |P(X − C_B)|², P = I − b bᵀ, maximised by Newton
      // from the rim point along the rim centre's offset (quadratic convergence; the optimum
      // is close to it as long as |e| ≫ R_J(1 − cos θ)). With X the true maximiser, dδ/dt is
      // the normal relative velocity of the material points at X (envelope theorem), so the
      // force is the exact gradient of the law's energy.
      const Vector3 E = E_minus + end * G.L_J * p.j;
      Vector3 n;
      radial_offset(E, n);
      Vector3 u1 = n - n.dot(p.j) * p.j;
      if (u1.norm() < 1e-12)
      {
        Vector3 h2;
        make_perpendiculars(p.j, u1, h2);
      }
      u1.normalize();
      const Vector3 u2 = p.j.cross(u1);
      const auto perp = [&](const Vector3 &v) { return Vector3(v - v.dot(p.b) * p.b); };
      double phi = 0.0;
      for (int it = 0; it < 20; ++it)
      {
        const double c = std::cos(phi), s = std::sin(phi);
        const Vector3 PX = perp(E - p.C_B + G.R_J * (c * u1 + s * u2));
        const Vector3 PX1 = perp(G.R_J * (-s * u1 + c * u2));
        const Vector3 PX2 = perp(-G.R_J * (c * u1 + s * u2));
        const double f1 = 2.0 * PX.dot(PX1), f2 = 2.0 * (PX1.dot(PX1) + PX.dot(PX2));
        if (!(f2 < 0.0))
          break;  // not near a maximum (should not happen for a rim inside the bearing)
        const double step = -f1 / f2;
        phi += step;
        if (std::abs(step) < 1e-15)
          break;
      }
      const Vector3 X = E + G.R_J * (std::cos(phi) * u1 + std::sin(phi) * u2);
      radial_offset(X, n);
      p.normal[0][end] = n;
      p.point[0][end] = X;
      const Vector3 w = X - p.C_B;
      d_end[end] = (w - w.dot(p.b) * p.b).norm() - G.R_B;
    }
    // Smooth maximum of the rim penetrations; its partial derivatives are the weights.
    const double eps = blend_fraction * G.c_r(), dd = d_end[1] - d_end[0];
    const double g = dd <= -eps ? 0.0 : (dd >= eps ? dd : (dd + eps) * (dd + eps) / (4.0 * eps));
    p.delta[0] = d_end[0] + g;
    const double w_plus = std::clamp(0.5 + 0.5 * dd / eps, 0.0, 1.0);
    p.weight[0] = {1.0 - w_plus, w_plus};

    // Axial walls.
    const double u = (p.C_J - p.C_B).dot(p.b);
    const double s0 = aligned_sine;
    const double phi = sin_t < s0 ? sin_t * sin_t / (2.0 * s0) : sin_t - 0.5 * s0;
    const double h = 0.5 * G.L_J * cos_t + G.R_J * phi;
    const Vector3 m_hat = m / std::max(sin_t, s0);
    for (int side = 0; side < 2; ++side)
    {
      const double sgn = side == 0 ? 1.0 : -1.0;
      p.delta[1 + side] = sgn * u + h - 0.5 * G.L_B;
      p.normal[1 + side] = {sgn * p.b, sgn * p.b};
      const Vector3 P = p.C_J + sgn * (0.5 * G.L_J * p.j + G.R_J * m_hat);
      p.point[1 + side] = {P, P};
      p.weight[1 + side] = {1.0, 0.0};
    }
    return p;
  }

  std::array<double, 3> ClearanceJoint::gaps(const KinematicsView &k) const
  {
    return place(k).delta;
  }

  std::array<double, 3> ClearanceJoint::root_functions(const KinematicsView &k) const
  {
    std::array<double, 3> g = place(k).delta;
    for (int c = 0; c < n_contacts; ++c)
      if (states_[c].active)
        g[c] += release_offset();
    return g;
  }

  std::array<double, 3> ClearanceJoint::rates(const KinematicsView &k) const
  {
    const Placement p = place(k);
    std::array<double, 3> r;
    for (int c = 0; c < n_contacts; ++c)
    {
      r[c] = 0.0;
      for (int i = 0; i < 2; ++i)
        if (p.weight[c][i] > 0.0)
          r[c] += p.weight[c][i] * (k[journal_].point_velocity(p.point[c][i]) -
                                    k[bearing_].point_velocity(p.point[c][i]))
                                     .dot(p.normal[c][i]);
    }
    return r;
  }

  void ClearanceJoint::observe_accepted(const KinematicsView &k, const double D) const
  {
    const Placement p = place(k);
    for (int c = 0; c < n_contacts; ++c)
    {
      if (states_[c].active)
        (c == 0 ? radial_ : axial_).observe_accepted(p.delta[c], c == 0 ? p.theta : 0.0);
      if (D > 0.0)  // the same allowance as guard_step()
        allowance_[c] = std::max(D, p.delta[c] + 0.5 * D);
    }
  }

  double ClearanceJoint::guard_step(
    const KinematicsView &k, const double D,
    const std::function<double(int, const Vector3 &, const Vector3 &)> &compliance,
    const double *accel) const
  {
    const Placement p = place(k);
    double h = std::numeric_limits<double>::infinity();
    for (int c = 0; c < n_contacts; ++c)
    {
      const double delta = p.delta[c];
      double rate = 0.0, inv_m = 0.0;
      for (int i = 0; i < 2; ++i)
      {
        const double w = p.weight[c][i];
        if (w <= 0.0)
          continue;
        const Vector3 &P = p.point[c][i], &n = p.normal[c][i];
        rate += w * (k[journal_].point_velocity(P) - k[bearing_].point_velocity(P)).dot(n);
        inv_m = std::max(inv_m, compliance(journal_, P, n) + compliance(bearing_, P, n));
      }
      const double allowance = std::max(D, delta + 0.5 * D), room = allowance - delta;
      const double a = accel ? std::max(accel[c], 0.0) : 0.0;
      if (a > 0.0)  // positive root of δ̈h²/2 + δ̇h − room = 0
        h = std::min(h, 2.0 * room / (rate + std::sqrt(rate * rate + 2.0 * a * room)));
      else if (rate > 0.0)
        h = std::min(h, room / rate);
      if (states_[c].active)
      {
        const ContactForceModel &model = c == 0 ? radial_ : axial_;
        const double theta = c == 0 ? p.theta : 0.0;
        const double d1 = std::max(D, delta), F1 = model.elastic_force(d1, theta);
        const double F2 = model.elastic_force(0.5 * d1, theta);
        // Secant stiffness F(d1)/d1 times the local exponent log2(F(d1)/F(d1/2)) when > 1
        // (a power law's tangent stiffness at d1 is n·F/d1).
        const double n_loc = F2 > 0.0 ? std::log2(F1 / F2) : 1.0;
        const double stiffness = F1 / d1 * std::max(1.0, n_loc);
        if (stiffness > 0.0 && inv_m > 0.0)
          h = std::min(h, 2.0 / std::sqrt(stiffness * inv_m));
      }
    }
    return h;
  }

  ContactResult ClearanceJoint::evaluate_contact(const KinematicsView &k, const int c,
                                                 const Placement &p, Eigen::VectorXd &Q) const
  {
    ContactResult r;
    r.delta = p.delta[c];
    const BodyKinematics &kb = k[bearing_], &kj = k[journal_];
    std::array<Vector3, 2> v_rel;
    std::array<double, 2> rate{0.0, 0.0};
    for (int i = 0; i < 2; ++i)
    {
      const double w = p.weight[c][i];
      r.point += w * p.point[c][i];
      r.normal += w * p.normal[c][i];
      v_rel[i] = kj.point_velocity(p.point[c][i]) - kb.point_velocity(p.point[c][i]);
      rate[i] = v_rel[i].dot(p.normal[c][i]);
      r.delta_dot += w * rate[i];  // = dδ/dt (power-consistent with the weights)
    }
    if (r.normal.norm() > 0.0)
      r.normal.normalize();
    if (!states_[c].active || r.delta <= 0.0)
      return r;
    const ContactForceModel &model = c == 0 ? radial_ : axial_;
    const ContactForce f =
      model.force(r.delta, r.delta_dot, states_[c].delta_dot_impact, c == 0 ? p.theta : 0.0);
    r.F_n = f.total;
    r.F_el = f.elastic;
    r.E_el = model.elastic_energy(r.delta, c == 0 ? p.theta : 0.0);
    r.P_damping = -(r.F_n - r.F_el) * r.delta_dot;
    const auto add = [&](const int body, const Vector3 &P, const Vector3 &f_G) {
      if (body == ground_index)
        return;
      const BodyKinematics &kk = k[body];
      Q.segment<3>(6 * body) += f_G;
      Q.segment<3>(6 * body + 3) += kk.A.transpose() * (P - kk.r).cross(f_G);
    };
    Vector3 F_t_total = Vector3::Zero();
    for (int i = 0; i < 2; ++i)
    {
      const double w = p.weight[c][i];
      if (w <= 0.0)
        continue;
      const Vector3 &n = p.normal[c][i], &P = p.point[c][i];
      const Vector3 v_T = v_rel[i] - rate[i] * n;
      const Vector3 F_f = friction_.force(w * r.F_n, v_T);
      r.P_friction += F_f.dot(v_T);
      F_t_total += F_f;
      const Vector3 f_J = -w * r.F_n * n + F_f;
      r.force_on_journal += f_J;
      add(journal_, P, f_J);
      add(bearing_, P, -f_J);
    }
    r.F_t = F_t_total.norm();
    return r;
  }

  void ClearanceJoint::apply(const KinematicsView &k, Eigen::VectorXd &Q,
                             ClearanceOutput *out) const
  {
    const Placement p = place(k);
    std::array<ContactResult, 3> results;
    for (int c = 0; c < n_contacts; ++c)
    {
      results[c] = evaluate_contact(k, c, p, Q);
      max_delta_any_[c] = std::max(max_delta_any_[c], p.delta[c]);
      if (p.delta[c] > allowance_[c])
        ++n_beyond_[c];
    }
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
