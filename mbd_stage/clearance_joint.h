// The spatial revolute joint with clearance (SPEC §4) as a force element between a bearing (a
// cylindrical cavity of radius R_B and length L_B closed by two end walls) in one body and a
// journal (radius R_J, length L_J) in another.
//
// Contacts, each with its own gap function g = δ for the integrator's root finding:
//  0 radial: for each end rim of the journal, X_k is its point farthest from the bearing axis
//    (Newton on the rim angle); rim k penetrates by δ_k = |P(X_k − C_B)| − R_B, P = I − b bᵀ,
//    along n_k = P(X_k − C_B)/|…| (= |e| − c_r when aligned). The law's δ is the deepest journal
//    point — the same quantity as the FE push beyond first touch — and F_n = F(δ).
//    The force acts at the material points X_k along n_k with weights w_k (w− + w+ = 1): all
//    on the deeper rim when tilted (rim contact), half on each when aligned (line contact:
//    resultant at mid-length), blended linearly while |δ+ − δ−| < ε = blend_width. As X_k is
//    the true maximiser, dδ_k/dt is the normal relative velocity of the material points there.
//    To make the force the exact gradient of the law's energy E(δ) everywhere, δ is the smooth
//    maximum δ = δ− + g(δ+ − δ−), g(d) = 0 (d ≤ −ε), (d + ε)²/(4ε) (|d| < ε), d (d ≥ ε), whose
//    partial derivatives are the weights; it differs from max(δ−, δ+) by at most ε/4
//    (0.125 nm for c_r = 0.5 mm).
//  1, 2 axial (+b, −b walls): u = (C_J − C_B)·b, h = (L_J/2)·cos θ + R_J·φ(sin θ), and
//    δ± = ±u + h − L_B/2 (a journal end face, or its rim when tilted, reaches a wall after the
//    axial clearance c_a = (L_B − L_J)/2 is used up). The force acts at the rim point farthest
//    along ±b; below sin θ = s0 (aligned_sine) the point moves to the face centre at fraction
//    sin θ/s0, and φ(s) = s²/(2 s0) there (s − s0/2 above) so that the force stays the
//    gradient of the energy (bias R_J·s0/2 ≈ 5 nm).
// Forces: normal F_n from the contact model, friction from CoulombFriction on the tangential
// relative velocity, applied equal and opposite at the same point P on both bodies (so the
// pair exerts no net moment about P, and each body gets its moment (P − r) × f).
#pragma once

#include "mbd_stage/contact_force_model.h"
#include "mbd_stage/friction.h"
#include "mbd_stage/kinematics.h"

#include <array>
#include <functional>
#include <limits>
#include <string>

namespace clearjoint::mbd
{
  struct ClearanceGeometry
  {
    double R_B = 0.0;  ///< [m] bearing radius
    double R_J = 0.0;  ///< [m] journal radius
    double L_B = 0.0;  ///< [m] bearing length (between its end walls)
    double L_J = 0.0;  ///< [m] journal length
    double c_r() const { return R_B - R_J; }          ///< [m] radial clearance
    double c_a() const { return 0.5 * (L_B - L_J); }  ///< [m] axial clearance per side
  };

  /// Evaluation of one contact (radial or an axial wall).
  struct ContactResult
  {
    double delta = 0.0;       ///< [m] penetration (negative: gap)
    double delta_dot = 0.0;   ///< [m/s] normal approach rate at P
    double F_n = 0.0;         ///< [N] normal force (0 when inactive)
    double F_el = 0.0;        ///< [N] its elastic part
    double F_t = 0.0;         ///< [N] friction force magnitude
    double E_el = 0.0;        ///< [J] elastic energy ∫F_el dδ (0 when inactive)
    double P_friction = 0.0;  ///< [W] power of friction (≤ 0)
    double P_damping = 0.0;   ///< [W] power of the damping term (≤ 0 when it dissipates)
    Vector3 point = Vector3::Zero();   ///< [m] resultant contact point (weighted), ground
    Vector3 normal = Vector3::Zero();  ///< [1] n (weighted), ground; journal penetrates along +n
    Vector3 force_on_journal = Vector3::Zero();  ///< [N] ground frame
  };

  struct ClearanceOutput
  {
    std::array<ContactResult, 3> contacts;  ///< radial, axial +, axial −
    double ecc_1 = 0.0, ecc_2 = 0.0;  ///< [m] journal-centre offset in the bearing frame (h1, h2)
    double theta = 0.0;               ///< [rad] misalignment of the two axes
  };

  /// Discrete contact state, switched only at roots of the gap functions.
  struct ContactState
  {
    bool active = false;
    double delta_dot_impact = 0.0;  ///< [m/s] δ̇⁻ recorded at onset
    unsigned long n_impacts = 0;
    /// Onsets whose recorded δ̇⁻ was below the model's floor (min_impact_velocity), so that the
    /// damping of that contact period used the floor instead.
    unsigned long n_impact_velocity_floored = 0;
  };

  class ClearanceJoint
  {
  public:
    static constexpr int n_contacts = 3;
    /// [1] sin θ below which an axial contact point moves from the rim toward the face centre
    /// (and R_J·sin θ in h is smoothed to match, see place()).
    static constexpr double aligned_sine = 1e-6;
    static constexpr double blend_fraction = 1e-6; ///< [1] blend_width = this × c_r

    /// Centres [m] and axes [1] in the ground frame at the initial configuration k0.
    ClearanceJoint(std::string name, int bearing_body, int journal_body,
                   const Vector3 &bearing_center_G, const Vector3 &bearing_axis_G,
                   const Vector3 &journal_center_G, const Vector3 &journal_axis_G,
                   ClearanceGeometry geometry, ContactForceModel radial, ContactForceModel axial,
                   CoulombFriction friction, const KinematicsView &k0);

    /// g_k = δ_k for k = radial, axial +, axial − [m].
    std::array<double, 3> gaps(const KinematicsView &k) const;
    /// Adds the generalised forces [f_G; n_B] of both bodies to Q (length 6·n_bodies) and
    /// fills `out` (if given).
    void apply(const KinematicsView &k, Eigen::VectorXd &Q, ClearanceOutput *out) const;
    /// Root functions for the integrator: δ_k for an inactive contact (onset when it rises
    /// through 0), δ_k + release_offset for an active one (release once δ_k < −release_offset,
    /// where the force is already 0). The offset keeps a root function from being exactly zero
    /// at the point where the integrator restarts after an event (SUNDIALS would stop with
    /// "root found at and very near t" when a contact grazes).
    std::array<double, 3> root_functions(const KinematicsView &k) const;
    double release_offset() const { return 1e-6 * geometry_.c_r(); }  ///< [m]
    /// Contact rates δ̇_k [m/s] (for onset and release decisions).
    std::array<double, 3> rates(const KinematicsView &k) const;
    /// An accepted state: the law-range counters and checks of the active contacts
    /// (ContactForceModel::observe_accepted; throws laws::LawRangeError under "error").
    /// With D > 0 [m] (the depth guard's depth_guard·c_r) it also sets each contact's allowance
    /// max(D, δ + D/2) that evaluations until the next accepted state should not exceed.
    void observe_accepted(const KinematicsView &k, double D = 0.0) const;
    /// The depth guard (docs/mbd.md §5) as a step bound [s] at an accepted state: (a) a
    /// contact approaching at δ̇ > 0 may not, at that rate, pass its allowance
    /// max(D, δ + D/2) within the step; (b) an active contact bounds the step by 1/ω, ω² =
    /// k/m_eff, with k the law's secant stiffness up to max(D, δ) (times its local exponent)
    /// and 1/m_eff the compliance of the two bodies at the contact point along n taken as free
    /// bodies — an upper bound of the constrained one, so ω is not underestimated. Without (b)
    /// the first explicit step after an onset (the natural period of the contact is ~0.1 ms
    /// here) produced trial stages several tenths of a millimetre deep.
    /// `compliance(body, P, n)` [1/kg] is 1/m + (r×n)ᵀJ⁻¹(r×n) of a body (0 for ground).
    /// Returns ∞ when nothing bounds the step.
    /// `accel` [m/s²] (optional): an estimate of δ̈ per contact (from the last accepted steps);
    /// a positive one turns (a) into δ + δ̇h + δ̈h²/2 ≤ allowance.
    double guard_step(const KinematicsView &k, double D,
                      const std::function<double(int, const Vector3 &, const Vector3 &)>
                        &compliance,
                      const double *accel = nullptr) const;
    /// [m] deepest radial and axial penetration of any evaluation, trial stages included
    /// (the depth guard keeps it below a fraction of the clearance; reported in the summary).
    double max_delta_any_stage(int contact) const { return max_delta_any_[contact]; }
    /// Evaluations (trial stages included) deeper than the allowance of the last accepted
    /// state: the explicit methods' guard is a step-size bound, not a rejection, so this counts
    /// where it fell short (0 on every shipped scene).
    long n_evaluations_beyond_allowance(int contact) const { return n_beyond_[contact]; }

    ContactState &state(int contact) { return states_[contact]; }
    const ContactState &state(int contact) const { return states_[contact]; }
    const std::string &name() const { return name_; }
    const ClearanceGeometry &geometry() const { return geometry_; }
    const ContactForceModel &radial_model() const { return radial_; }
    const ContactForceModel &axial_model() const { return axial_; }
    const CoulombFriction &friction() const { return friction_; }
    int bearing_body() const { return bearing_; }
    int journal_body() const { return journal_; }

  private:
    struct Placement
    {
      Vector3 C_B, b, C_J, j;
      double theta;
      std::array<double, 3> delta;
      // Up to two application points per contact (the two rims for the radial contact).
      std::array<std::array<Vector3, 2>, 3> point, normal;
      std::array<std::array<double, 2>, 3> weight;
    };
    Placement place(const KinematicsView &k) const;
    ContactResult evaluate_contact(const KinematicsView &k, int contact, const Placement &p,
                                   Eigen::VectorXd &Q) const;

    std::string name_;
    int bearing_, journal_;
    Vector3 s_B_, b_B_, s_J_, j_J_, h1_B_, h2_B_;  // body-frame markers
    ClearanceGeometry geometry_;
    ContactForceModel radial_, axial_;
    CoulombFriction friction_;
    std::array<ContactState, 3> states_;
    mutable std::array<double, 3> max_delta_any_{0.0, 0.0, 0.0};
    mutable std::array<double, 3> allowance_{std::numeric_limits<double>::infinity(),
                                             std::numeric_limits<double>::infinity(),
                                             std::numeric_limits<double>::infinity()};  // [m]
    mutable std::array<long, 3> n_beyond_{0, 0, 0};
  };
} // namespace clearjoint::mbd
