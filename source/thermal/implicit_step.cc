// The heat problem as one block of a Newton loop that is not its own: the
// monolithic scheme (doc/monolithic.md) evaluates R_T = M (T - T_n) - dt f(T, u)
// and its tangent at iterates it chooses, then hands the converged T back.
// Kept apart from the ARKode step, which owns its own iteration.
#include <anvil/core/instantiate.h>
#include <anvil/thermal/thermal_problem.h>

#include <limits>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void ThermalProblem<dim>::begin_step(const double time_old, const double time_new)
  {
    step_length       = time_new - time_old;
    linear_iterations = 0;
    if (!operators_current || mass_diagonal.size() == 0)
      {
        assemble_mass();
        operators_current = true;
      }
  }

  template <int dim>
  void ThermalProblem<dim>::implicit_residual(const double t, const Vector &T, Vector &f)
  {
    // The mechanics' sources change with every iterate: never the cached ones.
    sources_current = false;
    f.reinit(locally_owned_dofs, mpi_communicator);
    assemble(t, T, &f, nullptr);
  }

  template <int dim>
  const TrilinosWrappers::SparseMatrix &ThermalProblem<dim>::implicit_tangent(const double t,
                                                                             const Vector &T)
  {
    assemble(t, T, nullptr, &tangent_matrix);
    tangent_current = true;
    return tangent_matrix;
  }

  template <int dim>
  void ThermalProblem<dim>::mass_vmult(Vector &Mv, const Vector &v) const
  {
    if (parameters.lumped_mass)
      {
        Mv = v;
        Mv.scale(lumped_mass);
      }
    else
      mass_matrix.vmult(Mv, v);
  }

  template <int dim>
  void ThermalProblem<dim>::set_temperature(const Vector &T_owned)
  {
    Vector y(T_owned);
    hanging.distribute(y);
    solution              = y;
    temperature_ghosted   = solution;
    solution_heat_content = std::numeric_limits<double>::quiet_NaN();
  }

  template <int dim>
  void ThermalProblem<dim>::accept_temperature(const Vector &T_owned, const double time_old,
                                               const double time_new)
  {
    set_temperature(T_owned);
    step_balance(time_old, time_new);
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
