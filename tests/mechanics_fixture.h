// A MechanicalProblem built from a scene file the way the Simulator builds it
// (geometry, bodies' materials, mechanics parameters, boundary conditions),
// for C++ tests and benchmarks that drive the mechanics directly.
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <anvil/core/scene.h>
#include <anvil/simulator/simulator.h>
#include <anvil/geometry/geometry.h>
#include <anvil/material/material_point.h>
#include <anvil/mechanics/boundary_conditions.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace anvil_test
{
  using Overrides = std::vector<std::pair<std::string, std::string>>;

  template <int dim>
  struct MechanicsFixture
  {
    MechanicsFixture(const std::string &scene_file, const Overrides &overrides)
      : scene(scene_file, overrides)
      , triangulation(MPI_COMM_WORLD)
      , null_stream("/dev/null")
      , timer(MPI_COMM_WORLD, null_stream, dealii::TimerOutput::never,
              dealii::TimerOutput::wall_times)
    {
      scene.read_shape();
      scene.read([](dealii::ParameterHandler &prm, const anvil::Scene &s) {
        anvil::Simulator<dim>::declare_parameters(prm, s.body_names(), s.contact_pair_names(),
                                                  s.contact_tool_names());
      });
      auto &prm = scene.parameters();
      geometry.parse_parameters(prm, scene);
      prm.enter_subsection("Bodies");
      for (const auto &name : scene.body_names())
        {
          const auto id = geometry.body_id(name, scene.where("Bodies/Names"));
          prm.enter_subsection(name);
          materials[id] = anvil::MaterialFactory::create(prm, scene, "Bodies/" + name);
          prm.leave_subsection();
        }
      prm.leave_subsection();
      parameters.parse_parameters(prm, scene);
      boundary_conditions.parse_parameters(prm, scene, geometry);
      time_step = prm.get_double({"Time"}, "Time step");
      geometry.create(triangulation);
      problem = std::make_unique<anvil::MechanicalProblem<dim>>(triangulation, parameters,
                                                                boundary_conditions, materials,
                                                                timer);
      problem->setup();
    }

    /// Solve @p n steps of Time/Time step, committing all but the last
    /// (which stays the current iterate); false if one did not converge.
    bool run_steps(const unsigned int n)
    {
      for (unsigned int k = 0; k < n; ++k)
        {
          const auto result = problem->solve_step(k * time_step, (k + 1) * time_step);
          if (!result.converged)
            return false;
          if (k + 1 < n)
            problem->commit_step();
        }
      return true;
    }

    anvil::Scene                                          scene;
    anvil::Geometry<dim>                                  geometry;
    dealii::parallel::distributed::Triangulation<dim>    triangulation;
    std::ofstream                                         null_stream;
    dealii::TimerOutput                                   timer;
    std::map<dealii::types::material_id, std::shared_ptr<const anvil::MaterialModel>> materials;
    typename anvil::MechanicalProblem<dim>::Parameters    parameters;
    anvil::BoundaryConditions<dim>                        boundary_conditions;
    double                                                time_step = 1;
    std::unique_ptr<anvil::MechanicalProblem<dim>>        problem;
  };
} // namespace anvil_test
