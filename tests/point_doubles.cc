// A scene pays only for the physics it switched on: the mechanics keeps the
// heat's per-point doubles (heat sources, the points' own temperatures)
// only where a coupling reads them (MechanicalProblem::keep_heat_sources(),
// set_temperature_field()), else only Ẇirr, which the energy audit reads.
//
// Independent answers: a purely mechanical block keeps 1 double a point; the
// same block under a temperature field uniform at the reference temperature
// (the isothermal case of the seed's coupling: ΔT = 0 everywhere) keeps 5
// and gives the mechanical answer bit for bit (displacements, energies); its
// plastic heat χẆirr = heat_source − thermoelastic_source is a dissipation,
// ≥ 0 at every point and > 0 where the block flowed (seed eq. 21).
#include <deal.II/base/mpi.h>

#include "check.h"
#include "mechanics_fixture.h"

#include <string>
#include <vector>

using namespace dealii;

namespace
{
  const std::string scene = std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm";
  constexpr unsigned int n_steps = 3;
}

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks check;

  anvil_test::MechanicsFixture<2> mechanical(scene, {});
  check(mechanical.problem->n_point_doubles() == 1,
        "mechanical block after setup: " + std::to_string(mechanical.problem->n_point_doubles()) +
          " doubles a point (expected 1: Ẇirr)");
  check(mechanical.run_steps(n_steps), "mechanical block: the steps converge");
  mechanical.problem->commit_step();
  check(mechanical.problem->n_point_doubles() == 1,
        "mechanical block after its steps: " + std::to_string(mechanical.problem->n_point_doubles()) +
          " doubles a point (expected 1)");

  anvil_test::MechanicsFixture<2> coupled(scene, {});
  auto             &problem = *coupled.problem;
  const double      T_ref   = coupled.parameters.temperature;
  const unsigned int n_q    = problem.get_quadrature().size();
  problem.set_temperature_field(
    [T_ref](const typename Triangulation<2>::active_cell_iterator &, std::vector<double> &T) {
      std::fill(T.begin(), T.end(), T_ref);
    },
    false);
  problem.set_initial_point_temperatures(
    std::vector<double>(std::size_t(coupled.triangulation.n_active_cells()) * n_q, T_ref));
  problem.keep_heat_sources();
  check(problem.n_point_doubles() == 5,
        "coupled block: " + std::to_string(problem.n_point_doubles()) + " doubles a point (expected 5)");
  check(coupled.run_steps(n_steps), "coupled block: the steps converge");

  const auto  &u = mechanical.problem->displacement(), &u_coupled = problem.displacement();
  unsigned int differing = 0;
  for (const auto i : mechanical.problem->get_dof_handler().locally_owned_dofs())
    differing += u[i] != u_coupled[i];
  check(differing == 0, "uniform reference temperature: " + std::to_string(differing) +
                          " displacement entries differ from the mechanical block's (expected 0)");

  unsigned int negative = 0, positive = 0;
  for (const auto &cell : coupled.triangulation.active_cell_iterators())
    if (cell->is_locally_owned())
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const double plastic_heat = problem.heat_source(cell, q) - problem.thermoelastic_source(cell, q);
          negative += plastic_heat < 0;
          positive += plastic_heat > 0;
        }
  check(problem.largest_plastic_increment() > 0 && negative == 0 && positive > 0,
        "plastic heat χẆirr: " + std::to_string(positive) + " points > 0, " + std::to_string(negative) +
          " < 0 (expected some > 0, none < 0: the block flows)");

  problem.commit_step();
  const auto &e = mechanical.problem->energy(), &e_coupled = problem.energy();
  check(e.stress_work == e_coupled.stress_work && e.plastic_work == e_coupled.plastic_work &&
          e.elastic_energy == e_coupled.elastic_energy && e.external_work == e_coupled.external_work,
        "uniform reference temperature: the energy audit's terms are the mechanical block's, bit for "
        "bit (plastic work " + std::to_string(e_coupled.plastic_work) + " N mm)");
  return check.finish();
}
