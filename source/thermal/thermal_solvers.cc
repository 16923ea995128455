// ThermalProblem: the linear solvers behind ARKode (the Newton matrix
// M + γA and its KLU or AMG, the mass solve).
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/thermal_problem.h>

#include "newton_factorisation.h"

#include <cmath>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void ThermalProblem<dim>::setup_newton(const double gamma)
  {
    // M − γ'J with γ' within 20 % of γ preconditions ARKode's GMRES on M − γJ
    // well (a few iterations): keep the factorisation.
    if (current_gamma > 0 && std::abs(gamma / current_gamma - 1) < 0.2)
      return;
    TimerOutput::Scope t(timer, "Heat: Newton matrix");
    if (parameters.lumped_mass)
      {
        newton_matrix.copy_from(tangent_matrix);
        newton_matrix *= gamma;
        for (const auto i : locally_owned_dofs)
          newton_matrix.add(i, i, lumped_mass(i));
        newton_matrix.compress(VectorOperation::add);
      }
    else
      {
        newton_matrix.copy_from(mass_matrix);
        newton_matrix.add(gamma, tangent_matrix);
      }
    if (exchange.add_diagonal)
      {
        // The exchange's diagonal (its couplings act through GMRES only).
        Vector diagonal(locally_owned_dofs, mpi_communicator);
        exchange.add_diagonal(diagonal);
        for (const auto i : locally_owned_dofs)
          if (diagonal(i) != 0)
            newton_matrix.add(i, i, gamma * diagonal(i));
        newton_matrix.compress(VectorOperation::add);
      }
    thermal::factorise_newton_matrix(newton_matrix, use_direct, parameters.polynomial_degree,
                                     newton_direct, newton_amg);
    current_gamma = gamma;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_newton(Vector &x, const Vector &b, double)
  {
    if (use_direct)
      {
        newton_direct->solve(x, b);
        return 1;
      }
    newton_amg->vmult(x, b); // one V-cycle: the preconditioner of ARKode's GMRES
    return 1;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_mass(Vector &x, const Vector &b, const double tolerance)
  {
    ++mass_solves;
    if (parameters.lumped_mass)
      {
        x = b;
        for (const auto i : locally_owned_dofs)
          x(i) /= lumped_mass(i);
        x.compress(VectorOperation::insert);
        return 1;
      }
    SolverControl control(1000, std::min(tolerance, 1e-10 * b.l2_norm()));
    SolverCG<Vector> cg(control);
    x = 0;
    cg.solve(mass_matrix, x, b, mass_jacobi);
    linear_iterations += control.last_step();
    return control.last_step();
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
