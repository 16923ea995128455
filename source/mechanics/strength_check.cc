#include <deal.II/base/mpi.h>

#include <anvil/core/instantiate.h>
#include <anvil/material/number_format.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>
#include <limits>
#include <map>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  std::string MechanicalProblem<dim>::strength_lost(const double time) const
  {
    // Every point of the committed state at the temperature it was updated
    // at and, in a heat scene, at the one the next step starts from (the
    // heat field at t_n+1). The message names the hottest point that lost
    // its strength, whatever the partition.
    // A body whose law cannot lose its strength is not visited (it was a
    // virtual call and a call_once per point and temperature: 63 M
    // instructions on two_blocks); with none, no pass at all.
    std::map<types::material_id, bool> checked;
    for (const auto &[id, model] : materials)
      checked[id] = model->may_lose_strength();
    if (std::none_of(checked.begin(), checked.end(), [](const auto &c) { return c.second; }))
      return "";
    const bool          heat  = static_cast<bool>(temperature_field);
    const unsigned int  n_q   = quadrature.size();
    double              worst = -std::numeric_limits<double>::infinity();
    std::string         message;
    std::vector<double> next(n_q, parameters.temperature);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && checked.at(cell->material_id()))
        {
          const MaterialModel &model = *materials.at(cell->material_id());
          if (heat)
            temperature_field(cell, next);
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double eps = points(cell, q)->equivalent_plastic_strain();
              const double now = heat ? material_temperature_old(cell, q) : parameters.temperature;
              for (const double T : {now, next[q]})
                if (T > worst)
                  if (const auto loss = model.strength_lost(T, eps))
                    {
                      worst = T;
                      std::ostringstream m;
                      m << "the yield stress vanished at t = " << short_number(time)
                        << " s: a converged state has T = " << short_number(T)
                        << " K at a point of the cell at (" << cell->center() << ") of body id "
                        << cell->material_id() << " (" << model.name() << "), and "
                        << loss.location << " " << loss.reason
                        << ": expected a yield stress > 0 over the run's temperatures";
                      message = m.str();
                    }
            }
        }
    const double hottest = Utilities::MPI::max(worst, mpi_communicator);
    if (hottest == -std::numeric_limits<double>::infinity())
      return "";
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const unsigned int owner   = Utilities::MPI::min(
      worst == hottest ? Utilities::MPI::this_mpi_process(mpi_communicator) : n_ranks,
      mpi_communicator);
    return Utilities::MPI::broadcast(mpi_communicator, message, owner);
  }

  ANVIL_INSTANTIATE_CLASS(MechanicalProblem)
} // namespace anvil
