// The steady heat equation, f(T, t) = -K(T) T + F(T, t) = 0 (seed eq. 26
// without the capacity term rho c dT/dt), by Newton with the consistent
// tangent A = d(K T - F)/dT that the ARKode path assembles, and its heat
// balance. Kept apart from the time integration: it owns its iteration.
// Derivation and the meaning of "steady" under time-varying loads:
// doc/thermal.md, "Steady state".
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/kernels.h>
#include <anvil/thermal/thermal_problem.h>

#include "newton_factorisation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  double ThermalProblem<dim>::steady_residual(const double t, const Vector &T, Vector &f)
  {
    f.reinit(locally_owned_dofs, mpi_communicator);
    assemble(t, T, &f, nullptr);
    // Temperature rows hold M_DD g'(t) in the transient equation; here they
    // are satisfied exactly (T_D = g(t)) and carry no residual. Hanging rows
    // are empty already (their equations live in their masters').
    for (const auto i : dirichlet_dofs)
      f(i) = 0;
    f.compress(VectorOperation::insert);
    return f.l2_norm();
  }

  template <int dim>
  void ThermalProblem<dim>::steady_linear_solve(const double t, const Vector &T, const Vector &f,
                                                Vector &delta)
  {
    TimerOutput::Scope scope(timer, "Heat: steady Newton solve");
    assemble(t, T, nullptr, &tangent_matrix);
    tangent_current = true;
    // Temperature and hanging rows: delta_i = 0 (f_i = 0 there), with a unit
    // of the free diagonal's size so that neither KLU's pivoting nor AMG sees
    // a row out of scale.
    double diagonal = 0;
    for (const auto i : locally_owned_dofs)
      if (!constraints.is_constrained(i))
        diagonal = std::max(diagonal, std::abs(tangent_matrix.diag_element(i)));
    diagonal = Utilities::MPI::max(diagonal, mpi_communicator);
    if (!(diagonal > 0))
      diagonal = 1;
    newton_matrix.copy_from(tangent_matrix);
    exchange_pattern_current = false; // the tangent's pattern now
    newton_matrix.clear_rows(dirichlet_dofs, diagonal);
    for (const auto i : locally_owned_dofs)
      if (hanging.is_constrained(i))
        newton_matrix.set(i, i, diagonal);
    newton_matrix.compress(VectorOperation::insert);
    current_gamma = -1; // the transient Newton matrix M + gamma A is gone

    delta.reinit(locally_owned_dofs, mpi_communicator);
    thermal::factorise_newton_matrix(newton_matrix, use_direct, parameters.polynomial_degree,
                                     newton_direct, newton_amg);
    if (use_direct)
      newton_direct->solve(delta, f);
    else
      {
        // The kept Temperature columns and radiation make A nonsymmetric: GMRES.
        SolverControl       control(1000, 1e-12 * f.l2_norm());
        SolverGMRES<Vector> gmres(control, SolverGMRES<Vector>::AdditionalData(100));
        gmres.solve(newton_matrix, delta, f, *newton_amg);
        linear_iterations += control.last_step();
      }
    hanging.distribute(delta);
  }

  template <int dim>
  typename ThermalProblem<dim>::Statistics ThermalProblem<dim>::solve_steady(const double t)
  {
    TimerOutput::Scope scope(timer, "Heat: steady state");
    Statistics         stats;
    last_steady      = SteadyReport();
    last_steady.time = t;
    linear_iterations = 0;
    sources_current   = false; // the mechanics' sources, if any, as they are now
    solving_steady    = true;

    Vector T(solution), f, delta, trial, f_trial;
    apply_dirichlet(t, T);
    hanging.distribute(T);
    double residual = steady_residual(t, T, f);
    last_steady.residuals.push_back(residual);
    for (unsigned int it = 1; it <= parameters.steady_max_iterations && std::isfinite(residual); ++it)
      {
        steady_linear_solve(t, T, f, delta);
        ++stats.linear_solves;
        stats.nonlinear_iterations = it;
        // A Newton step this small: the next would change T by ~its square.
        // Taken whole: near the root |f| is round-off, and a line search on
        // it would only see noise.
        if (delta.linfty_norm() <= parameters.steady_tolerance)
          {
            T += delta;
            residual = steady_residual(t, T, f);
            last_steady.residuals.push_back(residual);
            last_steady.increments.push_back(delta.linfty_norm());
            last_steady.step_lengths.push_back(1.);
            stats.converged = std::isfinite(residual);
            break;
          }
        // Backtracking on |f| (Armijo, halving): radiation's T^4 can throw a
        // full step far past the root, or below 0 K, from a poor first guess.
        double alpha = 1, trial_residual = residual;
        bool   descent = false;
        for (unsigned int cut = 0; cut < 30 && !descent; ++cut, alpha = descent ? alpha : alpha / 2)
          {
            trial = T;
            trial.add(alpha, delta);
            const double lowest = Utilities::MPI::min(trial.size() ? trial.min() : 1., mpi_communicator);
            if (!(lowest > 0))
              continue;
            trial_residual = steady_residual(t, trial, f_trial);
            descent        = trial_residual <= (1 - 1e-4 * alpha) * residual || residual == 0;
          }
        if (!descent)
          {
            // |f| at its round-off floor before |dT| reached the tolerance
            // (a tight Tolerance): the full step, unless it leaves 0 K.
            alpha = 1;
            trial = T;
            trial.add(1., delta);
            if (!(Utilities::MPI::min(trial.size() ? trial.min() : 1., mpi_communicator) > 0))
              break; // reported as not converged below
            trial_residual = steady_residual(t, trial, f_trial);
          }
        const double increment = alpha * delta.linfty_norm();
        T        = trial;
        f        = f_trial;
        residual = trial_residual;
        last_steady.residuals.push_back(residual);
        last_steady.increments.push_back(increment);
        last_steady.step_lengths.push_back(alpha);
      }
    solving_steady          = false;
    stats.linear_iterations = linear_iterations;
    stats.rhs_evaluations   = last_steady.residuals.size();
    if (!stats.converged)
      {
        std::ostringstream why;
        why << std::setprecision(3) << "steady heat Newton did not converge at t = " << t
            << " s in " << stats.nonlinear_iterations
            << " iterations (Heat/Steady state/Maximum iterations " << parameters.steady_max_iterations
            << "): |f| " << last_steady.residuals.front() << " -> " << residual << " mW, last |dT| "
            << (last_steady.increments.empty() ? 0. : last_steady.increments.back())
            << " K (Tolerance " << parameters.steady_tolerance << " K)";
        stats.failure = why.str();
        last_steady.failure = stats.failure;
      }
    last_steady.converged = stats.converged;
    solution              = T;
    temperature_ghosted   = solution;
    solution_heat_content = std::numeric_limits<double>::quiet_NaN();
    return stats;
  }

  template <int dim>
  double ThermalProblem<dim>::dirichlet_heat_flow(const Vector &T) const
  {
    // Heat into the body through a face: -q . n = k(T) grad T . n (n outward).
    FEFaceValues<dim> fe_face(get_mapping(), fe, face_quadrature,
                              update_values | update_gradients | update_normal_vectors |
                                update_JxW_values | update_quadrature_points);
    std::vector<double>         T_f(face_quadrature.size());
    std::vector<Tensor<1, dim>> grad_T(face_quadrature.size());
    double                      power = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
              if (bc == boundary_conditions.boundaries.end() || !bc->second.temperature)
                continue;
              fe_face.reinit(cell, f);
              fe_face.get_function_values(T, T_f);
              fe_face.get_function_gradients(T, grad_T);
              const auto &m = materials.at(cell->material_id());
              for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                power += m.k(T_f[q]) * (grad_T[q] * fe_face.normal_vector(q)) * fe_face.JxW(q) *
                         thermal::ring_factor(fe_face.quadrature_point(q), parameters.axisymmetric);
            }
    return Utilities::MPI::sum(power, mpi_communicator);
  }

  template <int dim>
  typename ThermalProblem<dim>::SteadyBalance ThermalProblem<dim>::steady_balance(const double t) const
  {
    SteadyBalance b;
    b.boundary      = boundary_flows(t, temperature_ghosted);
    b.source        = source_power(t);
    b.dirichlet     = dirichlet_heat_flow(temperature_ghosted);
    double sum      = b.source + b.dirichlet;
    double largest  = std::max(std::abs(b.source), std::abs(b.dirichlet));
    for (const auto &[id, q] : b.boundary)
      {
        sum += q;
        largest = std::max(largest, std::abs(q));
      }
    b.error = largest > 0 ? std::abs(sum) / largest : 0.;
    return b;
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
