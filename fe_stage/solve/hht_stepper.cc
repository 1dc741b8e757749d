#include "fe_stage/solve/hht_stepper.h"

#include "fe_stage/core/step_failure.h"
#include "fe_stage/solve/root_finder.h"

#include "common/error.h"
#include "common/log.h"

#include <deal.II/base/mpi.h>

namespace clearjoint::fe::detail
{
  HhtStepper::HhtStepper(DynamicProblem &problem, const Parts &parts, const HhtAlpha &hht,
                         const double dt_nominal, const unsigned int max_cuts, const double m_J,
                         const double velocity, const bool deformable_journal)
    : problem_(problem)
    , model_(parts)
    , rank_(Utilities::MPI::this_mpi_process(parts.comm))
    , hht_(hht)
    // Δt: halved on failure, carried over after cuts, doubled back after four easy steps (as
    // Abaqus/Standard's automatic incrementation)
    , control_(dt_nominal, max_cuts, 4)
    , deformable_(deformable_journal)
    , m_J_(m_J)
    , journal_mass_(m_J)
    , dt_(dt_nominal)
    , dt_operator_(dt_nominal)
  {
    problem_.set_dynamic_operator(hht_.coefficients(dt_));
    problem_.start_from_rest();
    for (auto *x : {&u_, &v_, &a_, &lambda_, &u_new_, &v_new_, &a_new_, &lambda_new_, &tmp_,
                    &journal_mask_, &journal_y_})
      x->reinit(model_.dofs.owned(), model_.comm);
    d_rate_ = velocity;
    // A deformable journal: its DoFs (mask), its y-DoFs (the direction of δ), its mass from the
    // FE mass matrix; it starts as a rigid translation at −v e_y. δ is its centre of mass's
    // displacement: −(1_yᵀ M u)/(1_yᵀ M 1_y).
    if (deformable_)
      {
        std::vector<types::global_dof_index> dofs(model_.dofs.fe().n_dofs_per_cell());
        for (const auto &cell : model_.dofs.handler().active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == 1)
            {
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (model_.dofs.owned().is_element(dofs[i]))
                  {
                    journal_mask_[dofs[i]] = 1.0;
                    if (model_.dofs.fe().system_to_component_index(i).first == 1)
                      journal_y_[dofs[i]] = 1.0;
                  }
            }
        journal_mask_.compress(VectorOperation::insert);
        journal_y_.compress(VectorOperation::insert);
        model_.system.mass().vmult(tmp_, journal_y_);
        journal_mass_modelled_ = journal_y_ * tmp_;
        journal_mass_ = model_.bodies.symmetry_factor() * journal_mass_modelled_;
        v_.add(-velocity, journal_y_);
      }
    ledger_.start(0.5 * journal_mass_ * velocity * velocity);
  }

  void HhtStepper::operator_for(const double dt)
  {
    if (dt != dt_operator_)
      {
        problem_.set_dynamic_operator(hht_.coefficients(dt));
        dt_operator_ = dt;
      }
  }

  double HhtStepper::energy(const TrilinosWrappers::SparseMatrix &A,
                            const TrilinosWrappers::MPI::Vector &x, const bool journal_only)
  {
    A.vmult(tmp_, x);
    if (!journal_only)
      return 0.5 * model_.bodies.symmetry_factor() * (x * tmp_);
    TrilinosWrappers::MPI::Vector xm = x;
    xm.scale(journal_mask_);
    return 0.5 * model_.bodies.symmetry_factor() * (xm * tmp_);
  }

  double HhtStepper::centre_of_mass_y(const TrilinosWrappers::MPI::Vector &x)
  {
    model_.system.mass().vmult(tmp_, x);
    return -(journal_y_ * tmp_) / journal_mass_modelled_;
  }

  bool HhtStepper::step(const double end_time, DynamicStepRecord &rec, std::string &message)
  {
    // a given end time is reached exactly: the last step is shortened to it
    double dt = control_.begin_step();
    if (end_time > 0.0 && t_ + dt > end_time * (1.0 + 1e-12))
      dt = control_.begin_step(end_time - t_);
    operator_for(dt);
    Snapshot saved = problem_.save_state();
    saved.u = u_;  // converged
    IncrementRecord inc;
    double d_new = 0.0;
    for (;;)
      {
        try
          {
            d_new = solve_step(dt, rec, inc);
            break;
          }
        catch (const StepFailure &f)
          {
            problem_.restore_state(saved);
            if (!control_.cut())
              {
                message = "time step " + std::to_string(rec.step) + " at t = " + format_value(t_) +
                          " s failed after " + std::to_string(control_.cuts()) + " cuts" +
                          control_.floor_note("s") + ": " + f.reason;
                return false;
              }
            rec.cuts = control_.cuts();
            dt = control_.size();
            operator_for(dt);
            if (rank_ == 0)
              log::warning("fe_stage: time step " + std::to_string(rec.step) + " failed (" +
                           f.reason + "); retrying with dt " + format_value(dt) + " s");
          }
      }
    advance(dt, d_new, inc, rec);
    // after a cut, Δt grows back (doubling, up to its nominal value) once four steps in a row
    // have converged without one
    control_.accept();
    dt_ = control_.next_size();
    operator_for(dt_);
    return true;
  }

  double HhtStepper::solve_step(const double dt, DynamicStepRecord &rec, IncrementRecord &inc)
  {
    const double c_m = hht_.coefficients(dt).mass;
    // the predictor û and the known part b = c_m M û + α(K u_n − λ_n)
    TrilinosWrappers::MPI::Vector u_hat(model_.dofs.owned(), model_.comm);
    hht_.predict(u_, v_, a_, dt, u_hat, HhtAlpha::Predictor::newmark);
    model_.system.mass().vmult(model_.system.load(), u_hat);
    model_.system.load() *= c_m;
    model_.system.elastic_stiffness().vmult(tmp_, u_);
    tmp_ -= lambda_;
    model_.system.load().add(hht_.alpha(), tmp_);
    problem_.set_contact_load_offsets();  // the friction rows read the traction K u − b
    double d_hat = 0.0;
    hht_.predict(d_, d_rate_, d_acc_, dt, d_hat, HhtAlpha::Predictor::newmark);
    model_.state.u_owned() = u_hat;
    model_.state.publish();
    if (deformable_)
      {
        // the journal is part of the FE system: one contact solve (δ from its centre of mass)
        inc = problem_.solve_increment(0.0);
        rec.contact_iterations += inc.contact_iterations;
        rec.linear_iterations += inc.linear_iterations;
        rec.journal_iterations = 1;
        return 0.0;
      }
    // g(δ) = m_J c_m (δ − δ̂) + (1+α)F(δ) − αF_n, F from the contact solve; to 1e-9 of this
    // step's force scale max(g(δ̂), m_J c_m 10⁻³ δ_max) (the linear solves hold the contact
    // force to ~1e-10). From δ̂ (g ≥ 0 there), the second point the step with g's known slope
    // part m_J c_m ≤ g's slope: a bracket.
    auto g = [&](const double delta) {
      inc = problem_.solve_increment(delta);
      rec.contact_iterations += inc.contact_iterations;
      rec.linear_iterations += inc.linear_iterations;
      return m_J_ * c_m * (delta - d_hat) + inc.force - hht_.alpha() * F_;
    };
    IncreasingRoot position{g, 1e-9, 0.0, 60, "the journal's position"};
    position.g_scale_from_first = true;
    position.g_scale_floor = m_J_ * c_m * 1e-3 * model_.scene.loading.delta_max;
    const RootResult root = solve_increasing_from(position, d_hat, m_J_ * c_m);
    if (!root.converged)
      throw StepFailure{root.message};
    rec.journal_iterations = root.evaluations;
    return root.x;  // the last evaluation: the model's state is this one
  }

  void HhtStepper::advance(const double dt, double d_new, const IncrementRecord &inc,
                           DynamicStepRecord &rec)
  {
    // the Newmark updates, the new contact forces
    u_new_ = model_.state.u_owned();
    hht_.update_rates(u_new_, u_, v_, a_, dt, v_new_, a_new_);
    lambda_new_ = model_.state.forces();  // (1+α)λ_{n+1} at the constrained DoFs
    lambda_new_ *= 1.0 / hht_.weight_new();
    const double F_new = inc.force / hht_.weight_new();
    double d_rate_new = 0.0, d_acc_new = 0.0;
    if (deformable_)
      {
        d_new = centre_of_mass_y(u_new_);
        d_rate_new = centre_of_mass_y(v_new_);
        d_acc_new = centre_of_mass_y(a_new_);
      }
    else
      hht_.update_rates(d_new, d_, d_rate_, d_acc_, dt, d_rate_new, d_acc_new);
    // net work of the contact forces: on the meshed bodies (λ at the contact DoFs, and at a
    // deformable journal's mortar partners; the supports do not move) and on a rigid journal
    // (F e_y along its displacement −δ e_y)
    const double sym = model_.bodies.symmetry_factor();
    const double w_bodies = sym * trapezoidal_work(u_new_, u_, lambda_new_, lambda_);
    const double w_journal = deformable_ ? 0.0 : -0.5 * (d_new - d_) * (F_ + F_new);
    work_contact_ += w_bodies + w_journal;
    // the energies
    const double strain_total = energy(model_.system.elastic_stiffness(), u_new_, false);
    const double strain_j =
      deformable_ ? energy(model_.system.elastic_stiffness(), u_new_, true) : 0.0;
    const double kinetic_total = energy(model_.system.mass(), v_new_, false);
    const double kinetic_fe_journal =
      deformable_ ? energy(model_.system.mass(), v_new_, true) : 0.0;
    const double kinetic_b = kinetic_total - kinetic_fe_journal;
    const double kinetic_j =
      deformable_ ? kinetic_fe_journal : 0.5 * m_J_ * d_rate_new * d_rate_new;
    const double strain_old = ledger_.work_internal;
    ledger_.add_step(kinetic_b + kinetic_j, strain_total - strain_old, w_bodies + w_journal);
    // the state advanced
    t_ += dt;
    u_ = u_new_;
    v_ = v_new_;
    a_ = a_new_;
    lambda_ = lambda_new_;
    d_ = d_new;
    d_rate_ = d_rate_new;
    d_acc_ = d_acc_new;
    F_ = F_new;
    for (auto &cn : model_.contact.nodes())
      cn.relative_converged = cn.relative;

    rec.time = t_;
    rec.time_step = dt;
    rec.delta = d_;
    rec.delta_rate = d_rate_;
    rec.force = F_;
    rec.force_support = inc.force_support / hht_.weight_new();
    rec.kinetic_journal = kinetic_j;
    rec.kinetic_bearing = kinetic_b;
    rec.strain_bearing = strain_total - strain_j;
    rec.strain_journal = strain_j;
    rec.work_contact = work_contact_;
    rec.numerical_dissipation = ledger_.dissipation;
    rec.n_active = inc.n_active;
  }
}  // namespace clearjoint::fe::detail
