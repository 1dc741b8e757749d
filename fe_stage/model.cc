// Model's own functions (model.h): the study's run chosen in one place, the mesh and all that
// depends on it (with the linear solver's choice), the steppers over the model's parts, the
// start from rest and the rollback of a failed attempt, the elastoplastic bodies' start and
// their tangent with the contact nodes' share of its load.
#include "fe_stage/model.h"

#include "fe_stage/contact/contact_node.h"
#include "fe_stage/core/restart_values.h"
#include "fe_stage/core/scoped_timer.h"
#include "fe_stage/solve/impact_run.h"
#include "fe_stage/solve/quasi_static_run.h"
#include "fe_stage/solve/rolling_run.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <set>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// The linear solver's choice for a system of `n_dofs` DoFs: solver.linear, and with
    /// automatic a direct solve below solver.direct_below_dofs.
    bool direct_solve(const Solver &solver, const types::global_dof_index n_dofs)
    {
      switch (solver.linear)
        {
          case LinearSolver::direct:
            return true;
          case LinearSolver::cg_amg:
            return false;
          case LinearSolver::automatic:
            return n_dofs < solver.direct_below_dofs;
        }
      return false;
    }
  }  // namespace

  RunResult Model::run()
  {
    // the study chosen once (its plan)
    if (plan_.dynamic)
      return ImpactRun(*this, {scene_, plan_, options_, bodies_, dofs_, state_, fields_, comm_})
        .run();
    if (plan_.rolling)
      return RollingRun(*this, {scene_, plan_, options_, bodies_, dofs_, contact_, state_, frame_,
                                fields_, comm_})
        .run();
    return QuasiStaticRun(*this, {scene_, options_, bodies_, dofs_, contact_, system_, solver_,
                                  contact_solve_, state_, fields_, comm_})
      .run();
  }

  void Model::build_mesh()
  {
    bodies_.build();
    prepare_mesh();
  }

  /// Kelly's estimator: the jumps of the stress across interior faces, in both bodies; p4est
  /// keeps the 2:1 balance.
  void Model::refine_mesh()
  {
    Vector<float> indicator(bodies_.triangulation().n_active_cells());
    KellyErrorEstimator<dim>::estimate(bodies_.mapping(), dofs_.handler(),
                                       QGauss<dim - 1>(dofs_.fe().degree + 1), {}, state_.u(),
                                       indicator, ComponentMask(), nullptr,
                                       numbers::invalid_unsigned_int,
                                       bodies_.triangulation().locally_owned_subdomain());
    bodies_.refine_largest(indicator, scene_.mesh.adaptive_fraction);
    prepare_mesh();
  }

  void Model::free_journal()
  {
    journal_driven_ = false;
    prepare_mesh();
  }

  SpinStepper Model::spin_stepper(const rolling::Motion &motion, const double t_end,
                                  const unsigned int n_steps, const unsigned int max_cuts,
                                  const double inertia)
  {
    return SpinStepper(*this, scene_, state_, frame_, comm_, motion, t_end, n_steps, max_cuts,
                       inertia);
  }

  /// One state of the rolling bearing for the journal's spin now (SpinProblem): the material
  /// Newton iteration, then the journal's torque.
  RollingSolve Model::solve_rolling_state(const double delta)
  {
    RollingSolve rs;
    const MaterialSolve m = newton_.solve(delta, scene_.rolling.max_newton_iterations);
    rs.record = m.record;
    rs.newton_iterations = m.newton_iterations;
    rs.line_search_steps = m.line_search_steps;
    rs.contact_iterations = m.contact_iterations;
    rs.linear_iterations = m.linear_iterations;
    rs.torque_journal = journal_torque();
    return rs;
  }

  MaterialIteration Model::material_iteration(const double delta, const bool line_search,
                                              TurnSensitivity *sensitivity)
  {
    if (!sensitivity)
      return newton_.iterate(delta, line_search);
    return newton_.iterate(delta, line_search, [&](const TrilinosWrappers::MPI::Vector &u_start) {
      measure_turn_sensitivity(delta, u_start, *sensitivity);
    });
  }

  void Model::measure_turn_sensitivity(const double delta,
                                       const TrilinosWrappers::MPI::Vector &u_start,
                                       TurnSensitivity &s)
  {
    // what the solve left, to be put back: u, the nodal forces, the nodes (their frame-
    // dependent gaps and normals, forces and slips) and the partners' turn
    const double torque = journal_torque();
    const TrilinosWrappers::MPI::Vector u_solved = state_.u_owned();
    const TrilinosWrappers::MPI::Vector forces = state_.forces();
    const std::vector<ContactNode> nodes = contact_.nodes();
    const JournalFrame frame = frame_;
    // the obstacle linearised about the iteration's start, as the solve's was; the solve
    // itself starts from the solution at ψ (the answer differs from it by the turn's effect)
    auto put_back = [&] {
      frame_ = frame;
      contact_.nodes() = nodes;
      state_.set(u_solved);
      state_.forces() = forces;
    };
    state_.set(u_start);
    frame_.delta_psi += s.d_psi;
    try
      {
        s.linear_iterations = contact_solve_.solve_with_sets_kept(delta, u_solved);
      }
    catch (...)
      {
        put_back();  // (a failed solve: the caller restores the step's start anyway)
        throw;
      }
    s.d_torque = journal_torque() - torque;
    s.du = state_.u_owned();
    s.du -= u_solved;
    put_back();
  }

  double Model::journal_torque() const
  {
    // the contact's torque on the journal about its axis: the force on the journal is −t at
    // its surface point c' + R_J n (z-moments are the same in every frame turned about z)
    // (only the friction force has a moment: the normal n passes through the journal's axis)
    // (the deformable journal: the arm from its axis to the bore node where it is now)
    double torque = 0.0;
    for (const auto &cn : contact_.nodes())
      if (contact_.friction() && cn.owned && cn.active)
        {
          const Tensor<1, dim> t = tangential(contact_.traction(cn), cn.n);
          Tensor<1, dim> arm = scene_.geometry.R_J() * cn.n;
          if (plan_.journal_turns_deformable())
            for (unsigned int c = 0; c + 1 < dim; ++c)
              arm[c] = cn.X[c] + state_.u()[cn.dofs[c]] - frame_.centre[c];
          torque -= arm[0] * t[1] - arm[1] * t[0];
        }
    return bodies_.symmetry_factor() * Utilities::MPI::sum(torque, comm_);
  }

  HhtStepper Model::hht_stepper(const HhtAlpha &hht, const double dt_nominal,
                                const unsigned int max_cuts, const double m_J,
                                const double velocity, const bool deformable_journal)
  {
    return HhtStepper(*this, {scene_, bodies_, dofs_, system_, state_, contact_, comm_}, hht,
                      dt_nominal, max_cuts, m_J, velocity, deformable_journal);
  }

  QuasiStaticStepper Model::quasi_static_stepper()
  {
    return QuasiStaticStepper(*this, {scene_, dofs_, state_, contact_, newton_, comm_,
                                      pattern_.finite_sliding()});
  }

  void Model::start_from_rest()
  {
    state_.set_zero();
    newton_.forget_tangent();
    for (auto &cn : contact_.nodes())
      {
        cn.active = false;
        cn.stick = true;
        cn.relative = cn.relative_converged = Tensor<1, dim>();
        cn.obstacle_u = cn.obstacle_u_converged = Tensor<1, dim>();
      }
  }

  void Model::restore_state(const Snapshot &s)
  {
    newton_.forget_tangent();
    state_.u_owned() = s.u;
    state_.publish();
    contact_.nodes() = s.nodes;
    pattern_.pair_restored(s.u, s.sliding_rebuilds);
  }

  void Model::write_restart(RestartWriter &out) const
  {
    out.section("displacement");
    put_owned(out, state_.u_owned());
    out.section("material history");
    material_.law().write_history(out);
    out.section("contact nodes");
    out.put<std::uint64_t>(contact_.nodes().size());
    for (const auto &cn : contact_.nodes())
      {
        out.put(cn.dofs[0]);
        out.put(cn.active);
        out.put(cn.stick);
        out.put(cn.lambda);
        for (const auto *t :
             {&cn.relative, &cn.relative_converged, &cn.obstacle_u, &cn.obstacle_u_converged})
          put_tensor(out, *t);
      }
  }

  /// The nodes are matched by their first DoF: a deformable journal's search rebuilds the
  /// node list at every step, so a node the restart file has and this mesh's first pairing
  /// has not starts open (the next step's search pairs it again).
  void Model::read_restart(RestartReader &in)
  {
    newton_.forget_tangent();
    in.section("displacement");
    get_owned(in, state_.u_owned(), "the displacement");
    state_.publish();
    in.section("material history");
    material_.law().read_history(in);
    in.section("contact nodes");
    std::map<types::global_dof_index, ContactNode *> by_key;
    for (auto &cn : contact_.nodes())
      by_key[cn.dofs[0]] = &cn;
    const auto n = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n; ++k)
      {
        const auto key = in.get<types::global_dof_index>();
        ContactNode scratch;
        const auto it = by_key.find(key);
        ContactNode &cn = it != by_key.end() ? *it->second : scratch;
        cn.active = in.get<bool>() && cn.candidate;
        cn.stick = in.get<bool>();
        cn.lambda = in.get<double>();
        for (auto *t :
             {&cn.relative, &cn.relative_converged, &cn.obstacle_u, &cn.obstacle_u_converged})
          *t = get_tensor(in);
      }
  }

  /// The mesh the study runs on (DoFs, cells, symmetry factor, h_min) and the set-up time.
  void Model::record_mesh(RunResult &result) const
  {
    result.n_dofs = dofs_.handler().n_dofs();
    result.n_cells = bodies_.triangulation().n_global_active_cells();
    result.symmetry_factor = bodies_.symmetry_factor();
    result.h_min = bodies_.h_min();
    result.setup_time = elapsed();
  }

  /// Everything that depends on the mesh: DoFs, constraints, contact pairing, matrices.
  void Model::prepare_mesh(const TrilinosWrappers::MPI::Vector *search_displacement)
  {
    solver_.invalidate();  // its AMG was built for the previous mesh's matrix
    dofs_.distribute(journal_driven_);
    pattern_.find_contact_nodes(search_displacement);
    newton_.forget_tangent();  // the matrices are made again
    pattern_.make_matrices();
    state_.reinit(dofs_, comm_);
    solver_.configure(direct_solve(scene_.solver, dofs_.handler().n_dofs()),
                      scene_.solver.max_linear_iterations);
    system_.assemble_static(material_.law().elastic(), massless_dofs(system_.kind()));
    contact_solve_.compute_nodal_weights();
  }

  std::set<types::global_dof_index> Model::massless_dofs(const Assembler::Operator kind) const
  {
    // the contact surface's DoFs (every node, candidate or watched)
    std::set<types::global_dof_index> surface;
    if (kind == Assembler::Operator::dynamic && scene_.impact.mass == Impact::Mass::redistributed)
      for (const auto &cn : contact_.nodes())
        surface.insert(cn.dofs.begin(), cn.dofs.end());
    return surface;
  }

  void Model::init_plasticity()
  {
    material_.init_history(system_.n_q_points());
    system_.use_tangent();
  }

  /// The tangent and its load at the current displacement (small or finite kinematics),
  /// then the contact nodes' share of the load (MaterialProblem).
  unsigned int Model::assemble_plastic()
  {
    unsigned int n_plastic_points = 0;
    {
      const ScopedTimer timer = contact_solve_.assembly_timer();
      n_plastic_points = scene_.material.kinematics == Material::Kinematics::finite ?
                           system_.assemble_finite_tangent(material_.law(), state_.u()) :
                           system_.assemble_tangent(material_.law(), state_.u());
    }
    set_contact_load_offsets();
    return n_plastic_points;
  }

  void Model::set_dynamic_operator(const MatrixCoefficients &c)
  {
    system_.set_dynamic_operator(c.mass, c.stiffness, material_.law().elastic(),
                                 massless_dofs(Assembler::Operator::dynamic));
    solver_.invalidate();  // its AMG was built for the previous operator
  }

}  // namespace clearjoint::fe::detail
