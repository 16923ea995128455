#pragma once

// A ThermalProblem built from prm text for the thread tests and the heat
// assembly benchmark (tests/thermal_threads.cc, contrib/bench/thermal_assembly.cc):
// blocks geometry, one material, optionally refined near x = x0 (hanging
// nodes) and on a deformed configuration x = X + u(X) (MappingQEulerian, as
// in a coupled run).

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/thermal/thermal_problem.h>

#include <memory>
#include <string>

namespace anvil_test
{
  using namespace dealii;
  using namespace anvil;

  template <int dim>
  struct ThermalModel
  {
    using Vector = TrilinosWrappers::MPI::Vector;

    parallel::distributed::Triangulation<dim>     tria{MPI_COMM_WORLD};
    Geometry<dim>                                 geometry;
    ThermalBoundaryConditions<dim>                bcs;
    typename ThermalProblem<dim>::Parameters      parameters;
    std::map<types::material_id, ThermalMaterial> materials;
    TimerOutput timer{MPI_COMM_WORLD, std::cout, TimerOutput::never, TimerOutput::wall_times};
    FESystem<dim>                                 mechanics_fe{FE_Q<dim>(1), dim};
    DoFHandler<dim>                               mechanics_dofs{tria};
    Vector                                        displacement;
    std::unique_ptr<ThermalProblem<dim>>          problem;

    /**
     * @p text: Geometry, Heat and Material/Thermal subsections.
     * @p refine_below: cells whose centre has x < this are refined once.
     * @p displacement_expression: u(X) as dim ';'-separated components ("" : reference configuration).
     */
    ThermalModel(const std::string &text, const bool axisymmetric, const double refine_below,
                 const std::string &displacement_expression)
    {
      ParameterHandler prm;
      Geometry<dim>::declare_parameters(prm);
      ThermalProblem<dim>::Parameters::declare_parameters(prm);
      prm.enter_subsection("Material");
      ThermalMaterial::declare_parameters(prm);
      prm.leave_subsection();
      prm.parse_input_from_string(text);
      const Scene scene;
      geometry.parse_parameters(prm, scene);
      geometry.create(tria);
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center()[0] < refine_below)
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
      parameters.parse_parameters(prm, scene);
      parameters.axisymmetric = axisymmetric;
      bcs.parse_parameters(prm, scene, geometry);
      prm.enter_subsection("Material");
      const auto m = ThermalMaterial::parse_parameters(prm, scene, "Material", 7.8e-9, 4.6e8);
      prm.leave_subsection();
      for (const auto &[name, id] : geometry.body_names())
        materials[id] = m;
      problem = std::make_unique<ThermalProblem<dim>>(tria, parameters, bcs, materials, timer);
      problem->setup(0);
      if (!displacement_expression.empty())
        {
          mechanics_dofs.distribute_dofs(mechanics_fe);
          IndexSet relevant;
          DoFTools::extract_locally_relevant_dofs(mechanics_dofs, relevant);
          Vector owned(mechanics_dofs.locally_owned_dofs(), MPI_COMM_WORLD);
          FunctionParser<dim> u(dim);
          u.initialize(dim == 2 ? "x, y" : "x, y, z", displacement_expression, {});
          VectorTools::interpolate(mechanics_dofs, u, owned);
          displacement.reinit(mechanics_dofs.locally_owned_dofs(), relevant, MPI_COMM_WORLD);
          displacement = owned;
          problem->set_configuration(mechanics_dofs, displacement);
        }
    }

    /// T(x) on the current configuration as an owned vector (K).
    Vector temperature(const std::string &expression) const
    {
      Vector              T(problem->get_dof_handler().locally_owned_dofs(), MPI_COMM_WORLD);
      FunctionParser<dim> f(1);
      f.initialize(dim == 2 ? "x, y" : "x, y, z", expression, {});
      VectorTools::interpolate(problem->get_mapping(), problem->get_dof_handler(), f, T);
      return T;
    }

    ~ThermalModel()
    {
      problem.reset(); // before the configuration it maps with
      mechanics_dofs.clear();
    }
  };
} // namespace anvil_test
