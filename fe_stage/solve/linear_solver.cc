// Linear solves: MUMPS below a size, else CG (GMRES when friction makes A non-symmetric) with ML AMG
// on the six rigid-body modes, built again once its staleness has cost more than a build
// (checked within a solve too: a solve gone stale goes on from its iterate with a fresh AMG).
#include "fe_stage/solve/linear_solver.h"

#include "fe_stage/core/scoped_timer.h"
#include "fe_stage/core/step_failure.h"

#include "common/error.h"
#include "common/log.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <Epetra_Map.h>
#include <Teuchos_ParameterList.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  namespace
  {
    /// [bytes] the memory this machine has free for a new allocation (/proc/meminfo's
    /// MemAvailable; 0 where it cannot be read, so that nothing large is tried).
    double available_memory()
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string key;
      double kb = 0.0;
      while (meminfo >> key >> kb)
        {
          if (key == "MemAvailable:")
            return 1024.0 * kb;
          meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
        }
      return 0.0;
    }

    /// The Krylov solve's control with the AMG's staleness (solve/amg_staleness.h): given the
    /// staleness record, it stops the solve as failed once the AMG has lost more iterations
    /// than a build costs, so that the caller builds a fresh one and goes on from the iterate.
    class StaleAmgControl : public SolverControl
    {
    public:
      StaleAmgControl(const unsigned int max_steps, const double tolerance,
                      const AmgStaleness *staleness)
        : SolverControl(max_steps, tolerance, false, false)
        , staleness_(staleness)
      {}
      State check(const unsigned int step, const double value) override
      {
        const State state = SolverControl::check(step, value);
        if (state == iterate && staleness_ != nullptr &&
            staleness_->stale_within(step, initial_value(), value))
          {
            stopped_as_stale_ = true;
            lcheck = failure;
          }
        return lcheck;
      }
      bool stopped_as_stale() const { return stopped_as_stale_; }

    private:
      const AmgStaleness *staleness_;
      bool stopped_as_stale_ = false;
    };
  }  // namespace

  void SystemSolver::configure(const bool direct, const unsigned int max_iterations)
  {
    direct_ = direct;
    max_iterations_ = max_iterations;
  }

  void SystemSolver::build_amg(const TrilinosWrappers::SparseMatrix &A, const DoFHandler<dim> &dofs,
                               const Mapping<dim> &mapping)
  {
    ScopedTimer timer(t_amg_);
    const auto &fe = dofs.get_fe();
    const IndexSet &owned = dofs.locally_owned_dofs();
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = fe.degree > 1;
    data.smoother_sweeps = 2;
    // every connection strong: coarser aggregates, a cheaper setup and V-cycle than 0.02 for
    // the more iterations they take (t_B = 8 mm, standard: 3 557 iterations against 3 291,
    // 230 s against 257 s of CPU; 1.5 GB against 1.8 GB), and with rebuilds when stale the
    // cheaper setup is what pays (156 s against 187 s; docs/benchmarks.md "The AMG rebuilt
    // when stale")
    data.aggregation_threshold = 0.0;
    data.n_cycles = 1;
    data.w_cycle = false;
    Teuchos::ParameterList list;
    std::unique_ptr<Epetra_MultiVector> translation_modes;
    data.set_parameters(list, translation_modes, A);

    // All six rigid-body modes (SPEC §5: with only the translations ML needs ~3x the
    // iterations). deal.II 9.4 passes only translations, so they go in through ML's list.
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(mapping, dofs, support);
    const Epetra_Map &map = A.trilinos_matrix().DomainMap();
    null_space_ = std::make_unique<Epetra_MultiVector>(map, 6);
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
          cell->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < cell_dofs.size(); ++i)
            if (owned.is_element(cell_dofs[i]))
              {
                const unsigned int local = owned.index_within_set(cell_dofs[i]);
                const unsigned int c = fe.system_to_component_index(i).first;
                const Point<dim> &x = support.at(cell_dofs[i]);
                for (unsigned int m = 0; m < 6; ++m)
                  (*null_space_)[m][local] = 0.0;
                (*null_space_)[c][local] = 1.0;
                // rotations about x, y, z: ω × x
                if (c == 0)
                  {
                    (*null_space_)[4][local] = x[2];
                    (*null_space_)[5][local] = -x[1];
                  }
                else if (c == 1)
                  {
                    (*null_space_)[3][local] = -x[2];
                    (*null_space_)[5][local] = x[0];
                  }
                else
                  {
                    (*null_space_)[3][local] = x[1];
                    (*null_space_)[4][local] = -x[0];
                  }
              }
        }
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", 6);
    list.set("null space: vectors", null_space_->Values());
    amg_ = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg_->initialize(A, list);
    staleness_.built();
    ++n_amg_builds_;
  }

  unsigned int SystemSolver::solve(const TrilinosWrappers::SparseMatrix &A, const bool nonsymmetric,
                                   const DoFHandler<dim> &dofs, const Mapping<dim> &mapping,
                                   TrilinosWrappers::MPI::Vector &x,
                                   const TrilinosWrappers::MPI::Vector &b,
                                   const double relative_tolerance)
  {
    const double b_norm = b.l2_norm();
    if (!std::isfinite(b_norm))
      throw StepFailure{"non-finite right-hand side"};
    if (b_norm == 0.0)
      {
        x = 0.0;
        return 0;
      }
    if (direct_)
      return solve_direct(A, x, b, relative_tolerance * b_norm);
    if (amg_ && staleness_.stale())
      amg_.reset();  // the iterations it has lost since its build outweigh a new one
    unsigned int spent = 0;  // Krylov iterations of a first attempt that was stopped
    for (unsigned int attempt = 0; attempt < 2; ++attempt)
      {
        if (!amg_)
          build_amg(A, dofs, mapping);
        // the first attempt stops once its AMG has lost a build's worth of iterations; the
        // second, with a fresh AMG from the first's iterate (x), runs to the end
        StaleAmgControl control(max_iterations_, relative_tolerance * b_norm,
                                attempt == 0 ? &staleness_ : nullptr);
        SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
        SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
          control,  // right preconditioning: the tolerance applies to the true residual
          SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(100, true));
        try
          {
            if (nonsymmetric)
              gmres.solve(A, x, b, *amg_);
            else
              cg.solve(A, x, b, *amg_);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            spent += e.last_step;
            if (attempt == 0)
              {
                // stopped as stale, or out of iterations with a reused preconditioner that
                // may be stale: rebuild once and go on from the iterate reached
                if (control.stopped_as_stale())
                  ++n_stale_stops_;
                amg_.reset();
                continue;
              }
            const std::string failure = std::string(nonsymmetric ? "GMRES" : "CG") +
                                        " did not converge in " + std::to_string(e.last_step) +
                                        " iterations (residual " + format_value(e.last_residual) +
                                        ")";
            // A system the AMG cannot precondition (the rolling study's elastoplastic
            // tangent with friction rows at large plastic strain, measured at 7 k DoFs; an
            // adaptive mesh's at 242 k DoFs, the thickness study at t_B = 6 mm) is solved
            // exactly by MUMPS instead of cutting the step — where MUMPS's own estimate of
            // its factorization's memory fits in what the machine has free
            const double needed = direct_fallback_memory_margin * direct_solver_.analyse(A);
            const double available = Utilities::MPI::broadcast(
              A.get_mpi_communicator(), available_memory(), 0);
            if (needed > available)
              throw StepFailure{failure + "; the direct solver (MUMPS) is not tried: it would " +
                                "need " + format_value(needed / 1e9) + " GB, " +
                                format_value(available / 1e9) + " GB are free"};
            if (n_direct_fallbacks_++ == 0 &&
                Utilities::MPI::this_mpi_process(A.get_mpi_communicator()) == 0)
              log::warning("fe_stage: " + failure +
                           ": solved by the direct solver (MUMPS, " +
                           std::to_string(A.m()) + " DoFs, " + format_value(needed / 1e9) +
                           " GB of the " + format_value(available / 1e9) +
                           " GB free) instead, here and wherever the iterative solver fails "
                           "again");
            direct_solver_.solve(A, x, b);
            return spent;  // (the Krylov iterations spent)
          }
        const unsigned int its = control.last_step();
        staleness_.record(its, control.initial_value(), control.last_value());
        return spent + its;
      }
    throw StepFailure{"linear solver failed"};
  }

  std::string SystemSolver::summary() const
  {
    if (!direct_)
      return "AMG setup " + log::format_duration(t_amg_) + " in " + std::to_string(n_amg_builds_) +
             " builds" +
             (n_stale_stops_ > 0 ?
                ", " + std::to_string(n_stale_stops_) + " of them within a solve gone stale" :
                std::string());
    return "MUMPS: " + std::to_string(direct_solver_.n_factorizations()) + " factorizations, " +
           std::to_string(n_same_matrix_solves_) + " solves of the factored matrix, " +
           std::to_string(n_gmres_on_kept_factors_) +
           " by GMRES on the kept factors of an earlier one (" +
           std::to_string(n_factorization_reuse_failures_) + " such tries gave up)";
  }

  namespace
  {
    /// The kept factorization as a preconditioner (deal.II's solvers call vmult).
    struct KeptFactorization
    {
      const DirectSolver &lu;
      void vmult(TrilinosWrappers::MPI::Vector &dst, const TrilinosWrappers::MPI::Vector &src) const
      {
        lu.apply(dst, src);
      }
    };

    /// GMRES's control with the kept factors: it gives up as soon as the residual's mean rate
    /// over the iterations so far would need more than the allowed ones, so that a
    /// factorization too far from the matrix costs a few iterations, not all of them.
    class ForecastControl : public SolverControl
    {
    public:
      ForecastControl(const unsigned int max_steps, const double tolerance)
        : SolverControl(max_steps, tolerance, false, false)
      {}
      State check(const unsigned int step, const double value) override
      {
        const State state = SolverControl::check(step, value);
        if (state == iterate && FactorizationReuse::forecast_exceeds(step, initial_value(), value,
                                                                     tolerance(), max_steps()))
          lcheck = failure;
        return lcheck;
      }
    };
  }  // namespace

  unsigned int SystemSolver::solve_direct(const TrilinosWrappers::SparseMatrix &A,
                                          TrilinosWrappers::MPI::Vector &x,
                                          const TrilinosWrappers::MPI::Vector &b,
                                          const double tolerance)
  {
    if (direct_solver_.holds_pattern_of(A))
      {
        if (direct_solver_.holds_values_of(A))
          {
            direct_solver_.apply(x, b);
            ++n_same_matrix_solves_;
            return 1;
          }
        if (reuse_.worth_reusing())
          {
            // GMRES on A with the factorization of an earlier matrix of this pattern: the
            // matrix moved by a few contact rows or a plastic tangent's update, so a few
            // iterations replace a factorization (solve/factorization_reuse.h)
            ForecastControl control(FactorizationReuse::max_iterations_per_solve, tolerance);
            SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
              control,  // right preconditioning: the tolerance applies to the true residual
              SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(
                FactorizationReuse::max_iterations_per_solve + 2, true));
            try
              {
                gmres.solve(A, x, b, KeptFactorization{direct_solver_});
                reuse_.record(control.last_step());
                ++n_gmres_on_kept_factors_;
                return control.last_step();
              }
            catch (const SolverControl::NoConvergence &)
              {
                ++n_factorization_reuse_failures_;  // factored afresh below (x is overwritten)
              }
          }
      }
    direct_solver_.factor(A);
    reuse_.factored(direct_solver_.factorization_flops(), direct_solver_.factor_entries(),
                    double(A.n_nonzero_elements()));
    direct_solver_.apply(x, b);
    return 1;
  }
}  // namespace clearjoint::fe::detail
