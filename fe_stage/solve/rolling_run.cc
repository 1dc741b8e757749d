// The rolling study (paper §3.4, docs/fe.md "Rolling study"): time steps over the push ramp.
// Each step: the bearing turned to φ = ω_B t (its co-rotating frame: the mesh stays, the rigid
// journal's axis turns round it), the journal pushed to δ(t), and the journal's spin rate γ̇
// found from its torque balance (SpinStepper, solve/spin_stepper.h). Every evaluation of the
// journal's torque is a state of the elastoplastic bodies (Model::solve_rolling_state:
// material Newton iterations, each an active-set contact solve with Coulomb friction). What
// this file keeps (RollingRun, solve/rolling_run.h): the study's set-up, what each converged
// step records (forces, torques, energies, the paper's Eqs. 4–8), and the end state (strain
// profile, slip stages).
#include "fe_stage/solve/rolling_run.h"

#include "fe_stage/core/restart_values.h"
#include "fe_stage/solve/rolling_restart.h"

#include "common/error.h"
#include "common/log.h"
#include "common/units.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// The paper's tracked points (Fig. 9) by their DoFs: N_B the bore node at the bottom of
    /// the mid-plane (it touches the journal at t = 0; the generated ring has a vertex there),
    /// N_J the deformable journal's surface node under it at t = 0 (the same point as
    /// meshed). Each is owned by one rank. By DoFs, not contact-node index: a deformable
    /// journal's search rebuilds the contact nodes at every step.
    struct PaperNodes
    {
      bool bore = false, journal = false;  // owned by this rank
      std::array<types::global_dof_index, dim> bore_dofs{}, journal_dofs{};
    };

    PaperNodes find_paper_nodes(const FeScene &scene, const DofSpace &dofs,
                                const ContactProblem &contact, const bool deformable_journal,
                                MPI_Comm comm)
    {
      const double R_B = scene.geometry.R_B;
      PaperNodes p;
      for (const auto &cn : contact.nodes())
        if (cn.owned && std::abs(cn.X[0]) < 1e-9 * R_B && std::abs(cn.X[1] + R_B) < 1e-9 * R_B &&
            std::abs(cn.X[2]) < 1e-9 * R_B)
          p.bore = true, p.bore_dofs = cn.dofs;
      if (deformable_journal)
        {
          for (const auto &cell : dofs.handler().active_cell_iterators())
            if (cell->is_locally_owned() && cell->material_id() == 1)
              for (const auto v : cell->vertex_indices())
                if (cell->vertex(v).distance(Point<dim>(0.0, -R_B, 0.0)) < 1e-9 * R_B &&
                    dofs.owned().is_element(cell->vertex_dof_index(v, 0)))
                  {
                    p.journal = true;
                    for (unsigned int c = 0; c < dim; ++c)
                      p.journal_dofs[c] = cell->vertex_dof_index(v, c);
                  }
          if (Utilities::MPI::sum(p.journal ? 1u : 0u, comm) != 1)
            throw NumericalError("fe_stage: the rolling study found no single journal node at "
                                 "the bottom of the mid-plane to track");
        }
      if (Utilities::MPI::sum(p.bore ? 1u : 0u, comm) != 1)
        throw NumericalError("fe_stage: the rolling study found no single bore node at the "
                             "bottom of the mid-plane to track");
      return p;
    }

    /// A tracked node's displacement [m] (all ranks; 0 where no rank owns it).
    Vec3 tracked_displacement(const bool owned,
                              const std::array<types::global_dof_index, dim> &node_dofs,
                              const TrilinosWrappers::MPI::Vector &u, MPI_Comm comm)
    {
      Vec3 d{0.0, 0.0, 0.0};
      if (owned)
        for (unsigned int c = 0; c < dim; ++c)
          d[c] = u[node_dofs[c]];
      for (auto &c : d)
        c = Utilities::MPI::sum(c, comm);
      return d;
    }

    /// The bearing's balance in its frame: the contact forces' work on it, node by node (by
    /// the node's x-DoF: a deformable journal's search rebuilds the contact nodes at every
    /// step), by the trapezoidal rule between converged steps.
    struct FrameWork
    {
      std::map<types::global_dof_index, Tensor<1, dim>> force_before, u_before;
      double work = 0.0;  // [J] full body
    };

    /// What a converged step's contact did, summed over the ranks (full body where a force
    /// or a work): friction's slip work, the contact force on the bearing in its frame, the
    /// drive's torque on it, the active and slipping nodes (this rank's).
    struct ContactStep
    {
      double friction_work = 0.0, torque_bearing = 0.0;
      Tensor<1, dim> force_frame;
      unsigned int n_active = 0, n_slip = 0;
    };

    /// The converged step's contact sums, the frame's work advanced, and the contact's
    /// reference state (relative displacement, obstacle motion) moved to this step.
    ContactStep close_contact_step(ContactProblem &contact, const TrilinosWrappers::MPI::Vector &u,
                                   const double symmetry_factor, FrameWork &frame, MPI_Comm comm)
    {
      ContactStep s;
      double fr = 0.0, torque_bearing = 0.0;
      for (const auto &cn : contact.nodes())
        if (cn.owned && cn.active)
          {
            const Tensor<1, dim> tr = contact.traction(cn);
            fr -= tangential(tr, cn.n) * contact.slip_increment(cn);
            s.force_frame += tr;
            Tensor<1, dim> x = cn.X;
            for (unsigned int c = 0; c < dim; ++c)
              x[c] += u[cn.dofs[c]];
            torque_bearing += x[0] * tr[1] - x[1] * tr[0];
            ++s.n_active;
            if (contact.friction() && !cn.stick)
              ++s.n_slip;
          }
      for (unsigned int c = 0; c < dim; ++c)
        s.force_frame[c] = Utilities::MPI::sum(s.force_frame[c], comm);
      s.friction_work = symmetry_factor * Utilities::MPI::sum(fr, comm);
      s.torque_bearing = symmetry_factor * Utilities::MPI::sum(torque_bearing, comm);
      double dw = 0.0;
      for (auto &cn : contact.nodes())
        {
          if (cn.owned)  // (every node: a deformable journal's search may rebuild the nodes)
            {
              const Tensor<1, dim> f = cn.active ? contact.traction(cn) : Tensor<1, dim>();
              Tensor<1, dim> un;
              for (unsigned int c = 0; c < dim; ++c)
                un[c] = u[cn.dofs[c]];
              const auto key = cn.dofs[0];
              dw += 0.5 * (frame.force_before[key] + f) * (un - frame.u_before[key]);
              frame.force_before[key] = f;
              frame.u_before[key] = un;
            }
          cn.relative_converged = cn.relative;
          cn.obstacle_u_converged = cn.obstacle_u;
        }
      frame.work += symmetry_factor * Utilities::MPI::sum(dw, comm);
      return s;
    }

    /// The deformable journal's contact radii: both surfaces give way, so the contact is not
    /// at R_B + δ from the bearing's axis and R_J from the journal's. At the active node
    /// carrying the largest normal force (all ranks), from each axis to where the node is now
    /// (the contact closed: the journal's surface is there too). False without contact.
    bool contact_radii(const ContactProblem &contact, const TrilinosWrappers::MPI::Vector &u,
                       const std::array<double, 3> &journal_centre, double &r_bearing,
                       double &r_journal, MPI_Comm comm)
    {
      std::vector<double> mine{-1.0, 0.0, 0.0};
      for (const auto &cn : contact.nodes())
        if (cn.owned && cn.active && cn.lambda > mine[0])
          {
            const double x = cn.X[0] + u[cn.dofs[0]];
            const double y = cn.X[1] + u[cn.dofs[1]];
            mine = {cn.lambda, std::hypot(x, y),
                    std::hypot(x - journal_centre[0], y - journal_centre[1])};
          }
      std::array<double, 3> best{-1.0, 0.0, 0.0};
      for (const auto &part : Utilities::MPI::all_gather(comm, mine))
        if (part[0] > best[0])
          best = {part[0], part[1], part[2]};
      r_bearing = best[1];
      r_journal = best[2];
      return best[0] > 0.0;
    }

    /// The run's energy balance, paper §3.4: the drive's and the push's work against the
    /// elastic energy, plastic and friction dissipation and the journal's kinetic energy (the
    /// works by the trapezoidal rule between converged steps); and the bearing's own balance
    /// in its frame (the contact's work on it against its elastic energy and plastic work).
    struct RollingBalance
    {
      double work_drive = 0.0, work_push = 0.0, plastic = 0.0, friction = 0.0;  // [J]
      double bearing_plastic = 0.0;                                             // [J]
      double torque_drive_prev = 0.0, force_prev = 0.0;

      /// Adds the step from (φ0, δ0) to the record's φ, δ with its torque and force, the
      /// step's plastic and friction work, and writes the record's energies [J].
      void close_step(RollingStepRecord &rec, const double phi0, const double delta0,
                      const double plastic_step, const double bearing_plastic_step,
                      const double elastic_energy, const double bearing_elastic_energy,
                      const double friction_step, const double frame_work,
                      const double kinetic_energy)
      {
        work_drive += 0.5 * (torque_drive_prev + rec.torque_drive) * (rec.phi - phi0);
        work_push += 0.5 * (force_prev + rec.force_normal) * (rec.delta - delta0);
        plastic += plastic_step;
        friction += friction_step;
        rec.work_drive = work_drive;
        rec.work_push = work_push;
        rec.elastic_energy = elastic_energy;
        rec.plastic_dissipation = plastic;
        rec.friction_dissipation = friction;
        rec.kinetic_energy = kinetic_energy;
        rec.energy_balance_error =
          work_drive + work_push - rec.elastic_energy - plastic - friction - rec.kinetic_energy;
        rec.work_frame = frame_work;
        bearing_plastic += bearing_plastic_step;
        rec.frame_balance_error = frame_work - bearing_elastic_energy - bearing_plastic;
        torque_drive_prev = rec.torque_drive;
        force_prev = rec.force_normal;
      }
    };

    /// The paper's Eqs. 4–8 on N_B at X0 = (0, −R_B, 0) and N_J, the journal point under it at
    /// t = 0, from their displacements (the bore's in its frame, the journal's in its own; 0:
    /// rigid): the chord angles, unwrapped past half a turn by continuity with the last step
    /// (the sense of the turn from the point's start and end radii about its own centre), and
    /// the rates φ/t, γ/t.
    void set_paper_angles(RollingStepRecord &rec, const Geometry &G, const rolling::Motion &motion,
                          const Vec3 &u_tracked, const Vec3 &u_journal,
                          const RollingStepRecord *previous)
    {
      const Vec3 X0{0.0, -G.R_B, 0.0};
      const Vec3 xB = rolling::rotate_z({X0[0] + u_tracked[0], X0[1] + u_tracked[1], 0.0}, rec.phi);
      rec.phi_paper = rolling::unwrap_paper_angle(
        rolling::paper_angle({xB[0] - X0[0], xB[1] - X0[1], 0.0}, G.R_B),
        X0[0] * xB[1] - X0[1] * xB[0] >= 0.0, previous ? previous->phi_paper : 0.0);
      const Vec3 c0 = motion.centre_fixed(0.0), c1 = motion.centre_fixed(rec.time);
      const Vec3 pJ = rolling::rotate_z({u_journal[0], -G.R_J() + u_journal[1], 0.0}, rec.gamma);
      rec.gamma_paper =
        rolling::unwrap_paper_angle(rolling::paper_angle({c1[0] + pJ[0] - c0[0],
                                                          c1[1] + pJ[1] - (c0[1] - G.R_J()), 0.0},
                                                         G.R_J()),
                                    G.R_J() * pJ[0] >= 0.0,  // (0, −R_J) × pJ
                                    previous ? previous->gamma_paper : 0.0);
      rec.phi_rate_paper = rec.phi_paper / rec.time;
      rec.gamma_rate_paper = rec.gamma_paper / rec.time;
    }

    /// The step as an increment of the force–penetration record (force_penetration.csv).
    IncrementRecord increment_of(const RollingStepRecord &rec, IncrementRecord inc)
    {
      inc.delta = rec.delta;
      inc.force = inc.force_support = inc.force_load = rec.force_normal;
      inc.n_active = rec.n_active;
      inc.n_slip = rec.n_slip;
      inc.contact_iterations = rec.contact_iterations;
      inc.linear_iterations = rec.linear_iterations;
      inc.wall_time = rec.wall_time;
      return inc;
    }

    /// The run's first line: its size and the scene's motion.
    void log_rolling_start(const FeScene &scene, const RunResult &result,
                           const ContactProblem &contact, const double t_end, const double inertia)
    {
      const auto &R = scene.rolling;
      log::info("fe_stage: rolling study, " + std::to_string(result.n_dofs) + " DoFs, " +
                std::to_string(result.n_cells) + " cells, " +
                std::to_string(std::count_if(contact.nodes().begin(), contact.nodes().end(),
                                             [](const auto &c) { return c.candidate; })) +
                " contact candidate nodes (rank 0); omega_B " + format_value(R.omega_B) +
                " rad/s, delta_max " + format_value(scene.loading.delta_max) + " m at " +
                format_value(R.ramp_time) + " s, " + std::to_string(R.n_steps) + " steps to " +
                format_value(t_end) + " s, journal spin inertia " + format_value(inertia) +
                " kg m^2, mu " + format_value(scene.contact.mu) + ", setup " +
                log::format_duration(result.setup_time));
    }

    /// How the steps were solved: by the coupled iteration or the root finder, and the
    /// deformable journal's searches.
    void log_solver_summary(const FeScene &scene, const RunResult &result,
                            const SpinStepper &stepper, const bool deformable_journal,
                            const unsigned int n_sliding_rebuilds)
    {
      if (scene.rolling.spin_solver != Rolling::SpinSolver::nested)
        log::info(
          "fe_stage: the journal's spin: " +
          std::to_string(std::count_if(result.rolling_steps.begin(), result.rolling_steps.end(),
                                       [](const auto &r) { return r.spin_coupled; })) +
          " of " + std::to_string(result.rolling_steps.size()) + " steps by the " +
          (scene.rolling.spin_solver == Rolling::SpinSolver::bordered ? "bordered" : "coupled") +
          " iteration, " + std::to_string(stepper.n_coupled_fallbacks()) +
          " attempts by the root finder after it failed");
      if (deformable_journal)
        log::info("fe_stage: the deformable journal's coupling: " +
                  std::to_string(stepper.n_searches()) + " mortar searches, " +
                  std::to_string(n_sliding_rebuilds) + " of them with a new sparsity pattern, " +
                  log::format_duration(stepper.search_time()) + " in all");
    }

    /// The progress line of a converged step, with the time left [s] at this step's pace.
    void log_step(const RollingStepRecord &rec, const double seconds_left)
    {
      log::info(
        "fe_stage: step " + std::to_string(rec.step) + " t " + format_value(rec.time) +
        " s, delta " + format_value(rec.delta) + " m, F " + format_value(rec.force_normal) +
        " N, spin " + format_value(rec.gamma_rate) + " rad/s (slip " +
        format_value(rec.slip_speed) + " m/s), eps_p max " + format_value(rec.max_plastic_strain) +
        ", D_p " + format_value(rec.plastic_dissipation) + " J, " +
        std::to_string(rec.spin_iterations) + " spin / " + std::to_string(rec.contact_iterations) +
        " contact iterations" + (rec.cuts ? ", " + std::to_string(rec.cuts) + " cuts" : "") +
        ", ETA " + log::format_duration(seconds_left));
    }

    /// The run's summary from its steps: the slip stages (rolling::slip_stages on the slip
    /// speed's history), the largest strains and the balance's error at the end.
    void summarise(RollingSummary &S, const std::vector<RollingStepRecord> &steps)
    {
      std::vector<double> times, slips;
      for (const auto &rec : steps)
        {
          times.push_back(rec.time);
          slips.push_back(rec.slip_speed);
        }
      const auto stages = rolling::slip_stages(times, slips);
      S.stages_found = stages.found;
      S.slip_speed_max = stages.v_max;
      S.end_of_slip = stages.end_of_slip;
      S.settled = stages.settled;
      S.slip_speed_final = stages.v_final;
      if (!steps.empty())
        {
          const auto &last = steps.back();
          S.max_plastic_strain = last.max_plastic_strain;
          S.max_strain = last.max_strain;
          const double work_in = std::abs(last.work_drive) + std::abs(last.work_push);
          S.energy_balance_error =
            work_in > 0.0 ? std::abs(last.energy_balance_error) / work_in : 0.0;
        }
    }

    /// Closes each converged step into its record: what it reads, and the ledgers it carries
    /// from step to step (the bearing frame's work, the energy balance).
    struct StepCloser
    {
      const RollingRun::Parts &parts;
      StudyModel &model;
      const rolling::Motion &motion;
      const PaperNodes &paper;
      const double inertia;
      FrameWork frame_work;
      RollingBalance ledger;
      double wall_offset = 0.0;  // [s] a resumed run's: the wall time of the runs before it

      /// Step `step` (0-based) as `solved` left it: friction's slip work, the contact forces
      /// (frame → fixed), the torques, the energies and the paper's angles; the material and
      /// the contact's reference state committed. Before stepper.accept(solved).
      RollingStepRecord close(const unsigned int step, const SpinStepper &stepper,
                              const SpinStepper::Step &solved, const RollingStepRecord *previous)
      {
        const auto &R = parts.scene.rolling;
        const auto &G = parts.scene.geometry;
        const double t = stepper.time(), dt = solved.dt, rate_new = solved.rate;
        const double t1 = t + dt;
        const double gamma = stepper.gamma();
        const RollingSolve &rs = solved.state;
        const ContactStep cs =
          close_contact_step(parts.contact, parts.state.u(), parts.bodies.symmetry_factor(),
                             frame_work, parts.comm);
        const auto on_journal =
          rolling::rotate_z({-cs.force_frame[0], -cs.force_frame[1], 0.0}, motion.phi(t1));
        const Vec3 u_tracked =
          tracked_displacement(paper.bore, paper.bore_dofs, parts.state.u(), parts.comm);
        // in the journal's frame (0: rigid)
        const Vec3 u_journal =
          tracked_displacement(paper.journal, paper.journal_dofs, parts.state.u(), parts.comm);
        parts.frame.psi_converged += parts.frame.delta_psi;
        parts.frame.delta_psi = 0.0;
        const PlasticEnergies pe = model.commit_plasticity();

        RollingStepRecord rec;
        rec.step = step + 1;
        rec.time = t1;
        rec.delta = motion.delta(t1);
        // (+ 0.0: a step without contact sums no force, and −0 would be written "-0")
        rec.force_normal = parts.bodies.symmetry_factor() * on_journal[1] + 0.0;
        rec.force_tangential = parts.bodies.symmetry_factor() * on_journal[0] + 0.0;
        rec.phi = motion.phi(t1);
        rec.phi_rate = R.omega_B;
        rec.gamma_rate = rate_new;
        rec.gamma = gamma + rate_new * dt;
        rec.slip_speed = motion.slip_speed(t1, rate_new);
        double r_bearing = 0.0, r_journal = 0.0;  // ω_B r_B − γ̇ r_J where both give way
        if (model.journal_turns_deformable() &&
            contact_radii(parts.contact, parts.state.u(), parts.frame.centre, r_bearing, r_journal,
                          parts.comm))
          rec.slip_speed = R.omega_B * r_bearing - rate_new * r_journal;
        rec.torque_journal = rs.torque_journal;
        rec.torque_drive = -cs.torque_bearing;
        ledger.close_step(rec, motion.phi(t), motion.delta(t), pe.plastic_work_step,
                          pe.bearing_plastic_work_step, pe.elastic_energy,
                          pe.bearing_elastic_energy, cs.friction_work, frame_work.work,
                          0.5 * inertia * rate_new * rate_new);
        rec.max_plastic_strain = pe.max_plastic_strain;
        rec.max_strain = pe.max_strain;
        rec.plastic_volume = pe.plastic_volume;
        rec.n_active = Utilities::MPI::sum(cs.n_active, parts.comm);
        rec.n_slip = Utilities::MPI::sum(cs.n_slip, parts.comm);
        rec.spin_iterations = solved.spin_evaluations;
        rec.newton_iterations = solved.newton_iterations;
        rec.line_search_steps = solved.line_search_steps;
        rec.contact_iterations = solved.contact_iterations;
        rec.linear_iterations = solved.linear_iterations;
        rec.spin_coupled = solved.coupled;
        rec.cuts = solved.cuts;
        set_paper_angles(rec, G, motion, u_tracked, u_journal, previous);
        rec.wall_time = wall_offset + model.elapsed();
        return rec;
      }
    };

    /// The run's own part of a restart file: the steps' records, the ledgers carried from step
    /// to step, the journal frame's committed turn, the fields written so far.
    void write_run_part(RestartWriter &out, const RunResult &result, const StepCloser &closer,
                        const JournalFrame &frame, const unsigned int field_counter)
    {
      out.section("rolling run");
      out.put_vector(result.rolling_steps);
      out.put_vector(result.increments);
      out.put(closer.ledger);
      out.put(closer.frame_work.work);
      out.put<std::uint64_t>(closer.frame_work.force_before.size());
      for (const auto &[key, f] : closer.frame_work.force_before)
        {
          out.put(key);
          put_tensor(out, f);
          put_tensor(out, closer.frame_work.u_before.at(key));
        }
      out.put(frame.psi_converged);
      out.put(field_counter);
    }

    void read_run_part(RestartReader &in, RunResult &result, StepCloser &closer,
                       JournalFrame &frame, unsigned int &field_counter)
    {
      in.section("rolling run");
      result.rolling_steps = in.get_vector<RollingStepRecord>();
      result.increments = in.get_vector<IncrementRecord>();
      if (result.rolling_steps.size() != result.increments.size())
        in.damaged("its step records do not match its increments");
      closer.ledger = in.get<RollingBalance>();
      closer.frame_work.work = in.get<double>();
      const auto n = in.get<std::uint64_t>();
      for (std::uint64_t k = 0; k < n; ++k)
        {
          const auto key = in.get<types::global_dof_index>();
          closer.frame_work.force_before[key] = get_tensor(in);
          closer.frame_work.u_before[key] = get_tensor(in);
        }
      frame.psi_converged = in.get<double>();
      frame.delta_psi = 0.0;
      field_counter = in.get<unsigned int>();
      if (!result.rolling_steps.empty())
        closer.wall_offset = result.rolling_steps.back().wall_time;
    }

    /// The resumed run's first line: from where, and the state there.
    void log_resumed(const std::string &path, const RunResult &result, const SpinStepper &stepper)
    {
      std::string at = "t = " + format_value(stepper.time()) + " s";
      if (!result.rolling_steps.empty())
        {
          const auto &last = result.rolling_steps.back();
          at += ", delta " + format_value(last.delta) + " m, F " + format_value(last.force_normal) +
                " N, D_p " + format_value(last.plastic_dissipation) + " J, after " +
                log::format_duration(last.wall_time) + " of earlier runs";
        }
      log::info("fe_stage: resumed from " + path + " after step " +
                std::to_string(result.rolling_steps.size()) + ": " + at);
    }

    /// Why a run whose journal's spin ran away stops (`rec`: the step where it did).
    std::string runaway_message(const FeScene &scene, const rolling::Motion &motion,
                                const RollingStepRecord &first, const RollingStepRecord &rec)
    {
      return "the journal's spin ran away: " + format_value(rec.gamma_rate) +
             " rad/s at t = " + format_value(rec.time) + " s, more than " +
             format_value(rolling::Motion::runaway_factor) + " times the rolling rate " +
             format_value(motion.rolling_rate(rec.time)) + " rad/s (it was " +
             format_value(first.gamma_rate) + " rad/s at t = " + format_value(first.time) +
             " s); the torque balance on the journal has no root near rolling any more " +
             "(contact.mu " + format_value(scene.contact.mu) + ", largest plastic strain " +
             format_value(rec.max_plastic_strain) + ", slip speed " + format_value(rec.slip_speed) +
             " m/s); a finer mesh (mesh.contact_refinements) " +
             "or a smaller contact.mu are what to try";
    }
  }  // namespace

  RollingRun::RollingRun(StudyModel &model, const Parts &parts)
    : model_(model)
    , parts_(parts)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
    , n_ranks_(Utilities::MPI::n_mpi_processes(parts.comm))
  {}

  RunResult RollingRun::run()
  {
    RunResult result;
    begin(result);
    const auto &R = parts_.scene.rolling;
    const auto &L = parts_.scene.loading;
    const auto &G = parts_.scene.geometry;

    const rolling::Motion motion{R.omega_B, R.ramp_time, L.delta_max, G.c_r, G.R_B, G.R_J()};
    const double t_end = rolling_end_time(parts_.scene);
    const double dt_nominal = t_end / R.n_steps;
    const double inertia = rolling_journal_inertia(parts_.scene);
    auto &S = result.rolling;
    S.journal_inertia = inertia;
    S.rolling_rate = motion.rolling_rate(t_end);
    S.time_step = dt_nominal;
    if (rank_ == 0)
      log_rolling_start(parts_.scene, result, parts_.contact, t_end, inertia);

    model_.start_from_rest();
    const PaperNodes paper = find_paper_nodes(parts_.scene, parts_.dofs, parts_.contact,
                                              model_.journal_turns_deformable(), parts_.comm);

    unsigned int field_counter = 0;
    parts_.fields.create_directory();
    const auto &restart = parts_.options.restart;
    if (parts_.fields.enabled() && restart.resume_dir.empty())
      {
        parts_.frame.phi = 0.0;
        parts_.frame.centre_previous = parts_.frame.centre = motion.centre_frame(0.0);
        parts_.frame.delta_psi = 0.0;
        model_.evaluate_contact_at(0.0);
        parts_.fields.write(field_counter++, 0.0);
      }

    StepCloser closer{parts_, model_, motion, paper, inertia, {}, {}};
    SpinStepper stepper = model_.spin_stepper(motion, t_end, R.n_steps, L.max_cuts, inertia);
    const RestartHeader header = RestartHeader::of(parts_.scene, n_ranks_, result.n_dofs);
    if (!restart.resume_dir.empty())
      {
        RestartReader in = RestartFolder(restart.resume_dir, parts_.comm).read();
        RestartHeader::read(in, header);
        read_run_part(in, result, closer, parts_.frame, field_counter);
        stepper.read_restart(in);
        model_.read_restart(in);
        in.expect_end();
        if (rank_ == 0)
          log_resumed(in.path(), result, stepper);
        // the steps before are this run's output too
        for (std::size_t k = 0; k < result.rolling_steps.size(); ++k)
          {
            if (parts_.options.on_increment)
              parts_.options.on_increment(result.increments[k]);
            if (parts_.options.on_rolling_step)
              parts_.options.on_rolling_step(result.rolling_steps[k]);
          }
      }
    const double wall_steps_start = model_.elapsed(), t_steps_start = stepper.time();
    unsigned int step = result.rolling_steps.size();
    const unsigned int max_steps = R.n_steps << std::min(L.max_cuts + 1, 20u);
    for (; stepper.time() < t_end * (1.0 - 1e-12) && step < max_steps; ++step)
      {
        SpinStepper::Step solved;
        if (!stepper.solve(solved, result.message))
          break;
        const RollingStepRecord rec =
          closer.close(step, stepper, solved,
                       result.rolling_steps.empty() ? nullptr : &result.rolling_steps.back());
        const double t1 = rec.time;
        stepper.accept(solved);
        result.rolling_steps.push_back(rec);

        const IncrementRecord inc = increment_of(rec, solved.state.record);
        result.increments.push_back(inc);
        const bool last = t1 >= t_end * (1.0 - 1e-12);
        const bool writes_fields =
          parts_.fields.enabled() && (rec.step % R.field_stride == 0 || last);
        // before the callbacks: an interrupt there stops the run after this state is kept
        if (!restart.write_dir.empty() && (rec.step % std::max(restart.every, 1u) == 0 || last))
          {
            RestartHeader h = header;
            h.steps = rec.step;
            h.time = t1;
            RestartWriter out;
            h.write(out);
            write_run_part(out, result, closer, parts_.frame,
                           field_counter + (writes_fields ? 1 : 0));
            stepper.write_restart(out);
            model_.write_restart(out);
            RestartFolder(restart.write_dir, parts_.comm).write(out);
          }
        if (rank_ == 0)
          log_step(rec,
                   (model_.elapsed() - wall_steps_start) / (t1 - t_steps_start) * (t_end - t1));
        if (parts_.options.on_increment)
          parts_.options.on_increment(inc);
        if (parts_.options.on_rolling_step)
          parts_.options.on_rolling_step(rec);
        if (writes_fields)
          parts_.fields.write(field_counter++, t1);
        if (motion.spin_ran_away(t1, rec.gamma_rate))
          {
            // the step itself converged (its fields and row are written, to show it); the run
            // stops here rather than follow the spin where no balance near rolling holds it
            result.message =
              runaway_message(parts_.scene, motion, result.rolling_steps.front(), rec);
            if (rank_ == 0)
              log::error("fe_stage: " + result.message);
            break;
          }
      }
    if (result.message.empty() && stepper.time() < t_end * (1.0 - 1e-12))
      result.message = "the step limit (" + std::to_string(max_steps) +
                       ") was reached at t = " + format_value(stepper.time()) + " s";
    finish(result, stepper, motion);
    return result;
  }

  /// The turning frame at rest, the mesh, DoFs and material history; the run's sizes.
  void RollingRun::begin(RunResult &result)
  {
    const auto &G = parts_.scene.geometry;
    result.n_ranks = n_ranks_;
    parts_.frame.turning = true;
    // a deformable journal: its frame at the start (as meshed; the mortar search places it)
    parts_.frame.centre_previous = parts_.frame.centre = {0.0, -G.c_r, 0.0};
    parts_.frame.axis_mesh = Tensor<1, dim>({0.0, -G.c_r, 0.0});
    parts_.frame.psi_converged = parts_.frame.delta_psi = 0.0;
    model_.build_mesh();
    model_.init_plasticity();
    model_.record_mesh(result);
  }

  /// The end state (the strains across the contact zone), the slip stages, the solver's
  /// summary; the result closed.
  void RollingRun::finish(RunResult &result, const SpinStepper &stepper,
                          const rolling::Motion &motion)
  {
    const double t = stepper.time();
    result.strain_profile = model_.strain_profile(0, motion.phi(t), 30.0 * units::deg);
    if (model_.journal_turns_deformable())
      for (const auto &p : model_.strain_profile(1, stepper.gamma(), 30.0 * units::deg))
        result.strain_profile.push_back(p);
    summarise(result.rolling, result.rolling_steps);
    result.sliding_rebuilds = model_.sliding_rebuilds();
    if (rank_ == 0)
      {
        log_solver_summary(parts_.scene, result, stepper, model_.journal_turns_deformable(),
                           model_.sliding_rebuilds());
        log::info("fe_stage: linear solves: " + model_.solver_summary());
      }
    result.complete = result.message.empty();
    // the PVD that indexes the fields with them, as the other studies list it
    result.field_files = parts_.fields.files(result.complete);
    result.wall_time = model_.elapsed();
  }
}  // namespace clearjoint::fe::detail
