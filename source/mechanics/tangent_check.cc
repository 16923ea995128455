// The finite-difference check of the mechanical tangent (Mechanics/Newton/
// Check tangent): K δu against the central difference of the residual.
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;

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

#define INSTANTIATE(dim) template double MechanicalProblem<dim>::tangent_error();
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
