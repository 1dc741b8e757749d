// Hilber–Hughes–Taylor α time integration as Abaqus/Standard offers it (its three dynamic
// applications, issue 31 item 1): coefficients, predictor, Newmark updates of u, v, a, and the
// energy ledger whose residual is the scheme's numerical dissipation. Issue 12 item 1,
// FE_DESIGN §3.4 (TimeIntegrator: "the only place α, β, γ exist"). No deal.II: the vector
// functions are templates that work for Eigen vectors and for deal.II/Trilinos vectors (which
// have add(a, x) and operator*=); hht_test checks them on Eigen::VectorXd and on a vector type
// with deal.II's interface.
//
// Theory: H. M. Hilber, T. J. R. Hughes, R. L. Taylor, "Improved numerical dissipation for
// time integration algorithms in structural dynamics", Earthq. Eng. Struct. Dyn. 5 (1977)
// 283–292. For M a + C v + f_int(u) = f_ext(t) the step n → n+1 solves for u_{n+1}
//   r(u_{n+1}) = M a_{n+1} + (1+α)[C v_{n+1} + f_int(u_{n+1}) − f_ext,n+1]
//                           −   α [C v_n     + f_int(u_n)     − f_ext,n]     = 0,
// with the (generalised) Newmark relations
//   u_{n+1} = u_n + Δt v_n + Δt²[κ a_n + β a_{n+1}],
//   v_{n+1} = v_n + Δt[(1 − γ) a_n + γ a_{n+1}],
// κ = 1/2 − β for Newmark and HHT. The weighted load (1+α)f_{n+1} − α f_n is HHT's original
// form; f_ext(t_n + (1+α)Δt) (load_time()) is the same for loads linear in t.
//
// Abaqus/Standard's *DYNAMIC, APPLICATION= (Abaqus 2016 Keywords Reference, *DYNAMIC; Abaqus
// 2017 Analysis User's Guide, "Implicit dynamic analysis using direct integration"):
//   transient_fidelity   HHT-TF: α = −0.05, β = (1 − α)²/4 = 0.275625, γ = 1/2 − α = 0.55;
//                        Abaqus's default for models without contact.
//   moderate_dissipation HHT-MD: α = −0.41421, β = 0.5, γ = 0.91421 — the same formulas at
//                        α = 1 − √2 (used here, so that β = 1/2 exactly); Abaqus's default for
//                        models with contact, the paper's setting and ours.
//   quasi_static         backward Euler: v_{n+1} = v_n + Δt a_{n+1}, u_{n+1} = u_n + Δt v_{n+1},
//                        i.e. α = 0, β = γ = 1, κ = 0 in the form above (first order, every
//                        high-frequency mode annihilated: ρ∞ = 0).
// Abaqus accepts α ∈ [−1/2, 0] ("−0.333 provides maximum damping"). Why: the amplification
// matrix of ü + ω²u = 0 has, as ωΔt → ∞, a double principal root −(1+α)/(1−α) and a third, real
// root α/(1+α) (from (1+α)K u_{n+1} = αK u_n when inertia no longer counts). So
//   ρ∞ = max((1+α)/(1−α), |α|/(1+α)):
// 0.905 at α = −0.05; 0.5 at −1/3 (the minimum, all three roots meet); 1/√2 = 0.707 at
// HHT-MD's 1 − √2, where the principal pair has 0.414 = √2 − 1 but the third root dominates;
// 1 at −1/2 (stable, no longer asymptotically damping); > 1 below −1/2 (unstable).
// spectral_radius_limit() gives it for any (α, β, γ, κ) in closed form; hht_test checks it
// against the amplification matrix. Second order for every HHT α; backward Euler first order.
//
// Units: SI; t and Δt in s; u, v, a in the caller's units (m, m/s, m/s²).
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>

namespace clearjoint::fe
{
  /// ∂r/∂u_{n+1} = mass·M + damping·C + stiffness·K_t.
  struct MatrixCoefficients
  {
    double mass = 0.0;       ///< 1/(βΔt²) [1/s²]
    double damping = 0.0;    ///< (1+α)γ/(βΔt) [1/s]
    double stiffness = 1.0;  ///< 1+α [-]
  };

  namespace hht_detail
  {
    template <class V, class = void>
    struct has_add : std::false_type
    {};
    template <class V>
    struct has_add<V,
                   std::void_t<decltype(std::declval<V &>().add(1.0, std::declval<const V &>()))>>
      : std::true_type
    {};
    template <class V, class = void>
    struct has_dot : std::false_type
    {};
    template <class V>
    struct has_dot<V,
                   std::void_t<decltype(std::declval<const V &>().dot(std::declval<const V &>()))>>
      : std::true_type
    {};

    /// y += a x, with deal.II's add() where the vector has it (no temporaries).
    template <class V>
    void axpy(V &y, double a, const V &x)
    {
      if constexpr (has_add<V>::value)
        y.add(a, x);
      else
        y += a * x;
    }
    /// x · y (Eigen: dot(); deal.II: operator*, an MPI-global sum for distributed vectors).
    template <class V>
    double dot(const V &x, const V &y)
    {
      if constexpr (has_dot<V>::value)
        return x.dot(y);
      else
        return x * y;
    }
  }  // namespace hht_detail

  /// Abaqus/Standard's *DYNAMIC, APPLICATION=: the implicit operator and its parameters.
  enum class DynamicApplication
  {
    transient_fidelity,    ///< HHT-TF, α = −0.05
    moderate_dissipation,  ///< HHT-MD, α = 1 − √2 (the paper's, our default)
    quasi_static,          ///< backward Euler
  };

  /// The scene's word for an application ("transient_fidelity", …). Inline: the scene reader
  /// (which does not link this file's library) uses it too.
  inline const char *application_name(const DynamicApplication a)
  {
    switch (a)
      {
        case DynamicApplication::transient_fidelity:
          return "transient_fidelity";
        case DynamicApplication::moderate_dissipation:
          return "moderate_dissipation";
        case DynamicApplication::quasi_static:
          return "quasi_static";
      }
    return "?";
  }

  class HhtAlpha
  {
  public:
    /// Abaqus's range of α for HHT: [−1/2, 0] (unconditionally stable over it; ρ∞ above).
    static constexpr double alpha_min = -0.5;
    static constexpr double alpha_max = 0.0;
    /// HHT-TF's α: a little high-frequency damping (ρ∞ = 0.905).
    static constexpr double transient_fidelity_alpha = -0.05;
    /// HHT-MD's α = 1 − √2 (Abaqus prints −0.41421, β = 0.5, γ = 0.91421): ρ∞ = 1/√2.
    static constexpr double moderate_dissipation_alpha = -0.41421356237309504880;
    /// The impact study's default: moderate dissipation, as the paper ran it (Abaqus's default
    /// for models with contact).
    static constexpr DynamicApplication default_application =
      DynamicApplication::moderate_dissipation;

    /// The operator's form: HHT-α (κ = 1/2 − β) or backward Euler (κ = 0, β = γ = 1, α = 0).
    enum class Operator
    {
      hht,
      backward_euler,
    };

    /// HHT with β = (1 − α)²/4, γ = 1/2 − α (second order, unconditionally stable); α ∈
    /// [−1/2, 0], else an InputError naming `key_path` (e.g. "impact.alpha") and the range.
    explicit HhtAlpha(double alpha = moderate_dissipation_alpha,
                      const std::string &key_path = "impact.alpha", const std::string &file = "");

    /// HHT with explicit Newmark parameters (not a scene's keys: std::invalid_argument unless
    /// α ∈ [−1/2, 0], β > 0 and γ ≥ 1/2, all finite — necessary, not sufficient, for stability;
    /// spectral_radius_limit() tells the rest).
    HhtAlpha(double alpha, double beta, double gamma);

    /// Abaqus's application: its operator and parameters; an explicit α overrides the
    /// application's for HHT-TF and HHT-MD (as *DYNAMIC, ALPHA= does; β and γ then follow from
    /// it) and is an InputError on `alpha_key` for quasi_static (backward Euler has no α).
    static HhtAlpha for_application(DynamicApplication application,
                                    std::optional<double> alpha = std::nullopt,
                                    const std::string &alpha_key = "impact.alpha",
                                    const std::string &file = "");

    /// Backward Euler (Abaqus's quasi-static application).
    static HhtAlpha backward_euler();

    Operator op() const { return op_; }
    double alpha() const { return alpha_; }
    double beta() const { return beta_; }
    double gamma() const { return gamma_; }
    /// κ, the weight of Δt² a_n in u_{n+1}: 1/2 − β for HHT, 0 for backward Euler.
    double kappa() const { return kappa_; }

    /// Spectral radius of the amplification matrix of ü + ω²u = 0 as ωΔt → ∞, closed form for
    /// these (α, β, γ, κ): max(|α/(1+α)|, the moduli of the roots of λ² − Tλ + D) with
    /// T = 1 − (γ + κ)/β, D = (1 − γ − κ)/β (header comment; derived in docs/fe.md).
    double spectral_radius_limit() const;

    /// What the predictor assumes for the new step.
    enum class Predictor
    {
      same_displacement,  ///< u_{n+1} = u_n
      same_acceleration,  ///< a_{n+1} = a_n: u_{n+1} = u_n + Δt v_n + Δt²/2 a_n
      /// Newmark's ũ = u_n + Δt v_n + Δt² κ a_n (κ = ½ − β; 0 for backward Euler): the part of
      /// u_{n+1} known before a_{n+1} (u_{n+1} = ũ + βΔt² a_{n+1}); the impact study's step
      /// starts there and builds its known load c_m M ũ from it.
      newmark,
    };

    /// Weights of the new and old force states in r: (1+α) and −α.
    double weight_new() const { return 1.0 + alpha_; }
    double weight_old() const { return -alpha_; }
    /// t_{n+1+α} = t_n + (1+α)Δt, where a time-dependent load may be evaluated instead.
    double load_time(double t_n, double dt) const { return t_n + (1.0 + alpha_) * dt; }

    /// ∂r/∂u_{n+1}; dt must be finite and > 0 (std::invalid_argument otherwise: the scene
    /// validator owns the user-facing check of time.time_step).
    MatrixCoefficients coefficients(double dt) const;

    /// Displacement predictor u_{n+1} from the converged state n.
    template <class V>
    void predict(const V &u_n, const V &v_n, const V &a_n, double dt, V &u_new,
                 Predictor p = Predictor::same_acceleration) const
    {
      check_dt(dt);
      u_new = u_n;
      if (p == Predictor::same_acceleration)
        {
          hht_detail::axpy(u_new, dt, v_n);
          hht_detail::axpy(u_new, 0.5 * dt * dt, a_n);
        }
      else if (p == Predictor::newmark)
        {
          hht_detail::axpy(u_new, dt, v_n);
          hht_detail::axpy(u_new, dt * dt * kappa_, a_n);
        }
    }

    /// Newmark relations: v_{n+1}, a_{n+1} from u_{n+1} and the converged state n. The output
    /// vectors must be distinct objects from the inputs.
    template <class V>
    void update_rates(const V &u_new, const V &u_n, const V &v_n, const V &a_n, double dt, V &v_new,
                      V &a_new) const
    {
      check_dt(dt);
      const double bdt2 = beta_ * dt * dt;
      a_new = u_new;
      hht_detail::axpy(a_new, -1.0, u_n);
      a_new *= 1.0 / bdt2;
      hht_detail::axpy(a_new, -1.0 / (beta_ * dt), v_n);
      hht_detail::axpy(a_new, -kappa_ / beta_, a_n);
      v_new = v_n;
      hht_detail::axpy(v_new, dt * (1.0 - gamma_), a_n);
      hht_detail::axpy(v_new, dt * gamma_, a_new);
    }

  private:
    HhtAlpha(Operator op, double alpha, double beta, double gamma, double kappa);
    static void check_dt(double dt);
    Operator op_ = Operator::hht;
    double alpha_, beta_, gamma_, kappa_;
  };

  /// Work of a force over one step by the trapezoidal rule, (u_{n+1} − u_n)·(f_n + f_{n+1})/2.
  /// For a linear elastic f_int = K u it equals the change of ½uᵀKu exactly.
  template <class V>
  double trapezoidal_work(const V &u_new, const V &u_n, const V &f_new, const V &f_n)
  {
    V du = u_new;
    hht_detail::axpy(du, -1.0, u_n);
    return 0.5 * (hht_detail::dot(du, f_new) + hht_detail::dot(du, f_n));
  }

  /// Energy bookkeeping of an implicit dynamic run (issue 12 item 2: kinetic, strain, work of
  /// the contact forces, HHT's numerical dissipation). Per converged step the caller adds the
  /// new kinetic energy ½vᵀMv and the trapezoidal works of the internal forces (f_int: strain
  /// energy, plus plastic work for J2) and of the forces applied to the bodies (loads and
  /// contact, each sign as it acts on the body). What is left,
  ///     D_step = W_applied − ΔT − W_internal,
  /// is the energy the time integrator removed: exactly 0 (round-off) for α = 0 on a linear
  /// system, ≥ 0 on average for α < 0, and ≥ 0 in every step for backward Euler on a linear
  /// free system (ΔE = −½(|Δv|²_M + |Δu|²_K) there). The balance
  /// T + W_internal + D = T_0 + W_applied then closes by construction; its content is D.
  struct EnergyLedger
  {
    double kinetic_initial = 0.0;  ///< T_0 [J]
    double kinetic = 0.0;          ///< T_{n+1} [J]
    double work_internal = 0.0;    ///< Σ trapezoidal work of f_int [J]
    double work_applied = 0.0;     ///< Σ trapezoidal work of loads and contact forces [J]
    double dissipation = 0.0;      ///< Σ D_step, the numerical dissipation [J]

    void start(double T0);
    /// Adds one converged step; returns its D_step [J].
    double add_step(double T_new, double dW_internal, double dW_applied);
  };
}  // namespace clearjoint::fe
