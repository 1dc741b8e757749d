#include "mbd_stage/multibody_system.h"

#include "common/error.h"
#include "common/log.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <limits>

namespace clearjoint::mbd
{
  namespace
  {
    constexpr int n_pos = 7, n_vel = 6;
  }

  int MultibodySystem::add_body(const BodyProperties &props, const BodyKinematics &initial)
  {
    bodies_.push_back(props);
    BodyKinematics k = initial;
    k.A = rotation_matrix(k.e);
    initial_.push_back(k);
    return n_bodies() - 1;
  }

  int MultibodySystem::body_index(const std::string &name) const
  {
    if (name == "ground")
      return ground_index;
    for (int b = 0; b < n_bodies(); ++b)
      if (bodies_[b].name == name)
        return b;
    return -2;
  }

  void MultibodySystem::add_joint(std::string name, const JointType type, const int body_i,
                                  const int body_j, const Vector3 &point_G, const Vector3 &axis_G)
  {
    const KinematicsView k0(&initial_);
    joints_.emplace_back(std::move(name), type, body_i, body_j, point_G, axis_G, k0);
  }

  void MultibodySystem::add_driver(std::string name, const int joint, const double speed)
  {
    drivers_.emplace_back(std::move(name), joints_.at(static_cast<std::size_t>(joint)), speed);
  }

  void MultibodySystem::add_clearance_joint(std::unique_ptr<ClearanceJoint> joint)
  {
    clearance_.push_back(std::move(joint));
  }

  int MultibodySystem::n_states() const
  {
    return (n_pos + n_vel) * n_bodies() + 2 * static_cast<int>(clearance_.size()) +
           static_cast<int>(drivers_.size());
  }

  void MultibodySystem::constraint_rows(const KinematicsView &k, const double t,
                                        std::vector<ConstraintRow> &rows) const
  {
    rows.clear();
    for (const Joint &j : joints_)
      j.evaluate(k, rows);
    for (const Driver &d : drivers_)
      d.evaluate(k, t, rows);
  }

  void MultibodySystem::unpack_into(const double *y, std::vector<BodyKinematics> &k) const
  {
    const int nb = n_bodies();
    k.resize(static_cast<std::size_t>(nb));
    for (int b = 0; b < nb; ++b)
    {
      BodyKinematics &kb = k[b];
      kb.r = Eigen::Map<const Vector3>(y + n_pos * b);
      kb.e = Eigen::Map<const Vector4>(y + n_pos * b + 3);
      kb.A = rotation_matrix(kb.e);
      kb.v = Eigen::Map<const Vector3>(y + n_pos * nb + n_vel * b);
      kb.w_B = Eigen::Map<const Vector3>(y + n_pos * nb + n_vel * b + 3);
    }
  }

  std::vector<BodyKinematics> MultibodySystem::unpack(const double *y) const
  {
    std::vector<BodyKinematics> k;
    unpack_into(y, k);
    return k;
  }

  double MultibodySystem::finalize(const double t0)
  {
    const int nb = n_bodies(), nu = n_vel * nb;
    const KinematicsView k(&initial_);
    std::vector<ConstraintRow> rows;
    constraint_rows(k, t0, rows);
    n_rows_ = static_cast<int>(rows.size());
    rows_of_body_.assign(static_cast<std::size_t>(nb), {});
    {
      int r = 0;
      const auto add = [&](const int body, const int r0, const int n) {
        if (body != ground_index)
          for (int i = r0; i < r0 + n; ++i)
            rows_of_body_[body].push_back(i);
      };
      for (const Joint &j : joints_)
      {
        add(j.body_i(), r, j.n_equations());
        add(j.body_j(), r, j.n_equations());
        r += j.n_equations();
      }
      for (const Driver &d : drivers_)
      {
        add(d.joint().body_i(), r, 1);
        add(d.joint().body_j(), r, 1);
        r += 1;
      }
      if (r != n_rows_)
        throw std::logic_error("MultibodySystem: constraint row count mismatch");
    }

    Eigen::VectorXd u0(nu), m_inv(nu);
    for (int b = 0; b < nb; ++b)
    {
      u0.segment<3>(n_vel * b) = initial_[b].v;
      u0.segment<3>(n_vel * b + 3) = initial_[b].w_B;
      m_inv.segment<3>(n_vel * b).setConstant(1.0 / bodies_[b].mass);
      m_inv.segment<3>(n_vel * b + 3) = bodies_[b].inertia.cwiseInverse();
    }
    if (n_rows_ > 0)
    {
      Eigen::MatrixXd D(n_rows_, nu);
      Eigen::VectorXd phi(n_rows_), phi_t(n_rows_);
      for (int r = 0; r < n_rows_; ++r)
      {
        D.row(r) = rows[r].D;
        phi[r] = rows[r].phi;
        phi_t[r] = rows[r].phi_t;
      }
      if (phi.cwiseAbs().maxCoeff() > 1e-9)
        throw InputError("", "joints", format_value(phi.cwiseAbs().maxCoeff()),
                         "|Phi| <= 1e-9 at t = 0",
                         "the initial positions violate the joint constraints");
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(D.transpose());
      qr.setThreshold(1e-10);
      n_redundant_ = n_rows_ - static_cast<int>(qr.rank());
      independent_rows_.clear();
      for (Eigen::Index i = 0; i < qr.rank(); ++i)
        independent_rows_.push_back(static_cast<int>(qr.colsPermutation().indices()[i]));
      std::sort(independent_rows_.begin(), independent_rows_.end());
      if (n_redundant_ > 0)
        log::warning(std::to_string(n_redundant_) + " of " + std::to_string(n_rows_) +
                     " constraint equations are redundant (e.g. a planar mechanism built from "
                     "spatial joints): the motion is unique; the redundant rows are dropped "
                     "and the joint reactions are those of the independent rows");
      // Minimum-kinetic-energy velocity correction onto D·u = −Φ_t:
      //   u = u0 − M⁻¹Dᵀ(D M⁻¹ Dᵀ)⁺(D·u0 + Φ_t).
      const Eigen::MatrixXd S = D * m_inv.asDiagonal() * D.transpose();
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(S);
      cod.setThreshold(1e-12);
      const Eigen::VectorXd mu = cod.solve(D * u0 + phi_t);
      const Eigen::VectorXd du = -(m_inv.asDiagonal() * D.transpose() * mu);
      const Eigen::VectorXd m_diag = m_inv.cwiseInverse();
      velocity_correction_ = std::sqrt(du.dot(m_diag.asDiagonal() * du));  // √(2·ΔE-like) [√J]
      const double residual = (D * (u0 + du) + phi_t).cwiseAbs().maxCoeff();
      if (residual > 1e-8)
        throw InputError("", "bodies[*].velocity", format_value(residual),
                         "velocities satisfying the joint constraints",
                         "they could not be made consistent (conflicting drivers?)");
      u0 += du;
      // Corrections below 1e-6 (m/s, rad/s) are rounding of the input values: info only.
      if (du.cwiseAbs().maxCoeff() > 1e-12)
      {
        std::string changes;
        for (int b = 0; b < nb; ++b)
          if (du.segment<6>(n_vel * b).cwiseAbs().maxCoeff() > 1e-9)
          {
            const Vector3 dv = du.segment<3>(n_vel * b);
            const Vector3 dw = initial_[b].A * du.segment<3>(n_vel * b + 3);
            changes += " " + bodies_[b].name + ": dv = (" + format_value(dv.x()) + ", " +
                       format_value(dv.y()) + ", " + format_value(dv.z()) + ") m/s, dω = (" +
                       format_value(dw.x()) + ", " + format_value(dw.y()) + ", " +
                       format_value(dw.z()) + ") rad/s;";
          }
        const std::string msg =
          "initial velocities violated the constraints (max |D·u + Φ_t| = " +
          format_value((D * (u0 - du) + phi_t).cwiseAbs().maxCoeff()) +
          "); corrected with the least kinetic-energy change:" + changes;
        if (du.cwiseAbs().maxCoeff() > 1e-6)
          log::warning(msg);
        else
          log::info(msg);
      }
    }
    y0_.setZero(n_states());
    for (int b = 0; b < nb; ++b)
    {
      y0_.segment<3>(n_pos * b) = initial_[b].r;
      y0_.segment<4>(n_pos * b + 3) = initial_[b].e;
      y0_.segment<6>(n_pos * nb + n_vel * b) = u0.segment<6>(n_vel * b);
    }
    return velocity_correction_;
  }

  void MultibodySystem::assemble_applied_forces(Workspace &W) const
  {
    const int nb = n_bodies(), nu = n_vel * nb;
    W.Q.setZero(nu);
    W.m_inv.resize(nu);
    W.u.resize(nu);
    for (int b = 0; b < nb; ++b)
    {
      const BodyProperties &p = bodies_[b];
      const BodyKinematics &kb = W.kin[b];
      W.Q.segment<3>(n_vel * b) = p.mass * gravity_;
      const Vector3 Jw = p.inertia.cwiseProduct(kb.w_B);
      W.Q.segment<3>(n_vel * b + 3) = -kb.w_B.cross(Jw);
      W.m_inv.segment<3>(n_vel * b).setConstant(1.0 / p.mass);
      W.m_inv.segment<3>(n_vel * b + 3) = p.inertia.cwiseInverse();
      W.u.segment<3>(n_vel * b) = kb.v;
      W.u.segment<3>(n_vel * b + 3) = kb.w_B;
    }
  }

  void MultibodySystem::add_clearance_joint_forces(const KinematicsView &k, Workspace &W,
                                                   SystemEvaluation *eval) const
  {
    if (eval)
      eval->clearance.resize(clearance_.size());
    W.P_fric.assign(clearance_.size(), 0.0);
    W.P_damp.assign(clearance_.size(), 0.0);
    for (std::size_t c = 0; c < clearance_.size(); ++c)
    {
      ClearanceOutput out;
      clearance_[c]->apply(k, W.Q, &out);
      for (const ContactResult &r : out.contacts)
      {
        W.P_fric[c] += r.P_friction;
        W.P_damp[c] += r.P_damping;
      }
      if (eval)
        eval->clearance[c] = out;
    }
  }

  void MultibodySystem::assemble_constraint_equations(Workspace &W) const
  {
    const int nu = n_vel * n_bodies(), nc = static_cast<int>(W.rows.size());
    W.D.resize(nc, nu);
    W.phi.resize(nc);
    W.phi_dot.resize(nc);
    W.rhs_c.resize(nc);
    for (int r = 0; r < nc; ++r)
    {
      const ConstraintRow &row = W.rows[r];
      W.D.row(r) = row.D;
      W.phi[r] = row.phi;
      W.phi_dot[r] = row.D.dot(W.u) + row.phi_t;
      W.rhs_c[r] = row.gamma - 2.0 * stab_.alpha * W.phi_dot[r] - stab_.beta * stab_.beta * W.phi[r];
    }
  }

  void MultibodySystem::assemble_schur_complement(const int nc, Workspace &W) const
  {
    // S = D M⁻¹ Dᵀ (lower triangle, which is what LLT reads), body block by body block:
    // a row involves at most two bodies, so most of the dense product is zeros.
    W.S_full.setZero(nc, nc);
    for (int b = 0; b < n_bodies(); ++b)
    {
      const auto &rb = rows_of_body_[b];
      const Eigen::Matrix<double, 6, 1> mb = W.m_inv.segment<6>(n_vel * b);
      for (std::size_t i = 0; i < rb.size(); ++i)
      {
        const Eigen::Matrix<double, 1, 6> di = W.D.row(rb[i]).segment<6>(n_vel * b).cwiseProduct(mb.transpose());
        for (std::size_t j = 0; j <= i; ++j)
          W.S_full(rb[i], rb[j]) += di.dot(W.D.row(rb[j]).segment<6>(n_vel * b));
      }
    }
    if (n_redundant_ > 0)
    {
      const int ni = static_cast<int>(independent_rows_.size());
      W.S.resize(ni, ni);
      for (int i = 0; i < ni; ++i)
        for (int j = 0; j <= i; ++j)
          W.S(i, j) = W.S_full(independent_rows_[i], independent_rows_[j]);
    }
  }

  void MultibodySystem::solve_constraint_forces(const double t, const int nc, Workspace &W) const
  {
    const int nu = n_vel * n_bodies();
    W.b.noalias() = W.rhs_c - W.D * W.u_dot;
    // With redundant constraints the accelerations are solved on the independent rows
    // (the motion is the same for any consistent λ: Dᵀλ is unique); the others get λ = 0.
    const bool subset = n_redundant_ > 0;
    if (subset)
    {
      const int ni = static_cast<int>(independent_rows_.size());
      W.D_sub.resize(ni, nu);
      W.lambda_sub.resize(ni);
      for (int i = 0; i < ni; ++i)
      {
        W.D_sub.row(i) = W.D.row(independent_rows_[i]);
        W.lambda_sub[i] = W.b[independent_rows_[i]];
      }
    }
    const Eigen::MatrixXd &Dk = subset ? W.D_sub : W.D;
    W.DM.noalias() = Dk * W.m_inv.asDiagonal();
    assemble_schur_complement(nc, W);
    W.llt.compute(subset ? W.S : W.S_full);
    if (W.llt.info() != Eigen::Success)
      throw NumericalError("constraint Jacobian lost rank at t = " + format_value(t) +
                           " s (a singular configuration?)");
    if (subset)
    {
      W.llt.solveInPlace(W.lambda_sub);
      for (std::size_t i = 0; i < independent_rows_.size(); ++i)
        W.lambda[independent_rows_[i]] = W.lambda_sub[static_cast<Eigen::Index>(i)];
    }
    else
      W.lambda = W.llt.solve(W.b);
    W.u_dot.noalias() += W.DM.transpose() * (subset ? W.lambda_sub : W.lambda);
  }

  void MultibodySystem::write_state_derivative(const int nc, const Workspace &W,
                                               double *ydot) const
  {
    const int nb = n_bodies(), nu = n_vel * nb;
    for (int b = 0; b < nb; ++b)
    {
      const BodyKinematics &kb = W.kin[b];
      Eigen::Map<Vector3>(ydot + n_pos * b) = kb.v;
      const double norm2 = kb.e.squaredNorm();
      Eigen::Map<Vector4>(ydot + n_pos * b + 3) =
        euler_parameter_rate(kb.e, kb.w_B) - stab_.euler_gain * (norm2 - 1.0) * kb.e;
    }
    for (int i = 0; i < nu; ++i)
      ydot[n_pos * nb + i] = W.u_dot[i];
    int w = (n_pos + n_vel) * nb;
    for (std::size_t c = 0; c < clearance_.size(); ++c)
    {
      ydot[w++] = W.P_fric[c];
      ydot[w++] = W.P_damp[c];
    }
    // Driver power: the constraint force Dᵀλ of the driver row times u.
    for (std::size_t d = 0; d < drivers_.size(); ++d)
    {
      const int r = nc - static_cast<int>(drivers_.size()) + static_cast<int>(d);
      ydot[w++] = W.lambda[r] * W.D.row(r).dot(W.u);
    }
  }

  void MultibodySystem::check_finite(const double t, const double *ydot) const
  {
    for (int i = 0; i < n_states(); ++i)
      if (!std::isfinite(ydot[i]))
        throw NumericalError("non-finite state derivative (component " + std::to_string(i) +
                             ") at t = " + format_value(t) + " s");
  }

  void MultibodySystem::record_energies_and_work(const double *y, const Workspace &W,
                                                 SystemEvaluation &eval) const
  {
    const int nb = n_bodies();
    eval.E_kin = eval.E_pot = eval.E_el = 0.0;
    eval.euler_norm_error = 0.0;
    for (int b = 0; b < nb; ++b)
    {
      const BodyProperties &p = bodies_[b];
      const BodyKinematics &kb = W.kin[b];
      eval.E_kin += 0.5 * p.mass * kb.v.squaredNorm() + 0.5 * kb.w_B.dot(p.inertia.cwiseProduct(kb.w_B));
      eval.E_pot += -p.mass * gravity_.dot(kb.r);
      eval.euler_norm_error = std::max(eval.euler_norm_error, std::abs(kb.e.norm() - 1.0));
    }
    for (const auto &c : eval.clearance)
      for (const ContactResult &r : c.contacts)
        eval.E_el += r.E_el;
    int s = (n_pos + n_vel) * nb;
    eval.W_friction = eval.W_damping = eval.W_drivers = 0.0;
    for (std::size_t c = 0; c < clearance_.size(); ++c)
    {
      eval.W_friction += y[s++];
      eval.W_damping += y[s++];
    }
    for (std::size_t d = 0; d < drivers_.size(); ++d)
      eval.W_drivers += y[s++];
  }

  void MultibodySystem::record_joint_reactions(const Workspace &W, SystemEvaluation &eval) const
  {
    // Force on body_j from each joint's rows, f = D_vᵀ·λ.
    eval.joint_force_on_j.assign(joints_.size(), Vector3::Zero());
    int r0 = 0;
    for (std::size_t j = 0; j < joints_.size(); ++j)
    {
      const Joint &J = joints_[j];
      const int ne = J.n_equations();
      if (J.body_j() != ground_index)
        eval.joint_force_on_j[j] =
          W.D.block(r0, n_vel * J.body_j(), ne, 3).transpose() * W.lambda.segment(r0, ne);
      else if (J.body_i() != ground_index)
        eval.joint_force_on_j[j] =
          -(W.D.block(r0, n_vel * J.body_i(), ne, 3).transpose() * W.lambda.segment(r0, ne));
      r0 += ne;
    }
  }

  void MultibodySystem::rhs(const double t, const double *y, double *ydot,
                            SystemEvaluation *eval) const
  {
    Workspace &W = *ws_;
    unpack_into(y, W.kin);
    const KinematicsView k(&W.kin);

    // Applied forces: gravity, gyroscopic terms, then the clearance joints' contact, damping
    // and friction forces.
    assemble_applied_forces(W);
    add_clearance_joint_forces(k, W, eval);

    // Accelerations without constraints, then the constraint forces Dᵀλ added to them.
    // (The order of the first allocations of W is that of the code before rhs() was split:
    // it decides where the constraint rows' own buffers land in the heap, which cost ~1 % of
    // the run's instructions in malloc when it changed.)
    constraint_rows(k, t, W.rows);
    const int nc = static_cast<int>(W.rows.size());
    W.u_dot = W.m_inv.cwiseProduct(W.Q);
    W.lambda.setZero(nc);
    assemble_constraint_equations(W);
    if (nc > 0)
      solve_constraint_forces(t, nc, W);

    write_state_derivative(nc, W, ydot);
    check_finite(t, ydot);

    if (eval)
    {
      eval->t = t;
      eval->u_dot = W.u_dot;
      eval->lambda = W.lambda;
      eval->phi_norm = nc > 0 ? W.phi.cwiseAbs().maxCoeff() : 0.0;
      eval->phi_dot_norm = nc > 0 ? W.phi_dot.cwiseAbs().maxCoeff() : 0.0;
      record_energies_and_work(y, W, *eval);
      record_joint_reactions(W, *eval);
      eval->bodies = W.kin;
    }
  }

  void MultibodySystem::gaps(const double *y, double *g) const
  {
    std::vector<BodyKinematics> kin = unpack(y);
    const KinematicsView k(&kin);
    int i = 0;
    for (const auto &c : clearance_)
      for (const double d : c->root_functions(k))
        g[i++] = d;
  }

  std::vector<double> MultibodySystem::radial_forces(const double *y) const
  {
    std::vector<BodyKinematics> kin = unpack(y);
    const KinematicsView k(&kin);
    Eigen::VectorXd Q = Eigen::VectorXd::Zero(6 * n_bodies());
    std::vector<double> out;
    for (const auto &c : clearance_)
    {
      ClearanceOutput o;
      c->apply(k, Q, &o);
      out.push_back(o.contacts[0].F_n);
    }
    return out;
  }

  void MultibodySystem::observe_accepted(const double *y, const double guard_fraction) const
  {
    std::vector<BodyKinematics> kin = unpack(y);
    const KinematicsView k(&kin);
    for (const auto &c : clearance_)
      c->observe_accepted(k, guard_fraction * c->geometry().c_r());
  }

  double MultibodySystem::guard_step(const double *y, const double fraction,
                                     const double *accel) const
  {
    if (clearance_.empty() || !(fraction > 0.0))
      return std::numeric_limits<double>::infinity();
    std::vector<BodyKinematics> kin = unpack(y);
    const KinematicsView k(&kin);
    const auto compliance = [&](const int body, const Vector3 &P, const Vector3 &n) {
      if (body == ground_index)
        return 0.0;
      const BodyProperties &b = bodies_[body];
      const Vector3 rn = kin[body].A.transpose() * (P - kin[body].r).cross(n);
      return 1.0 / b.mass + rn.dot(b.inertia.cwiseInverse().cwiseProduct(rn));
    };
    double h = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < clearance_.size(); ++c)
      h = std::min(h, clearance_[c]->guard_step(k, fraction * clearance_[c]->geometry().c_r(),
                                                compliance, accel ? accel + 3 * c : nullptr));
    return h;
  }

  std::vector<double> MultibodySystem::contact_rates(const double *y) const
  {
    std::vector<BodyKinematics> kin = unpack(y);
    const KinematicsView k(&kin);
    std::vector<double> out;
    for (const auto &c : clearance_)
      for (const double r : c->rates(k))
        out.push_back(r);
    return out;
  }
} // namespace clearjoint::mbd
