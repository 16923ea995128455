// The Newton–Raphson solve of one step of MechanicalProblem: predictor,
// linear solves, convergence tests, line search; the finite-difference check
// of the tangent.
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/first_message.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <cmath>
#include <iostream>
#include <limits>

namespace anvil
{
  using namespace dealii;

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

    // Distinct symbols for the two kinds of evaluation, which assemble()
    // does not tell apart by name: callgrind counts the assemblies with the
    // tangent apart from the residual-only ones (contrib/bench/instruction_ratio.py).
    template <typename Assemble>
    [[gnu::noinline]] bool tangent_assembly(const Assemble &assemble) { return assemble(true); }
    template <typename Assemble>
    [[gnu::noinline]] bool residual_assembly(const Assemble &assemble) { return assemble(false); }
    template <typename Assemble>
    bool evaluate(const bool with_matrix, const Assemble &assemble)
    {
      return with_matrix ? tangent_assembly(assemble) : residual_assembly(assemble);
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
  double MechanicalProblem<dim>::tangent_error()
  {
    // Random direction on the free dofs; K is assembled at the current u.
    TrilinosWrappers::MPI::Vector du;
    du.reinit(system_rhs);
    TrilinosWrappers::MPI::Vector Kdu(du), r_plus(du);
    for (const auto i : locally_owned_dofs)
      du(i) = std::sin(1.0 + 7.3 * i);
    du.compress(VectorOperation::insert);
    constraints.set_zero(du);
    assemble(true, current_time);
    system_matrix.vmult(Kdu, du);
    constraints.set_zero(Kdu);
    const TrilinosWrappers::MPI::Vector u0 = owned_solution;
    const double h = 1e-7 * std::max(1.0, u0.l2_norm()) / std::max(du.l2_norm(), 1e-300);
    owned_solution.add(h, du);
    solution = owned_solution;
    assemble(false, current_time);
    r_plus = system_rhs; // −R(u + h du)
    owned_solution = u0;
    owned_solution.add(-h, du);
    solution = owned_solution;
    assemble(false, current_time);
    r_plus -= system_rhs; // −R(u+) + R(u−)
    r_plus /= -2 * h;     // (R(u+) − R(u−)) / 2h ≈ K du
    owned_solution = u0;
    solution       = owned_solution;
    r_plus -= Kdu;
    return r_plus.l2_norm() / std::max(Kdu.l2_norm(), 1e-300);
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
    // likely_converged below), the full step's state is evaluated for its
    // residual only, and the matrix assembled only if that test fails after
    // all: the matrix of the last evaluation of a step is never used.
    bool residual_only = false;
    // A step like the last one, which converged at its first update (a
    // nearly linear response), will likely too: the line search's trial of
    // that update and the convergence test after it are on the residual
    // alone, as in the quadratic phase (K only if the test fails).
    const bool one_update_expected = last_step_iterations == 1;
    last_step_iterations           = 0;
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
        catch (const std::exception &e)
          {
            result.failure = "the linear solver failed";
            return result;
          }
        distribute_constraints(*active_constraints, du);
        active_constraints = &constraints;
        last_increment     = du.l2_norm();
        result.increments.push_back(last_increment);

        // Quadratic convergence predicts the next residual as r (r / r_prev)²;
        // a tenth of the tolerance below that, the full step is taken without
        // the line search's trial (which accepts α = 1 there anyway); below
        // the tolerance, the next evaluation sums the audit's terms.
        const double contraction = r / std::max(r_previous, 1e-300);
        const double predicted   = it > 0 && contraction < 0.5 ?
                                     r * contraction * contraction :
                                     std::numeric_limits<double>::infinity();
        const double tolerance   = std::max(parameters.absolute_residual_tolerance,
                                          parameters.residual_tolerance * scale);
        const bool likely_converged = predicted <= 0.1 * tolerance;
        may_converge                = predicted <= tolerance;
        // The first update carries the boundary jump: take it whole.
        // Near convergence (and on the round-off floor) s(α) is noise.
        const bool full_step = (it == 0 && has_jump) || residual_ok || likely_converged;
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
          (residual_ok || likely_converged || (it == 0 && one_update_expected)) && !assembled;
      }
  }

  template <int dim>
  bool MechanicalProblem<dim>::predict(const double time_old, const double time_new,
                                       const bool from_last_solution, bool *assembled)
  {
    // Predictor: the first Newton iteration starts from the committed
    // configuration and imposes the jump of the prescribed displacements as
    // inhomogeneous constraints, so the whole body follows the boundary
    // (moving only the boundary nodes would invert the cells next to it when
    // the jump exceeds their size).
    //
    // The free dofs start from the last step's increment scaled to this step
    // (linear extrapolation in time), which puts yielding points on their
    // plastic branch from the first iteration; if that inverts an element,
    // from the committed configuration.
    // Again on the same step (iterated staggered): from the last solution,
    // which already satisfies the step's boundary values.
    if (!from_last_solution)
      owned_solution = owned_old_solution;
    const bool extrapolate =
      !from_last_solution && parameters.extrapolate && previous_time_step > 0;
    if (extrapolate)
      owned_solution.add(current_time_step / previous_time_step, previous_increment);
    solution = owned_solution;
    build_predictor_constraints(time_old, time_new);
    if (extrapolate)
      {
        // The check of the extrapolated state is the first iteration's
        // assembly when the caller takes it (@p assembled): the same state
        // and constraints.
        const bool with_matrix = assembled != nullptr;
        if (evaluate(with_matrix, [&](bool m) { return assemble(m, time_new); }))
          {
            if (assembled)
              *assembled = true;
          }
        else
          {
            owned_solution = owned_old_solution;
            solution       = owned_solution;
            build_predictor_constraints(time_old, time_new); // the jump from u_n
          }
      }
    double largest_jump = 0;
    for (const auto &line : predictor_constraints.get_lines())
      largest_jump = std::max(largest_jump, std::abs(line.inhomogeneity));
    return Utilities::MPI::max(largest_jump, mpi_communicator) > 0;
  }

  template <int dim>
  void MechanicalProblem<dim>::build_predictor_constraints(const double time_old,
                                                           const double time_new)
  {
    // The prescribed dofs and their points once per numbering, the
    // functions evaluated at every step (BoundaryConditions::Points).
    KeptPredictor &kept = kept_predictor;
    if (!kept.found)
      kept.points = boundary_conditions.points(dof_handler);
    boundary_conditions.values(kept.points, time_new, kept.values);
    boundary_conditions.velocity_increments(kept.points, time_old, time_new, kept.increments);
    const auto &displacement = kept.points.displacement;
    const auto &velocity     = kept.points.velocity;
    active_constraints       = &predictor_constraints;
    if (kept.lines_kept)
      {
        // The same lines as the last build (hanging nodes, axis, supports,
        // remote), closed, none with entries: only the jumps are new.
        for (unsigned int k = 0; k < displacement.size(); ++k)
          if (kept.displacement_line[k])
            predictor_constraints.set_inhomogeneity(displacement[k].index,
                                                    kept.values[k] - solution(displacement[k].index));
        for (unsigned int k = 0; k < velocity.size(); ++k)
          if (kept.velocity_line[k])
            {
              const auto dof = velocity[k].index;
              predictor_constraints.set_inhomogeneity(dof, kept.increments[k] + old_solution(dof) -
                                                             solution(dof));
            }
        return;
      }

    predictor_constraints.clear();
    predictor_constraints.reinit(constraint_lines);
    DoFTools::make_hanging_node_constraints(dof_handler, predictor_constraints);
    make_axis_constraints(predictor_constraints);
    kept.displacement_line.assign(displacement.size(), 0);
    kept.velocity_line.assign(velocity.size(), 0);
    for (unsigned int k = 0; k < displacement.size(); ++k)
      {
        const auto dof = displacement[k].index;
        if (locally_relevant_dofs.is_element(dof) && !predictor_constraints.is_constrained(dof))
          {
            predictor_constraints.add_line(dof);
            predictor_constraints.set_inhomogeneity(dof, kept.values[k] - solution(dof));
            kept.displacement_line[k] = 1;
          }
      }
    for (unsigned int k = 0; k < velocity.size(); ++k)
      {
        const auto dof = velocity[k].index;
        if (locally_relevant_dofs.is_element(dof) && !predictor_constraints.is_constrained(dof))
          {
            predictor_constraints.add_line(dof);
            predictor_constraints.set_inhomogeneity(dof, kept.increments[k] + old_solution(dof) -
                                                           solution(dof));
            kept.velocity_line[k] = 1;
          }
      }
    add_remote_constraints(predictor_constraints);
    predictor_constraints.close();
    // Lines with masters (hanging nodes) take their masters' jumps in
    // close(): those are built at every step.
    kept.found      = true;
    kept.lines_kept = true;
    for (const auto &line : predictor_constraints.get_lines())
      if (!line.entries.empty())
        kept.lines_kept = false;
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
  template double MechanicalProblem<dim>::tangent_error();                                       \
  template typename MechanicalProblem<dim>::StepResult MechanicalProblem<dim>::solve_step(       \
    double, double, bool);                                                                       \
  template bool   MechanicalProblem<dim>::predict(double, double, bool, bool *);                 \
  template void   MechanicalProblem<dim>::build_predictor_constraints(double, double);          \
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
