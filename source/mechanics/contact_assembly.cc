// The contact elements' share of the mechanical system (seed eq. 27–29),
// assembled after the cell loop, serially: ContactProblem::assemble is not
// thread-safe (its search and element state are shared).
#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  bool MechanicalProblem<dim>::assemble_contact(const bool with_matrix)
  {
    // r is an internal force; in dynamics it takes the (1 − α_f) of the static part.
    const double factor = parameters.dynamic ? 1 - alpha_f : 1.;
    // Kept over the elements (of one size each in a scene): no allocation per element.
    dealii::Vector<double> rhs;
    FullMatrix<double>     matrix;
    return contact->assemble(
      solution, with_matrix,
      [&](const std::vector<types::global_dof_index> &dofs, const dealii::Vector<double> &r,
          const FullMatrix<double> *K) {
        rhs = r;
        rhs *= -factor;
        if (with_matrix && K)
          {
            matrix = *K;
            matrix *= factor;
            active_constraints->distribute_local_to_global(matrix, rhs, dofs, system_matrix,
                                                           system_rhs);
          }
        else
          active_constraints->distribute_local_to_global(rhs, dofs, system_rhs);
        internal_force.add(dofs, r); // reactions include the contact forces
        contact_force.add(dofs, r);
      });
  }

#define INSTANTIATE(dim) template bool MechanicalProblem<dim>::assemble_contact(bool);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
