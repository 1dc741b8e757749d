// The rolling study (paper §3.4, docs/fe.md "Rolling study"): time steps over the push ramp.
// Each step: the bearing turned to φ = ω_B t (its co-rotating frame: the mesh stays, the rigid
// journal's axis turns round it), the journal pushed to δ(t), and the journal's spin rate γ̇
// found from its torque balance (SpinStepper, solve/spin_stepper.h). Every evaluation of the
// journal's torque is a state of the elastoplastic bodies (solve_rolling_state below: material
// Newton iterations, each an active-set contact solve with Coulomb friction). What this file
// keeps: the study's set-up, what each converged step records (forces, torques, energies, the
// paper's Eqs. 4–8), and the end state (strain profile, slip stages).
#include "fe_stage/core/contact_model.h"
#include "fe_stage/solve/spin_stepper.h"

#include <cmath>

namespace clearjoint::fe::detail
{
  ContactModel::RollingSolve ContactModel::solve_rolling_state(const double delta)
  {
    RollingSolve rs;
    // Material Newton converged when the correction is below 1e-7 of the push (δ_max = 1 mm:
    // 0.1 nm), far below the discretisation error; quadratic convergence reaches it in a few
    // iterations once the plastic zone and the active set have settled.
    const double tolerance = 1e-7 * scene_.loading.delta_max;
    const unsigned int max_it = scene_.rolling.max_newton_iterations;
    TrilinosWrappers::MPI::Vector before(dofs_.owned(), comm_);
    double last_correction = 0.0;
    unsigned int growths = 0;
    for (unsigned int k = 0;; ++k)
      {
        const PlasticAssembly pa = assemble_plastic();
        before = solution_owned_;
        rs.record = solve_increment(delta);
        rs.contact_iterations += rs.record.contact_iterations;
        rs.linear_iterations += rs.record.linear_iterations;
        rs.newton_iterations = k + 1;
        before -= solution_owned_;
        const double correction = before.linfty_norm();
        if (log::level() <= log::Level::debug && rank_ == 0)
          log::debug("  material Newton iteration " + std::to_string(k + 1) + ": correction " +
                     format_value(correction) + " m, " + std::to_string(pa.n_plastic_points) +
                     " quadrature points yielding, contact force " + format_value(rs.record.force) +
                     " N");
        if (!std::isfinite(correction))
          throw StepFailure{"non-finite displacement in the material Newton iteration"};
        if (correction <= tolerance)
          break;
        // diverging (the correction grew in each of the last three iterations): give up at
        // once, so that the step is cut instead of running out its iterations
        growths = k > 0 && correction > last_correction ? growths + 1 : 0;
        last_correction = correction;
        if (growths >= 3)
          throw StepFailure{"the material Newton iteration diverges (the correction grew in "
                            "three iterations running, to " +
                            format_value(correction) + " m)"};
        if (k + 1 >= max_it)
          throw StepFailure{"the material Newton iteration did not converge in " +
                            std::to_string(max_it) + " iterations (last correction " +
                            format_value(correction) + " m)"};
      }
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
          if (rolling_deformable_journal())
            for (unsigned int c = 0; c + 1 < dim; ++c)
              arm[c] = cn.X[c] + solution_[cn.dofs[c]] - frame_.centre[c];
          torque -= arm[0] * t[1] - arm[1] * t[0];
        }
    rs.torque_journal = bodies_.symmetry_factor() * Utilities::MPI::sum(torque, comm_);
    return rs;
  }

  RunResult ContactModel::run_rolling()
  {
    RunResult result;
    result.n_ranks = n_ranks_;
    const auto &R = scene_.rolling;
    const auto &L = scene_.loading;
    const auto &G = scene_.geometry;
    frame_.turning = true;
    // a deformable journal: its frame at the start (as meshed; the mortar search places it)
    frame_.centre_previous = frame_.centre = {0.0, -G.c_r, 0.0};
    frame_.axis_mesh = Tensor<1, dim>({0.0, -G.c_r, 0.0});
    frame_.psi_converged = frame_.delta_psi = 0.0;
    bodies_.build();
    prepare_mesh();
    init_plasticity();
    result.n_dofs = dofs_.handler().n_dofs();
    result.n_cells = bodies_.triangulation().n_global_active_cells();
    result.symmetry_factor = bodies_.symmetry_factor();
    result.h_min = bodies_.h_min();
    result.setup_time = elapsed();

    const rolling::Motion motion{R.omega_B, R.ramp_time, L.delta_max, G.c_r, G.R_B, G.R_J()};
    const double t_end = rolling_end_time(scene_);
    const double dt_nominal = t_end / R.n_steps;
    const double inertia = rolling_journal_inertia(scene_);
    auto &S = result.rolling;
    S.journal_inertia = inertia;
    S.rolling_rate = motion.rolling_rate(t_end);
    S.time_step = dt_nominal;
    if (rank_ == 0)
      log::info("fe_stage: rolling study, " + std::to_string(result.n_dofs) + " DoFs, " +
                std::to_string(result.n_cells) + " cells, " +
                std::to_string(std::count_if(contact_.nodes().begin(), contact_.nodes().end(),
                                             [](const auto &c) { return c.candidate; })) +
                " contact candidate nodes (rank 0); omega_B " + format_value(R.omega_B) +
                " rad/s, delta_max " + format_value(L.delta_max) + " m at " +
                format_value(R.ramp_time) + " s, " + std::to_string(R.n_steps) + " steps to " +
                format_value(t_end) + " s, journal spin inertia " + format_value(inertia) +
                " kg m^2, mu " + format_value(scene_.contact.mu) + ", setup " +
                log::format_duration(result.setup_time));

    start_from_rest();
    // the bore node at the bottom of the mid-plane: it touches the journal at t = 0 (paper
    // Fig. 9's N_B); the generated ring has a vertex there
    // (kept by its DoFs: a deformable journal's search rebuilds contact_.nodes() at every step)
    int tracked = -1;
    std::array<types::global_dof_index, dim> tracked_dofs{};
    for (unsigned int i = 0; i < contact_.nodes().size(); ++i)
      if (contact_.nodes()[i].owned && std::abs(contact_.nodes()[i].X[0]) < 1e-9 * G.R_B &&
          std::abs(contact_.nodes()[i].X[1] + G.R_B) < 1e-9 * G.R_B &&
          std::abs(contact_.nodes()[i].X[2]) < 1e-9 * G.R_B)
        tracked = int(i), tracked_dofs = contact_.nodes()[i].dofs;
    // the deformable journal's surface node under it at t = 0 (paper Fig. 9's N_J, the same
    // point as meshed; owned by one rank)
    bool journal_tracked = false;
    std::array<types::global_dof_index, dim> journal_dofs{};
    if (rolling_deformable_journal())
      {
        for (const auto &cell : dofs_.handler().active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == 1)
            for (const auto v : cell->vertex_indices())
              if (cell->vertex(v).distance(Point<dim>(0.0, -G.R_B, 0.0)) < 1e-9 * G.R_B &&
                  dofs_.owned().is_element(cell->vertex_dof_index(v, 0)))
                {
                  journal_tracked = true;
                  for (unsigned int c = 0; c < dim; ++c)
                    journal_dofs[c] = cell->vertex_dof_index(v, c);
                }
        if (Utilities::MPI::sum(journal_tracked ? 1u : 0u, comm_) != 1)
          throw NumericalError("fe_stage: the rolling study found no single journal node at "
                               "the bottom of the mid-plane to track");
      }
    if (Utilities::MPI::sum(tracked >= 0 ? 1u : 0u, comm_) != 1)
      throw NumericalError("fe_stage: the rolling study found no single bore node at the "
                           "bottom of the mid-plane to track");

    const bool fields = options_.write_fields && !options_.output_dir.empty();
    unsigned int field_counter = 0;
    if (fields && rank_ == 0)
      std::filesystem::create_directories(options_.output_dir + "/fields");
    if (fields)
      {
        frame_.phi = 0.0;
        frame_.centre_previous = frame_.centre = motion.centre_frame(0.0);
        frame_.delta_psi = 0.0;
        set_obstacle_position(0.0);
        evaluate_contact(0.0);
        write_fields(field_counter++, 0.0);
      }

    // the bearing's balance in its frame: the contact forces' work on it, node by node
    // (by the node's x-DoF: a deformable journal's search rebuilds contact_.nodes() at every step)
    std::map<types::global_dof_index, Tensor<1, dim>> force_before, u_before;
    double work_frame = 0.0;
    double work_drive = 0.0, work_push = 0.0, plastic = 0.0, friction_work = 0.0;
    double bearing_plastic = 0.0;  // [J] the bearing's own, for its balance in its frame
    double torque_drive_prev = 0.0, force_prev = 0.0;
    std::vector<double> times, slips;
    const double wall_steps_start = elapsed();
    unsigned int step = 0;
    SpinStepper stepper(*this, motion, t_end, R.n_steps, L.max_cuts, inertia);
    const unsigned int max_steps = R.n_steps << std::min(L.max_cuts + 1, 20u);
    for (; stepper.time() < t_end * (1.0 - 1e-12) && step < max_steps; ++step)
      {
        SpinStepper::Step solved;
        if (!stepper.solve(solved, result.message))
          break;
        const double t = stepper.time(), dt = solved.dt, rate_new = solved.rate;
        const double gamma = stepper.gamma();
        const RollingSolve &rs = solved.state;

        // the converged step: friction's slip work, the contact forces (frame → fixed), the
        // torques; then commit the material and the contact's reference state
        const double t1 = t + dt;
        double fr = 0.0, torque_bearing = 0.0;
        Tensor<1, dim> force_frame;
        unsigned int n_active = 0, n_slip = 0;
        for (const auto &cn : contact_.nodes())
          if (cn.owned && cn.active)
            {
              const Tensor<1, dim> tr = contact_.traction(cn);
              fr -= tangential(tr, cn.n) * contact_.slip_increment(cn);
              force_frame += tr;
              Tensor<1, dim> x = cn.X;
              for (unsigned int c = 0; c < dim; ++c)
                x[c] += solution_[cn.dofs[c]];
              torque_bearing += x[0] * tr[1] - x[1] * tr[0];
              ++n_active;
              if (contact_.friction() && !cn.stick)
                ++n_slip;
            }
        for (unsigned int c = 0; c < dim; ++c)
          force_frame[c] = Utilities::MPI::sum(force_frame[c], comm_);
        fr = bodies_.symmetry_factor() * Utilities::MPI::sum(fr, comm_);
        torque_bearing = bodies_.symmetry_factor() * Utilities::MPI::sum(torque_bearing, comm_);
        const auto on_journal =
          rolling::rotate_z({-force_frame[0], -force_frame[1], 0.0}, motion.phi(t1));
        Vec3 u_tracked{0.0, 0.0, 0.0};
        if (tracked >= 0)
          for (unsigned int c = 0; c < dim; ++c)
            u_tracked[c] = solution_[tracked_dofs[c]];
        for (auto &c : u_tracked)
          c = Utilities::MPI::sum(c, comm_);
        Vec3 u_journal{0.0, 0.0, 0.0};  // in the journal's frame (0: rigid)
        if (journal_tracked)
          for (unsigned int c = 0; c < dim; ++c)
            u_journal[c] = solution_[journal_dofs[c]];
        for (auto &c : u_journal)
          c = Utilities::MPI::sum(c, comm_);
        double dw = 0.0;
        for (unsigned int i = 0; i < contact_.nodes().size(); ++i)
          {
            auto &cn = contact_.nodes()[i];
            if (
              cn.owned)  // (every node: a deformable journal's search may rebuild contact_.nodes())
              {
                const Tensor<1, dim> f = cn.active ? contact_.traction(cn) : Tensor<1, dim>();
                Tensor<1, dim> u;
                for (unsigned int c = 0; c < dim; ++c)
                  u[c] = solution_[cn.dofs[c]];
                const auto key = cn.dofs[0];
                dw += 0.5 * (force_before[key] + f) * (u - u_before[key]);
                force_before[key] = f;
                u_before[key] = u;
              }
            cn.relative_converged = cn.relative;
            cn.obstacle_u_converged = cn.obstacle_u;
          }
        work_frame += bodies_.symmetry_factor() * Utilities::MPI::sum(dw, comm_);
        frame_.psi_converged += frame_.delta_psi;
        frame_.delta_psi = 0.0;
        const PlasticEnergies pe = commit_plasticity();

        RollingStepRecord rec;
        rec.step = step + 1;
        rec.time = t1;
        rec.delta = motion.delta(t1);
        // (+ 0.0: a step without contact sums no force, and −0 would be written "-0")
        rec.force_normal = bodies_.symmetry_factor() * on_journal[1] + 0.0;
        rec.force_tangential = bodies_.symmetry_factor() * on_journal[0] + 0.0;
        rec.phi = motion.phi(t1);
        rec.phi_rate = R.omega_B;
        rec.gamma_rate = rate_new;
        rec.gamma = gamma + rate_new * dt;
        rec.slip_speed = motion.slip_speed(t1, rate_new);
        if (rolling_deformable_journal())
          {
            // Both surfaces give way, so the contact is not at R_B + δ from the bearing's axis
            // and R_J from the journal's: the radii at the active node carrying the largest
            // normal force, from each axis to where the node is now (the contact closed:
            // the journal's surface is there too), ω_B r_B − γ̇ r_J
            std::vector<double> mine{-1.0, 0.0, 0.0};
            for (const auto &cn : contact_.nodes())
              if (cn.owned && cn.active && cn.lambda > mine[0])
                {
                  const double x = cn.X[0] + solution_[cn.dofs[0]];
                  const double y = cn.X[1] + solution_[cn.dofs[1]];
                  mine = {cn.lambda, std::hypot(x, y),
                          std::hypot(x - frame_.centre[0], y - frame_.centre[1])};
                }
            std::array<double, 3> best{-1.0, 0.0, 0.0};
            for (const auto &part : Utilities::MPI::all_gather(comm_, mine))
              if (part[0] > best[0])
                best = {part[0], part[1], part[2]};
            if (best[0] > 0.0)
              rec.slip_speed = R.omega_B * best[1] - rate_new * best[2];
          }
        rec.torque_journal = rs.torque_journal;
        rec.torque_drive = -torque_bearing;
        work_drive += 0.5 * (torque_drive_prev + rec.torque_drive) * (rec.phi - motion.phi(t));
        work_push += 0.5 * (force_prev + rec.force_normal) * (rec.delta - motion.delta(t));
        plastic += pe.plastic_work_step;
        friction_work += fr;
        rec.work_drive = work_drive;
        rec.work_push = work_push;
        rec.elastic_energy = pe.elastic_energy;
        rec.plastic_dissipation = plastic;
        rec.friction_dissipation = friction_work;
        rec.kinetic_energy = 0.5 * inertia * rate_new * rate_new;
        rec.energy_balance_error = work_drive + work_push - rec.elastic_energy - plastic -
                                   friction_work - rec.kinetic_energy;
        rec.work_frame = work_frame;
        bearing_plastic += pe.bearing_plastic_work_step;
        rec.frame_balance_error = work_frame - pe.bearing_elastic_energy - bearing_plastic;
        rec.max_plastic_strain = pe.max_plastic_strain;
        rec.max_strain = pe.max_strain;
        rec.plastic_volume = pe.plastic_volume;
        rec.n_active = Utilities::MPI::sum(n_active, comm_);
        rec.n_slip = Utilities::MPI::sum(n_slip, comm_);
        rec.spin_iterations = solved.spin_evaluations;
        rec.newton_iterations = rs.newton_iterations;
        rec.contact_iterations = rs.contact_iterations;
        rec.linear_iterations = rs.linear_iterations;
        rec.cuts = solved.cuts;
        // paper Eqs. 4–8: N_B at X0 = (0, −R_B, 0), N_J the journal point under it at t = 0
        const Vec3 X0{0.0, -G.R_B, 0.0};
        const Vec3 xB =
          rolling::rotate_z({X0[0] + u_tracked[0], X0[1] + u_tracked[1], 0.0}, rec.phi);
        rec.phi_paper = rolling::paper_angle({xB[0] - X0[0], xB[1] - X0[1], 0.0}, G.R_B);
        const Vec3 c0 = motion.centre_fixed(0.0), c1 = motion.centre_fixed(t1);
        const Vec3 pJ = rolling::rotate_z({u_journal[0], -G.R_J() + u_journal[1], 0.0}, rec.gamma);
        rec.gamma_paper =
          rolling::paper_angle({c1[0] + pJ[0] - c0[0], c1[1] + pJ[1] - (c0[1] - G.R_J()), 0.0},
                               G.R_J());
        rec.phi_rate_paper = rec.phi_paper / t1;
        rec.gamma_rate_paper = rec.gamma_paper / t1;
        rec.wall_time = elapsed();
        torque_drive_prev = rec.torque_drive;
        force_prev = rec.force_normal;
        stepper.accept(solved);
        times.push_back(t1);
        slips.push_back(rec.slip_speed);
        result.rolling_steps.push_back(rec);

        IncrementRecord inc = rs.record;
        inc.delta = rec.delta;
        inc.force = inc.force_support = inc.force_load = rec.force_normal;
        inc.n_active = rec.n_active;
        inc.n_slip = rec.n_slip;
        inc.contact_iterations = rec.contact_iterations;
        inc.linear_iterations = rec.linear_iterations;
        inc.wall_time = rec.wall_time;
        result.increments.push_back(inc);
        if (rank_ == 0)
          {
            const double per_second = (elapsed() - wall_steps_start) / t1;
            log::info("fe_stage: step " + std::to_string(rec.step) + " t " + format_value(t1) +
                      " s, delta " + format_value(rec.delta) + " m, F " +
                      format_value(rec.force_normal) + " N, spin " + format_value(rec.gamma_rate) +
                      " rad/s (slip " + format_value(rec.slip_speed) + " m/s), eps_p max " +
                      format_value(rec.max_plastic_strain) + ", " +
                      std::to_string(rec.spin_iterations) + " spin / " +
                      std::to_string(rec.contact_iterations) + " contact iterations" +
                      (rec.cuts ? ", " + std::to_string(rec.cuts) + " cuts" : "") + ", ETA " +
                      log::format_duration(per_second * (t_end - t1)));
          }
        if (options_.on_increment)
          options_.on_increment(inc);
        if (options_.on_rolling_step)
          options_.on_rolling_step(rec);
        const bool last = t1 >= t_end * (1.0 - 1e-12);
        if (fields && (rec.step % R.field_stride == 0 || last))
          write_fields(field_counter++, t1);
      }
    const double t = stepper.time();
    if (result.message.empty() && t < t_end * (1.0 - 1e-12))
      result.message = "the step limit (" + std::to_string(max_steps) +
                       ") was reached at t = " + format_value(t) + " s";
    // the end state: strains across the contact zone, the slip stages, the balance
    result.strain_profile = strain_profile(0, motion.phi(t), 30.0 * units::deg);
    if (rolling_deformable_journal())
      for (const auto &p : strain_profile(1, stepper.gamma(), 30.0 * units::deg))
        result.strain_profile.push_back(p);
    const auto stages = rolling::slip_stages(times, slips);
    S.stages_found = stages.found;
    S.slip_speed_max = stages.v_max;
    S.end_of_slip = stages.end_of_slip;
    S.settled = stages.settled;
    S.slip_speed_final = stages.v_final;
    if (!result.rolling_steps.empty())
      {
        const auto &last = result.rolling_steps.back();
        S.max_plastic_strain = last.max_plastic_strain;
        S.max_strain = last.max_strain;
        const double work_in = std::abs(last.work_drive) + std::abs(last.work_push);
        S.energy_balance_error =
          work_in > 0.0 ? std::abs(last.energy_balance_error) / work_in : 0.0;
      }
    result.sliding_rebuilds = n_sliding_rebuilds_;
    if (rolling_deformable_journal() && rank_ == 0)
      log::info("fe_stage: the deformable journal's coupling: " +
                std::to_string(stepper.n_searches()) + " mortar searches, " +
                std::to_string(n_sliding_rebuilds_) + " of them with a new sparsity pattern, " +
                log::format_duration(stepper.search_time()) + " in all");
    result.field_files = field_files_;
    result.complete = result.message.empty();
    result.wall_time = elapsed();
    return result;
  }
}  // namespace clearjoint::fe::detail
