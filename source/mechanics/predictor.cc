// The first iterate of a Newton step of MechanicalProblem: the extrapolated
// (or committed, or last) configuration and the constraints that carry the
// step's boundary values into the body.
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include "evaluation_kinds.h"

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;
  using evaluation_kinds::evaluate;

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

#define INSTANTIATE(dim)                                                                         \
  template bool MechanicalProblem<dim>::predict(double, double, bool, bool *);                   \
  template void MechanicalProblem<dim>::build_predictor_constraints(double, double);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
