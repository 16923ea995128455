#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/expression.h>
#include <anvil/core/first_message.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/coupling/coupled_problem.h>
#include <anvil/material/number_format.h>

#include <cmath>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    template <int dim>
    std::string at_node(const Point<dim> &x)
    {
      std::ostringstream s;
      s << " at a node (" << x << ")";
      return s.str();
    }
  } // namespace

  template <int dim>
  void CoupledProblem<dim>::check_temperatures(const parallel::DistributedTriangulationBase<dim> &tria,
                                               const Scene &scene, const double end_time,
                                               const bool uniform_temperature) const
  {
    // This rank's first problem; then the lowest rank's is every rank's error.
    std::string problem;
    // A temperature the scene sets at a node of a body: absolute, and one the
    // body's yield stress survives (at zero plastic strain).
    // @p where: " at a node (x y)", or "" for a uniform temperature.
    const auto examine = [&](const double T, const std::string &where, const types::material_id body,
                             const std::string &source) {
      if (!problem.empty())
        return;
      if (!(T > 0) || !std::isfinite(T))
        {
          problem = source + " gives " + short_number(T) + " K" + where +
                    ": expected a finite absolute temperature > 0 K at every node";
          return;
        }
      if (!with_mechanics)
        return;
      if (const auto loss = materials.at(body)->strength_lost(T, 0))
        problem = loss.location + " " + loss.reason + ", but " + source + " gives T = " +
                  short_number(T) + " K" + where + " in body id " + std::to_string(body) +
                  ": expected a yield stress > 0 at the scene's temperatures";
    };

    if (with_mechanics && !with_heat && uniform_temperature)
      for (const auto &[id, model] : materials)
        examine(mechanical_parameters.temperature, "", id,
                scene.where("Mechanics/Temperature") + ": 'Mechanics/Temperature' = " +
                  short_number(mechanical_parameters.temperature) + " K");

    if (with_heat)
      {
        // The run's own check (ThermalProblem::setup) comes after the mesh,
        // the matrices and the output directory: here it is before any work.
        const std::string &text    = thermal_parameters.initial_temperature;
        const auto         initial = parse_expression<dim>(text, scene, "Heat/Initial temperature");
        const std::string  source  = thermal_parameters.initial_temperature_location +
                                   ": 'Heat/Initial temperature' = '" + text + "'";
        initial->set_time(0);
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              examine(initial->value(cell->vertex(v)), at_node(cell->vertex(v)), cell->material_id(),
                      source);

        // Prescribed boundary temperatures at the start and at the end of the run.
        const std::string path = "Heat/Boundary conditions/Temperature";
        for (const double t : {0., end_time})
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned() && cell->at_boundary())
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary())
                  {
                    const auto b = thermal_boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
                    if (b == thermal_boundary_conditions.boundaries.end() || !b->second.temperature)
                      continue;
                    b->second.temperature->set_time(t);
                    for (const unsigned int v : cell->face(f)->vertex_indices())
                      examine(b->second.temperature->value(cell->face(f)->vertex(v)),
                              at_node(cell->face(f)->vertex(v)), cell->material_id(),
                              scene.where(path) + ": '" + path + "' on '" + b->second.name +
                                "' at t = " + short_number(t) + " s");
                  }
        for (const auto &[id, b] : thermal_boundary_conditions.boundaries)
          if (b.temperature)
            b.temperature->set_time(0);
      }

    // A formula that gave NaN or inf says so itself, with where and when.
    const MPI_Comm comm = tria.get_communicator();
    throw_recorded_input_error(comm);
    if (const std::string first = first_message(problem, comm); !first.empty())
      throw InputError(first);
  }

  ANVIL_INSTANTIATE_CLASS(CoupledProblem)
} // namespace anvil
