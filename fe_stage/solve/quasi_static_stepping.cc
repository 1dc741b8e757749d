// Quasi-static stepping: increments of δ from 0 to δ_max, a linear predictor, step cutting with
// rollback on failure, one log line per increment (as an Abaqus .sta file) with an ETA, and the
// yield check of the last converged state.
#include "fe_stage/core/contact_model.h"

namespace clearjoint::fe::detail
{
  RunResult ContactModel::run()
  {
    RunResult result;
    result.n_ranks = n_ranks_;
    make_grid();
    setup_system();
    find_contact_nodes();
    make_matrices();
    assemble_static();
    compute_nodal_weights();
    result.n_dofs = dof_handler_.n_dofs();
    result.n_cells = tria_.n_global_active_cells();
    result.symmetry_factor = symmetry_factor_;
    result.h_min = h_min_;
    auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    };
    result.setup_time = seconds();
    const bool fields = options_.write_fields && !options_.output_dir.empty();
    if (fields && rank_ == 0)
      std::filesystem::create_directories(options_.output_dir + "/fields");
    const unsigned int n_candidates = Utilities::MPI::sum(
      (unsigned int)std::count_if(nodes_.begin(), nodes_.end(),
                                  [](const ContactNode &c) { return c.owned && c.candidate; }),
      comm_);  // collective: outside the rank-0 branch
    if (rank_ == 0)
      log::info("fe_stage: " + std::to_string(result.n_cells) + " cells, " +
                std::to_string(result.n_dofs) + " DoFs, " + std::to_string(n_candidates) +
                " contact candidate nodes, " + std::to_string(contact_cell_matrices_.size()) +
                " contact cells (rank 0), " + (use_direct_ ? "direct" : "CG+AMG") +
                " solver, setup " + log::format_duration(result.setup_time));

    const auto &L = scene_.loading;
    const double step0 = L.delta_max / L.n_increments;
    solution_owned_ = 0.0;
    solution_ = 0.0;
    if (fields)
      {
        set_obstacle_position(0.0);
        evaluate_contact(0.0);
        write_fields(0, 0.0);
      }
    // One line per converged increment: what an Abaqus user reads in the .sta file. The ETA
    // prices the remaining push at the cost per metre of the increments after the first: the
    // first carries the AMG setup and the cold active set (3–6× a later increment's cost,
    // which made an ETA taken from it overshoot up to 6-fold; docs/benchmarks.md).
    double first_time = 0.0, first_delta = 0.0;
    auto log_increment = [&](const unsigned int inc, const IncrementRecord &r) {
      if (inc == 1)
        {
          first_time = r.wall_time;
          first_delta = r.delta;
        }
      if (rank_ != 0)
        return;
      std::string eta;
      if (inc == 1 && inc < L.n_increments)
        eta = "  ETA after the next increment";
      else if (inc < L.n_increments)
        {
          const double seconds_per_metre = (r.wall_time - first_time) / (r.delta - first_delta);
          eta = "  ETA " + log::format_duration(seconds_per_metre * (L.delta_max - r.delta));
        }
      char buf[320];
      std::snprintf(buf, sizeof(buf),
                    "fe_stage: increment %u/%u  delta %.4g um  F %.6g N  contact its %u  "
                    "linear its %u  active %u (slip %u)  %s%s",
                    inc, L.n_increments, r.delta * 1e6, r.force, r.contact_iterations,
                    r.linear_iterations, r.n_active, r.n_slip,
                    log::format_duration(r.wall_time).c_str(), eta.c_str());
      log::info(buf);
    };
    double delta_done = 0.0, delta_previous = 0.0;
    bool have_previous = false;
    TrilinosWrappers::MPI::Vector solution_previous(owned_, comm_);
    for (unsigned int inc = 1; inc <= L.n_increments; ++inc)
      {
        const double target = (inc == L.n_increments) ? L.delta_max : inc * step0;
        double step = target - delta_done;
        unsigned int cuts = 0;
        IncrementRecord rec;
        unsigned int total_contact_its = 0, total_linear_its = 0;
        while (delta_done < target)
          {
            const double try_delta = std::min(target, delta_done + step);
            // keep what converged so far, to restore after a failed attempt
            const TrilinosWrappers::MPI::Vector saved = solution_owned_;
            const std::vector<ContactNode> saved_nodes = nodes_;  // active set, friction
            try
              {
                // Predictor: extrapolate the displacement linearly in δ from the last two
                // converged states and start with every node the prediction penetrates
                // activated (the active set then mostly settles in one or two iterations).
                if (have_previous && delta_done > delta_previous)
                  {
                    const double ratio = (try_delta - delta_done) / (delta_done - delta_previous);
                    solution_owned_.sadd(1.0 + ratio, -ratio, solution_previous);
                    solution_ = solution_owned_;
                    set_obstacle_position(try_delta);
                    evaluate_contact(try_delta);
                    const double eps_g = 1e-9 * L.delta_max;
                    for (auto &cn : nodes_)
                      if (cn.candidate && cn.gap < -eps_g)
                        cn.active = true;
                  }
                rec = solve_increment(try_delta);
                for (auto &cn : nodes_)
                  cn.relative_converged = cn.relative;  // friction: slip counts from here
                solution_previous = saved;
                delta_previous = delta_done;
                have_previous = true;
                total_contact_its += rec.contact_iterations;
                total_linear_its += rec.linear_iterations;
                delta_done = try_delta;
              }
            catch (const StepFailure &f)
              {
                solution_owned_ = saved;
                solution_ = solution_owned_;
                nodes_ = saved_nodes;
                if (cuts >= L.max_cuts)
                  {
                    result.message = "increment " + std::to_string(inc) + " to delta = " +
                                     format_value(try_delta) + " m failed after " +
                                     std::to_string(cuts) + " cuts: " + f.reason;
                    if (rank_ == 0)
                      log::error("fe_stage: " + result.message);
                    result.wall_time = seconds();
                    result.field_files = field_files_;
                    if (!result.increments.empty())
                      {
                        result.yield_check = check_yield(nullptr);
                        log_yield_check(result.yield_check);
                      }
                    return result;
                  }
                ++cuts;
                step *= 0.5;
                if (rank_ == 0)
                  log::warning("fe_stage: increment " + std::to_string(inc) + " to delta = " +
                               format_value(try_delta) + " m failed (" + f.reason +
                               "); retrying with step " + format_value(step) + " m");
              }
          }
        rec.contact_iterations = total_contact_its;
        rec.linear_iterations = total_linear_its;
        rec.wall_time = seconds();
        result.increments.push_back(rec);
        if (options_.on_increment)
          options_.on_increment(rec);
        if (fields)
          write_fields(inc, target);
        log_increment(inc, rec);
      }
    result.complete = true;
    result.yield_check = check_yield(nullptr);
    log_yield_check(result.yield_check);
    result.wall_time = seconds();
    if (rank_ == 0)
      log::info("fe_stage: time in contact assembly " + log::format_duration(t_assemble_) +
                ", linear solves " + log::format_duration(t_solve_) + " (of which AMG setup " +
                log::format_duration(t_amg_) + "), contact evaluation " +
                log::format_duration(t_evaluate_));
    result.field_files = field_files_;
    if (rank_ == 0 && fields)
      result.field_files.push_back(options_.output_dir + "/fields/solution.pvd");
    return result;
  }
} // namespace clearjoint::fe::detail
