// The multibody system in absolute coordinates (Nikravesh; the paper's §4 formulation):
// per body the state is r (3, m), e (4 Euler parameters), v (3, m/s), ω' (3, rad/s, body
// frame); the equations of motion with Lagrange multipliers
//     [ M   Dᵀ ] [ u̇ ]   [ Q                     ]      M = diag(m·I, J')
//     [ D   0  ] [ −λ] = [ γ − 2α·Φ̇ − β²·Φ        ]      Q = [f_G ; n' − ω'×J'ω']
// are solved through the Schur complement D·M⁻¹·Dᵀ each time the right-hand side is evaluated
// (Baumgarte stabilisation with α, β in 1/s). Redundant constraints (e.g. the planar
// slider–crank with four ideal joints in 3D) are detected at set-up (pivoted QR) and dropped:
// the accelerations are solved on the independent rows, the motion is unique, the reactions
// are those of the independent rows (as Adams does after removing redundant constraints), and
// a warning says so.
// Extra states integrate the work of friction, of damping (per clearance joint) and of each
// driver, so the energy balance E_kin + E_pot + E_el − W = E(0) can be checked.
#pragma once

#include "mbd_stage/clearance_joint.h"
#include "mbd_stage/joint.h"

#include <Eigen/Cholesky>

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace clearjoint::mbd
{
  struct BodyProperties
  {
    std::string name;
    double mass = 0.0;                  ///< [kg]
    Vector3 inertia = Vector3::Zero();  ///< [kg·m²] principal moments about the body axes
  };

  struct Stabilization
  {
    double alpha = 0.0;       ///< [1/s] Baumgarte velocity gain
    double beta = 0.0;        ///< [1/s] Baumgarte position gain
    double euler_gain = 0.0;  ///< [1/s] pull of ‖e‖ back to 1 (does not affect A(e))
  };

  /// Everything evaluated at one (t, y), for outputs.
  struct SystemEvaluation
  {
    double t = 0.0;
    std::vector<BodyKinematics> bodies;
    Eigen::VectorXd u_dot;   ///< [m/s², rad/s²] [v̇_G, ω̇'_B] per body
    Eigen::VectorXd lambda;  ///< multipliers, one per constraint row
    std::vector<ClearanceOutput> clearance;
    std::vector<Vector3> joint_force_on_j;  ///< [N] per joint, force on body_j, ground frame
    double phi_norm = 0.0;      ///< [m or 1] max |Φ_k|
    double phi_dot_norm = 0.0;  ///< max |Φ̇_k|
    double euler_norm_error = 0.0;  ///< [1] max |‖e‖ − 1|
    double E_kin = 0.0, E_pot = 0.0, E_el = 0.0;  ///< [J]
    double W_friction = 0.0, W_damping = 0.0, W_drivers = 0.0;  ///< [J] work done (≤ 0: lost)
    Vector3 acceleration_G(int body) const { return u_dot.segment<3>(6 * body); }
  };

  class MultibodySystem
  {
  public:
    MultibodySystem() = default;
    MultibodySystem(const MultibodySystem &) = delete;

    int add_body(const BodyProperties &props, const BodyKinematics &initial);
    /// Joints and clearance joints are defined at the initial configuration of the bodies.
    void add_joint(std::string name, JointType type, int body_i, int body_j,
                   const Vector3 &point_G, const Vector3 &axis_G);
    void add_driver(std::string name, int joint, double speed);
    void add_clearance_joint(std::unique_ptr<ClearanceJoint> joint);
    void set_gravity(const Vector3 &g) { gravity_ = g; }  ///< [m/s²]
    void set_stabilization(const Stabilization &s) { stab_ = s; }

    /// Call once after adding everything: checks constraint rank, projects the initial
    /// velocities onto D·u = −Φ_t (minimum kinetic-energy change), returns the size of that
    /// correction [m/s, rad/s scaled by M] and stores the initial state.
    double finalize(double t0);

    int n_bodies() const { return static_cast<int>(bodies_.size()); }
    int n_states() const;
    int n_constraints() const { return n_rows_; }
    int n_redundant_constraints() const { return n_redundant_; }
    int n_gaps() const { return 3 * static_cast<int>(clearance_.size()); }
    const Eigen::VectorXd &initial_state() const { return y0_; }
    const std::vector<BodyProperties> &bodies() const { return bodies_; }
    const std::deque<Joint> &joints() const { return joints_; }
    const std::vector<Driver> &drivers() const { return drivers_; }
    std::vector<std::unique_ptr<ClearanceJoint>> &clearance_joints() { return clearance_; }
    const std::vector<std::unique_ptr<ClearanceJoint>> &clearance_joints() const
    {
      return clearance_;
    }
    int body_index(const std::string &name) const;  ///< ground_index for "ground", −2 if none
    /// Kinematics of the initial configuration (before finalize's velocity correction).
    KinematicsView initial_view() const { return KinematicsView(&initial_); }
    double initial_velocity_correction() const { return velocity_correction_; }

    /// ẏ = f(t, y); fills `eval` when given. Throws NumericalError on a non-finite result.
    void rhs(double t, const double *y, double *ydot, SystemEvaluation *eval = nullptr) const;
    /// Root functions of every clearance-joint contact (3 per joint), [m]: see
    /// ClearanceJoint::root_functions.
    void gaps(const double *y, double *g) const;
    /// Radial normal force [N] of every clearance joint (cheap: no constraint solve).
    std::vector<double> radial_forces(const double *y) const;
    /// An accepted state y: law-range counters of every clearance joint (see
    /// ClearanceJoint::observe_accepted).
    /// guard_fraction > 0: the depth guard's fraction of c_r, for the allowance check.
    void observe_accepted(const double *y, double guard_fraction = 0.0) const;
    /// The depth guard's step bound [s] at an accepted state y, with allowance D = fraction·c_r
    /// per clearance joint (ClearanceJoint::guard_step); ∞ if nothing bounds the step.
    /// `accel`: optional δ̈ estimates, one per contact (n_gaps()).
    double guard_step(const double *y, double fraction, const double *accel = nullptr) const;
    /// δ̇_k of every contact [m/s].
    std::vector<double> contact_rates(const double *y) const;
    /// Unpacks y into per-body kinematics.
    std::vector<BodyKinematics> unpack(const double *y) const;

  private:
    void constraint_rows(const KinematicsView &k, double t, std::vector<ConstraintRow> &rows) const;
    void unpack_into(const double *y, std::vector<BodyKinematics> &k) const;

    /// Buffers rhs() reuses between calls (one system is never evaluated from two threads):
    /// allocating them per call cost ~10 % of a run.
    struct Workspace
    {
      std::vector<BodyKinematics> kin;
      std::vector<ConstraintRow> rows;
      std::vector<double> P_fric, P_damp;
      Eigen::VectorXd Q, m_inv, u, u_dot, lambda, phi, phi_dot, rhs_c, b, lambda_sub;
      Eigen::MatrixXd D, DM, S, S_full, D_sub;
      Eigen::LLT<Eigen::MatrixXd> llt;
    };
    mutable std::shared_ptr<Workspace> ws_ = std::make_shared<Workspace>();

    // The steps of rhs(), in order; each reads and writes the workspace W (no allocation once
    // its buffers have their sizes).
    /// Q = gravity and gyroscopic terms −ω'×J'ω' per body; M⁻¹ and u = [v, ω'] from W.kin.
    void assemble_applied_forces(Workspace &W) const;
    /// Adds each clearance joint's contact, damping and friction forces to Q; their powers
    /// into P_fric, P_damp [W]; its contacts into eval->clearance when eval is given.
    void add_clearance_joint_forces(const KinematicsView &k, Workspace &W,
                                    SystemEvaluation *eval) const;
    /// From the constraint rows W.rows: D, Φ, Φ̇ and the stabilised right side
    /// γ − 2αΦ̇ − β²Φ of each.
    void assemble_constraint_equations(Workspace &W) const;
    /// S = D M⁻¹ Dᵀ (lower triangle) in S_full, and on the independent rows in S when
    /// constraints are redundant.
    void assemble_schur_complement(int nc, Workspace &W) const;
    /// λ from S·λ = γ' − D·M⁻¹Q (Cholesky, on the independent rows when redundant), and
    /// u̇ += M⁻¹Dᵀλ. Throws NumericalError when S is not positive definite.
    void solve_constraint_forces(double t, int nc, Workspace &W) const;
    /// ẏ: ṙ = v, ė (with the pull of ‖e‖ to 1), u̇, the friction and damping powers of each
    /// clearance joint and each driver's power.
    void write_state_derivative(int nc, const Workspace &W, double *ydot) const;
    /// Throws NumericalError naming the first non-finite component of ẏ.
    void check_finite(double t, const double *ydot) const;
    /// Energies (kinetic, potential, elastic), ‖e‖ error and the integrated work in y.
    void record_energies_and_work(const double *y, const Workspace &W,
                                  SystemEvaluation &eval) const;
    /// The force on body_j of every joint, from its rows of D and λ.
    void record_joint_reactions(const Workspace &W, SystemEvaluation &eval) const;
    /// Rows of D kept when constraints are redundant (chosen at finalize by a pivoted QR of
    /// Dᵀ): the accelerations are solved on this independent subset (Cholesky), as Adams
    /// does after removing redundant constraints.
    std::vector<int> independent_rows_;
    /// Per moving body, the constraint rows that involve it (set at finalize from the joints'
    /// bodies): S = D M⁻¹ Dᵀ is assembled body by body from these 6-column blocks, ~4× fewer
    /// operations than the dense product for the slider–crank.
    std::vector<std::vector<int>> rows_of_body_;

    std::vector<BodyProperties> bodies_;
    std::vector<BodyKinematics> initial_;
    std::deque<Joint> joints_;  // deque: drivers keep references to joints
    std::vector<Driver> drivers_;
    std::vector<std::unique_ptr<ClearanceJoint>> clearance_;
    Vector3 gravity_ = Vector3::Zero();
    Stabilization stab_;
    int n_rows_ = 0, n_redundant_ = 0;
    double velocity_correction_ = 0.0;
    Eigen::VectorXd y0_;
  };
} // namespace clearjoint::mbd
