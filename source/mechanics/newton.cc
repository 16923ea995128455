// The Newton–Raphson solve of one step of MechanicalProblem: linear solves,
// convergence tests, line search (its first iterate: predictor.cc).
#include <deal.II/base/utilities.h>
#include <deal.II/lac/solver_control.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/first_message.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include "evaluation_kinds.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

namespace anvil
{
  using namespace dealii;

  using evaluation_kinds::evaluate;

  namespace
  {
    /// The line search's full-step trial (it keeps α = 1 when |s(1)| <= 0.8
    /// |s(0)|, s(α) = δu · R(u + α δu)) on the residual alone. True: u + δu
    /// kept with R evaluated there; false: u restored, the line search as ever.
    template <typename EvaluateResidual>
    bool full_step_on_residual(TrilinosWrappers::MPI::Vector       &u,
                               TrilinosWrappers::MPI::Vector       &u_ghosted,
                               const TrilinosWrappers::MPI::Vector &du,
                               const TrilinosWrappers::MPI::Vector &rhs,
                               TrilinosWrappers::MPI::Vector       &u_start,
                               EvaluateResidual                   &&evaluate_residual)
    {
      const double s0 = -(du * rhs);
      u_start         = u;
      u.add(1., du);
      u_ghosted = u;
      if (evaluate_residual())
        {
          const double s1 = -(du * rhs);
          if (std::isfinite(s1) && std::abs(s1) <= 0.8 * std::abs(s0))
            return true;
        }
      u         = u_start;
      u_ghosted = u;
      return false;
    }
    /**
     * c.distribute(du) for an owned vector. Lines without masters (supports,
     * the predictor's jumps) only set their owned entries to the
     * inhomogeneity; deal.II 9.4's distribute() first imports a ghosted copy
     * of du through a new vector and Epetra_Import (~60 000 instructions on
     * the tube), which only lines with masters (hanging nodes) read. Those
     * keep deal.II's route; the result is the same either way.
     */
    void distribute_constraints(const AffineConstraints<double> &c, TrilinosWrappers::MPI::Vector &du)
    {
      bool masters = false;
      for (const auto &line : c.get_lines())
        if (!line.entries.empty())
          {
            masters = true;
            break;
          }
      if (Utilities::MPI::max(masters ? 1 : 0, du.get_mpi_communicator()) == 1)
        {
          c.distribute(du);
          return;
        }
      // As deal.II writes them (its ElementAccess): by local index, then compress.
      Epetra_FEVector &values = du.trilinos_vector();
      for (const auto &line : c.get_lines())
        {
          const int k = values.Map().LID(static_cast<int>(line.index));
          if (k >= 0)
            values[0][k] = line.inhomogeneity;
        }
      du.compress(VectorOperation::insert);
    }

    /**
     * What the residual's contraction predicts of the next convergence test:
     * quadratic convergence puts the next residual at r (r / r_prev)². An
     * iteration whose prediction was wrong in the last two steps (bit it of
     * @p distrusted) acts on it no more, until a step shows it right again:
     * the cantilever's first update from its extrapolated predictor
     * contracts the residual by 3e-4, the next one only by 6e-4, so the
     * residual-only evaluations this asked for failed at 13 of its 20 steps,
     * each followed by a full assembly at the same state.
     */
    struct NextTest
    {
      bool quadratic = false; // within a tenth of the tolerance: the full step, no line search
      bool likely    = false; // that, trusted: the residual alone (K only if the test fails)
      bool possible  = false; // within the tolerance, trusted: the evaluation sums the audit's terms
    };

    NextTest predict_next_test(const unsigned int it, const double r, const double r_previous,
                               const double tolerance, const unsigned int distrusted)
    {
      const double contraction = r / std::max(r_previous, 1e-300);
      const double predicted   = it > 0 && contraction < 0.5 ? r * contraction * contraction :
                                                              std::numeric_limits<double>::infinity();
      const bool   trusted     = it >= 32 || (distrusted >> it & 1u) == 0;
      NextTest     next;
      next.quadratic = predicted <= 0.1 * tolerance;
      next.likely    = next.quadratic && trusted;
      next.possible  = predicted <= tolerance && trusted;
      return next;
    }

    struct ConvergenceTest
    {
      bool residual_ok = false; // the residual alone is small enough
      bool converged   = false;
    };

    /// Newton's convergence test at residual @p r: the residual (absolute,
    /// relative to the force @p scale, or on its round-off floor) and the
    /// next correction, predicted from the last one @p last_increment (< 0:
    /// none yet) and the residual's contraction, below the displacement
    /// tolerance. The first iterate of a step whose boundary values jump
    /// (@p with_jump) is never accepted.
    template <typename Parameters, typename Floor>
    ConvergenceTest test_convergence(const Parameters &parameters, const double r,
                                     const double r_previous, const double scale,
                                     const double du_scale, const double last_increment,
                                     const double increment_floor, const bool first_iterate,
                                     const bool with_jump, Floor &&residual_floor)
    {
      ConvergenceTest test;
      // Below the round-off floor of u's digits no tolerance can be met
      // (residual_floor.cc). The floor is ε-relative: a residual above 1e-3
      // of the force scale is never on it, and the floor (a pass over the
      // matrix diagonal) is only worth computing in the last iterations.
      test.residual_ok = r <= parameters.absolute_residual_tolerance ||
                         r <= parameters.residual_tolerance * scale ||
                         (r <= 1e-3 * scale && r <= residual_floor());
      // The correction that would come next is about the last one times the
      // residual's contraction (quadratic convergence makes this sharp):
      // test that instead of paying one more solve to see it.
      const double predicted_increment =
        last_increment * std::min(1.0, r / std::max(r_previous, 1e-300));
      const bool increment_ok =
        (last_increment >= 0 &&
         predicted_increment <= std::max({parameters.displacement_tolerance * du_scale,
                                          parameters.absolute_displacement_tolerance,
                                          increment_floor})) ||
        r <= parameters.absolute_residual_tolerance;
      // Corrections a thousand times below the increment tolerance mean the
      // residual sits on its round-off floor: accept.
      const bool stagnated =
        last_increment >= 0 &&
        last_increment <= std::max(1e-3 * parameters.displacement_tolerance * du_scale,
                                   increment_floor) &&
        r <= 1e3 * parameters.residual_tolerance * scale;
      test.converged =
        (test.residual_ok && (increment_ok || first_iterate) && !(first_iterate && with_jump)) ||
        stagnated;
      return test;
    }
  } // namespace

  template <int dim>
  std::string MechanicalProblem<dim>::material_failure_message() const
  {
    // The first rank that failed tells (all ranks return the same text).
    const std::string first = first_message(material_failure, mpi_communicator);
    return first.empty() ? "an element inverted (J <= 0)" : first;
  }

  template <int dim>
  double MechanicalProblem<dim>::residual_norm() const
  {
    return system_rhs.l2_norm();
  }

  template <int dim>
  typename MechanicalProblem<dim>::StepResult
  MechanicalProblem<dim>::solve_step(const double time_old, const double time_new,
                                     const bool from_last_solution)
  {
    // The whole step's Newton solve (contact step, pattern, predictor,
    // iterations): the cost per iteration perf.py sets against one assembly
    // and one linear solve.
    TimerOutput::Scope timed(timer, "Mechanics: Newton solve");
    StepResult result;
    current_time_step = time_new - time_old;
    current_time      = time_new;
    if (contact)
      {
        contact->begin_step(time_old, time_new, old_solution);
        if (contact->couplings_changed())
          setup_matrix();
      }

    // K and R already assembled at the current iterate (by the predictor's
    // check of the extrapolated state, or the line search's full-step trial):
    // the iteration costs one assembly, not one plus a residual evaluation at
    // the same state.
    bool       assembled = false;
    const bool has_jump  = predict(time_old, time_new, from_last_solution, &assembled);

    // Of system_rhs's layout: copies among the vectors are plain copies.
    TrilinosWrappers::MPI::Vector &du = owned_work(work_increment);
    double last_increment = -1;
    // When the next test will almost surely converge (quadratic phase, see
    // predict_next_test()), the full step's state is evaluated for its
    // residual only, and the matrix assembled only if that test fails after
    // all: the matrix of the last evaluation of a step is never used.
    bool residual_only = false;
    // A step like the last one, which converged at its first update (a
    // nearly linear response), will likely too: the line search's trial of
    // that update and the convergence test after it are on the residual
    // alone, as in the quadratic phase (K only if the test fails).
    const bool one_update_expected = last_step_iterations == 1;
    last_step_iterations           = 0;
    // Iterations whose prediction was wrong in each of the last two steps
    // (predict_next_test(); one alone may be a first step's start).
    const unsigned int distrusted  = mispredicted & mispredicted_before;
    mispredicted_before            = mispredicted;
    mispredicted                   = 0;
    bool quadratic_prediction      = false; // made at the last iteration, acted on or not
    bool residual_ready            = false; // R (not K) already at the iterate
    // An evaluation the next convergence test will likely accept sums the
    // energy audit's terms of its state (kept_audit), so that commit_step()
    // need not visit the cells again; where none did, it does (the terms cost
    // ~0.6 of a residual evaluation: not at every evaluation).
    bool       audit        = false;
    bool       may_converge = false; // quadratic convergence puts the next residual below tolerance
    const auto at_new       = [&](const bool with_matrix) {
      return assemble(with_matrix, time_new, audit);
    };
    for (unsigned int it = 0;; ++it)
      {
        audit = residual_only || may_converge;
        if (!assembled && !residual_ready && !evaluate(!residual_only, at_new))
          {
            result.failure = material_failure_message();
            return result;
          }
        residual_ready = false;
        const double r = residual_norm();
        if (!std::isfinite(r))
          {
            result.failure = "the residual is not a number";
            return result;
          }
        result.residuals.push_back(r);
        if (parameters.check_tangent)
          {
            const double e = tangent_error();
            if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              std::cout << "    tangent check: |K du - FD| / |K du| = " << e << std::endl;
            assemble(true, time_new); // restore K and R at u
          }
        // Force scale: the forces of the step, and the first residual of the
        // step (in dynamics the inertia of the predictor dominates it, and
        // round-off of M ã is relative to it).
        const double scale = std::max({internal_force.l2_norm(), external_force.l2_norm(),
                                       inertia_force.l2_norm(), result.residuals.front()});
        // The step's displacement so far, in du (free until the next solve):
        // a copy into a vector of the same layout object, not a new vector.
        du = owned_solution;
        du -= owned_old_solution;
        const double du_scale = du.l2_norm();
        const double r_previous = result.residuals.size() > 1 ?
                                    result.residuals[result.residuals.size() - 2] : r;
        // Corrections cannot fall below round-off of the displacement itself.
        // (positions x = X + u carry the digits, so the scale is the mesh size).
        const double increment_floor =
          100 * std::numeric_limits<double>::epsilon() *
          (owned_solution.l2_norm() + std::sqrt(double(dof_handler.n_dofs())) * mesh_diameter);
        const ConvergenceTest test =
          test_convergence(parameters, r, r_previous, scale, du_scale, last_increment,
                           increment_floor, it == 0, has_jump, [&] { return residual_floor(); });
        const bool residual_ok = test.residual_ok;
        if (quadratic_prediction && !test.converged && it <= 32)
          mispredicted |= 1u << (it - 1);
        if (test.converged)
          {
            result.converged     = true;
            result.iterations    = it;
            last_step_iterations = it;
            return result;
          }
        if (it >= parameters.max_iterations)
          {
            result.iterations = it;
            result.failure    = "Newton did not converge in " + std::to_string(it) +
                             " iterations (|R| = " + Utilities::to_string(r, 3) + " N)";
            return result;
          }
        audit = false; // (the state just tested, now with the matrix)
        if (residual_only && !assembled && !evaluate(true, at_new))
          {
            result.failure = material_failure_message();
            return result;
          }

        du = 0;
        try
          {
            result.linear_iterations += solve_linear_system(du);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            // Work the run paid: summary.json counts it (the 2D 512² block's
            // stalled solves were missing from its figure, session 25).
            result.linear_iterations += e.last_step;
            char residual[32];
            std::snprintf(residual, sizeof residual, "%.3g", e.last_residual);
            result.failure = "the linear solver did not converge in " + std::to_string(e.last_step) +
                             " iterations (|r| = " + residual + " N)";
            return result;
          }
        catch (const std::exception &e)
          {
            result.failure = "the linear solver failed";
            return result;
          }
        distribute_constraints(*active_constraints, du);
        active_constraints = &constraints;
        last_increment     = du.l2_norm();
        result.increments.push_back(last_increment);

        // A predicted convergence takes the full step without the line
        // search's trial (which accepts α = 1 there anyway).
        const NextTest next = predict_next_test(
          it, r, r_previous,
          std::max(parameters.absolute_residual_tolerance, parameters.residual_tolerance * scale),
          distrusted);
        quadratic_prediction = next.quadratic;
        may_converge         = next.possible;
        // The first update carries the boundary jump: take it whole.
        // Near convergence (and on the round-off floor) s(α) is noise.
        const bool full_step = (it == 0 && has_jump) || residual_ok || next.quadratic;
        audit = true; // (a step like the last, converged at its first update)
        if (it == 0 && one_update_expected && !full_step && parameters.line_search)
          residual_ready = full_step_on_residual(owned_solution, solution, du, system_rhs,
                                                 owned_work(work_start),
                                                 [&] { return evaluate(false, at_new); });
        if (residual_ready)
          {
            result.line_search_steps.push_back(1.);
            assembled = false;
          }
        else
          {
            // Far from convergence (the pre-quadratic iterations of yielding
            // hinges, whose plastic tangent overshoots the points that unload)
            // the scene may ask for a stricter search; near it s(α) is noise.
            const double bound = r > 0.1 * result.residuals.front() ?
                                   parameters.line_search_far_bound : 0.8;
            result.line_search_steps.push_back(
              line_search(du, full_step, time_new, assembled, bound, may_converge));
          }
        residual_only =
          (residual_ok || next.likely || (it == 0 && one_update_expected)) && !assembled;
      }
  }

  template <int dim>
  double MechanicalProblem<dim>::line_search(const TrilinosWrappers::MPI::Vector &du,
                                            const bool full_step, const double time_new,
                                            bool &assembled, const double bound, const bool audit)
  {
    // Line search on the energy norm s(α) = δu · R(u + α δu) (Crisfield):
    // the residual norm itself grows in the first iterations of large
    // rotations although the step is good, so it is a poor merit function.
    // A full step is kept unless |s(1)| > bound |s(0)| (0.8 by default) or an
    // element inverts; then α follows the secant root of s, within [0.1, 1].
    // The full step is tried with the matrix: it is kept far more often than
    // not, and then the next iteration needs K and R at exactly this state.
    TrilinosWrappers::MPI::Vector &u_start = owned_work(work_start);
    u_start                                = owned_solution;
    double       alpha = 1;
    const double s0    = -(du * system_rhs);
    assembled          = false;
    for (unsigned int ls = 0;; ++ls)
      {
        owned_solution = u_start;
        owned_solution.add(alpha, du);
        solution  = owned_solution;
        assembled = false;
        if (!parameters.line_search || ls == 5 || full_step)
          break;
        const bool ok =
          evaluate(ls == 0, [&](bool m) { return assemble(m, time_new, audit && ls == 0); });
        assembled     = ok && ls == 0;
        if (!ok)
          {
            alpha *= 0.5;
            continue;
          }
        const double s1 = -(du * system_rhs);
        if (!std::isfinite(s1))
          {
            alpha *= 0.5;
            continue;
          }
        if (std::abs(s1) <= bound * std::abs(s0))
          break;
        // Secant root of s between (0, s0) and (α, s1). If s has not changed
        // sign and grows in magnitude the root lies beyond α: keep α.
        const double next = alpha * s0 / (s0 - s1);
        if (!(next > 0) || next >= alpha)
          break;
        alpha = std::max(0.1 * alpha, next);
      }
    return alpha;
  }

  template <int dim>
  bool MechanicalProblem<dim>::begin_step(const double time_old, const double time_new)
  {
    current_time_step = time_new - time_old;
    current_time      = time_new;
    if (contact)
      {
        contact->begin_step(time_old, time_new, old_solution);
        if (contact->couplings_changed())
          setup_matrix();
      }
    return predict(time_old, time_new, false);
  }

  template <int dim>
  bool MechanicalProblem<dim>::predictor_update(unsigned int &linear_iterations)
  {
    if (!evaluate(true, [&](bool m) { return assemble(m, current_time); }))
      return false;
    TrilinosWrappers::MPI::Vector &du = owned_work(work_increment);
    du                                = 0;
    linear_iterations += solve_linear_system(du);
    distribute_constraints(*active_constraints, du);
    active_constraints = &constraints;
    owned_solution += du;
    solution = owned_solution;
    return true;
  }

  template <int dim>
  TrilinosWrappers::MPI::Vector &MechanicalProblem<dim>::owned_work(TrilinosWrappers::MPI::Vector &v)
  {
    // A vector reinit from system_rhs shares its map's data (operator='s
    // plain copy); setup() makes a new map.
    if (v.trilinos_vector().Map().DataPtr() != system_rhs.trilinos_vector().Map().DataPtr())
      v.reinit(system_rhs);
    return v;
  }

  template <int dim>
  void MechanicalProblem<dim>::set_displacement(const TrilinosWrappers::MPI::Vector &u_owned)
  {
    owned_solution = u_owned;
    solution       = owned_solution;
  }

  template <int dim>
  double MechanicalProblem<dim>::force_scale() const
  {
    return std::max({internal_force.l2_norm(), external_force.l2_norm(), inertia_force.l2_norm()});
  }

  template <int dim>
  void MechanicalProblem<dim>::revert_step()
  {
    kept_audit.evaluation = 0; // the points' last update is forgotten
    for (auto &p : points.raw())
      if (p)
        p->revert();
    owned_solution = owned_old_solution;
    solution       = owned_solution;
  }

#define INSTANTIATE(dim)                                                                         \
  template std::string  MechanicalProblem<dim>::material_failure_message() const;                \
  template double       MechanicalProblem<dim>::residual_norm() const;                           \
  template typename MechanicalProblem<dim>::StepResult MechanicalProblem<dim>::solve_step(       \
    double, double, bool);                                                                       \
  template double MechanicalProblem<dim>::line_search(const TrilinosWrappers::MPI::Vector &,     \
                                                      bool, double, bool &, double, bool);       \
  template void   MechanicalProblem<dim>::revert_step();                                          \
  template bool   MechanicalProblem<dim>::begin_step(double, double);                            \
  template bool   MechanicalProblem<dim>::predictor_update(unsigned int &);                      \
  template void   MechanicalProblem<dim>::set_displacement(const TrilinosWrappers::MPI::Vector &); \
  template TrilinosWrappers::MPI::Vector &MechanicalProblem<dim>::owned_work(                   \
    TrilinosWrappers::MPI::Vector &);                                                            \
  template double MechanicalProblem<dim>::force_scale() const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
