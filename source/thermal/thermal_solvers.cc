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
    // Contact (eq. 30) couples slave and master temperatures that share no
    // cell: their entries need a pattern of their own, rebuilt only when a
    // new pair exchanges heat (the list only grows).
    const bool new_pattern =
      exchange.add_matrix && (!exchange_pattern_current || exchange.couplings_changed());
    // M − γ'J with γ' within 20 % of γ preconditions ARKode's GMRES on M − γJ
    // well (a few iterations): keep the factorisation.
    if (!new_pattern && current_gamma > 0 && std::abs(gamma / current_gamma - 1) < 0.2)
      return;
    TimerOutput::Scope t(timer, "Heat: Newton matrix");
    if (new_pattern)
      {
        newton_matrix.reinit(locally_owned_dofs, locally_owned_dofs, sparsity(exchange.couplings()),
                             mpi_communicator);
        newton_direct->clear();
        exchange_pattern_current = true;
      }
    if (exchange.add_matrix)
      {
        // M + γA − γ ∂q/∂T in the larger pattern (M's and A's a part of it).
        newton_matrix = 0;
        if (parameters.lumped_mass)
          {
            for (const auto i : locally_owned_dofs)
              newton_matrix.add(i, i, lumped_mass(i));
            newton_matrix.compress(VectorOperation::add);
          }
        else
          newton_matrix.add(1., mass_matrix);
        newton_matrix.add(gamma, tangent_matrix);
        exchange.add_matrix([&](const types::global_dof_index i, const types::global_dof_index j,
                                const double d) { newton_matrix.add(i, j, -gamma * d); });
        newton_matrix.compress(VectorOperation::add);
      }
    else if (parameters.lumped_mass)
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
    if (thermal::mass_by_klu(use_direct, parameters.lumped_mass, dof_handler.n_dofs()))
      {
        // M is fixed (reference configuration): factorised once, one solve
        // here instead of ~20 CG iterations.
        mass_direct->solve(x, b);
        ++linear_iterations;
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
