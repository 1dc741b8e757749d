#include "mbd_stage/output_rows.h"

#include "common/units.h"

#include <cmath>

namespace clearjoint::mbd
{
  namespace
  {
    /// Rotation angle [rad] of e relative to e0 about the unit axis a (ground frame), in
    /// (−π, π].
    double relative_angle(const Vector4 &e, const Vector4 &e0, const Vector3 &a)
    {
      const Eigen::Quaterniond q(e[0], e[1], e[2], e[3]), q0(e0[0], e0[1], e0[2], e0[3]);
      const Eigen::Quaterniond r = q.normalized() * q0.normalized().conjugate();
      return std::remainder(2.0 * std::atan2(r.vec().dot(a), r.w()), 2.0 * units::pi);
    }

    Vector4 initial_euler_parameters(const MultibodySystem &sys, const int body)
    {
      return body >= 0 ? sys.initial_state().segment<4>(7 * body + 3) : Vector4(1, 0, 0, 0);
    }

    Vector3 crank_axis(const Scene &scene)
    {
      return scene.crank ? scene.crank->axis : Vector3(1, 0, 0);
    }
  } // namespace

  OutputColumns make_output_columns(const Scene &scene, const MultibodySystem &sys)
  {
    OutputColumns out;
    const auto col = [&](const std::string &n, const std::string &u) {
      out.names.push_back(n);
      out.units.push_back(u);
    };
    col("t", "s");
    if (scene.slider)
    {
      out.slider = sys.body_index(scene.slider->body);
      col("slider_position", "m");
      col("slider_velocity", "m/s");
      col("slider_acceleration", "m/s^2");
    }
    if (scene.crank)
    {
      out.crank = sys.body_index(scene.crank->body);
      col("crank_angle", "rad");
      col("crank_rate", "rad/s");
    }
    for (const auto &cj : sys.clearance_joints())
    {
      const std::string p = cj->name() + "_";
      col(p + "ecc_1", "m");
      col(p + "ecc_2", "m");
      col(p + "eccentricity", "m");
      col(p + "theta", "rad");
      for (int c = 0; c < ClearanceJoint::n_contacts; ++c)
      {
        const std::string q = p + contact_names[c] + "_";
        col(q + "delta", "m");
        col(q + "delta_dot", "m/s");
        col(q + "F_n", "N");
        col(q + "F_t", "N");
      }
    }
    for (std::size_t j = 0; j < sys.joints().size(); ++j)
    {
      const Joint &J = sys.joints()[j];
      if (J.body_i() == ground_index || J.body_j() == ground_index)
      {
        out.ground_joints.push_back(static_cast<int>(j));
        for (const char *a : {"_Fx", "_Fy", "_Fz"})
          col(J.name() + a, "N");
      }
    }
    for (const char *n : {"E_kin", "E_pot", "E_el", "E_total", "W_friction", "W_damping",
                          "W_drivers", "energy_error"})
      col(n, "J");
    col("phi_max", "m|1");
    col("phi_dot_max", "m/s|1/s");
    col("euler_norm_error", "1");
    return out;
  }

  CrankAngle::CrankAngle(const Vector4 &e0, const Vector3 &axis)
    : e0_(e0)
    , axis_(axis)
  {
  }

  double CrankAngle::operator()(const Vector4 &e)
  {
    const double ang = relative_angle(e, e0_, axis_);
    if (ang - previous_ > units::pi)
      turns_ -= 1.0;
    else if (ang - previous_ < -units::pi)
      turns_ += 1.0;
    previous_ = ang;
    return ang + 2.0 * units::pi * turns_;
  }

  OutputRows::OutputRows(const Scene &scene, const MultibodySystem &sys,
                         const OutputColumns &columns)
    : scene_(scene)
    , columns_(columns)
    , crank_angle_(initial_euler_parameters(sys, columns.crank), crank_axis(scene))
  {
  }

  void OutputRows::append(const double t, const SystemEvaluation &ev, SimulationResult &res)
  {
    std::vector<double> row;
    row.reserve(columns_.names.size());
    row.push_back(t);
    if (const int slider = columns_.slider; slider >= 0)
    {
      const Vector3 &a = scene_.slider->axis;
      row.push_back(ev.bodies[slider].r.dot(a));
      row.push_back(ev.bodies[slider].v.dot(a));
      row.push_back(ev.acceleration_G(slider).dot(a));
    }
    if (const int crank = columns_.crank; crank >= 0)
    {
      row.push_back(crank_angle_(ev.bodies[crank].e));
      row.push_back(ev.bodies[crank].w_G().dot(scene_.crank->axis));
    }
    for (const ClearanceOutput &o : ev.clearance)
    {
      row.push_back(o.ecc_1);
      row.push_back(o.ecc_2);
      row.push_back(std::hypot(o.ecc_1, o.ecc_2));
      row.push_back(o.theta);
      for (const ContactResult &r : o.contacts)
      {
        row.push_back(r.delta);
        row.push_back(r.delta_dot);
        row.push_back(r.F_n);
        row.push_back(r.F_t);
      }
    }
    for (const int j : columns_.ground_joints)
      for (int a = 0; a < 3; ++a)
        row.push_back(ev.joint_force_on_j[j][a]);
    // Energy balance: E − W − E0 stays 0 up to the integration error (docs/mbd.md).
    const double E = ev.E_kin + ev.E_pot + ev.E_el;
    if (!have_E0_)
    {
      res.E0 = E;
      have_E0_ = true;
    }
    const double W = ev.W_friction + ev.W_damping + ev.W_drivers;
    const double err = E - W - res.E0;
    for (const double v : {ev.E_kin, ev.E_pot, ev.E_el, E, ev.W_friction, ev.W_damping,
                           ev.W_drivers, err})
      row.push_back(v);
    row.push_back(ev.phi_norm);
    row.push_back(ev.phi_dot_norm);
    row.push_back(ev.euler_norm_error);
    res.rows.push_back(std::move(row));
    res.max_relative_energy_error =
      std::max(res.max_relative_energy_error, std::abs(err) / std::max(std::abs(res.E0), 1e-300));
    res.max_energy_gain = std::max(res.max_energy_gain, E - res.E0 - ev.W_drivers);
    res.max_phi = std::max(res.max_phi, ev.phi_norm);
    res.max_euler_norm_error = std::max(res.max_euler_norm_error, ev.euler_norm_error);
  }
} // namespace clearjoint::mbd
