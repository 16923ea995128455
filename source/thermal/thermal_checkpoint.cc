// The heat problem's part of a checkpoint: the committed temperature moved
// with the cells, the step scalars by name; everything derived from them is
// marked stale so the first step after a restart rebuilds it.
#include <anvil/core/instantiate.h>
#include <anvil/thermal/thermal_problem.h>

#include <limits>
#include <string>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void ThermalProblem<dim>::prepare_checkpoint()
  {
    checkpoint_vector.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    checkpoint_vector = old_solution;
    checkpoint_transfer = std::make_unique<parallel::distributed::SolutionTransfer<dim, Vector>>(dof_handler);
    checkpoint_transfer->prepare_for_serialization(checkpoint_vector);
  }

  template <int dim>
  void ThermalProblem<dim>::load_checkpoint()
  {
    parallel::distributed::SolutionTransfer<dim, Vector> transfer(dof_handler);
    transfer.deserialize(old_solution);
    solution                = old_solution;
    old_temperature_ghosted = old_solution;
    temperature_ghosted     = old_solution;
    solution_heat_content = old_heat_content = std::numeric_limits<double>::quiet_NaN();
    operators_current       = false;
    tangent_current         = false;
    couplings_current       = false;
    loads_current           = false;
  }

  template <int dim>
  NamedValues ThermalProblem<dim>::checkpoint_scalars() const
  {
    NamedValues v = {{"committed_time", committed_time},
                     {"last_internal_step", last_internal_step},
                     {"source_heat", total_source}};
    for (const auto &[id, q] : total_heat_in)
      v["boundary_heat_in." + std::to_string(id)] = q;
    return v;
  }

  template <int dim>
  void ThermalProblem<dim>::restore_scalars(const NamedValues &v)
  {
    committed_time     = named_value(v, "committed_time");
    last_internal_step = named_value(v, "last_internal_step");
    total_source       = named_value(v, "source_heat");
    total_heat_in.clear();
    const std::string prefix = "boundary_heat_in.";
    for (const auto &[key, q] : v)
      if (key.rfind(prefix, 0) == 0)
        total_heat_in[static_cast<types::boundary_id>(std::stoul(key.substr(prefix.size())))] = q;
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
