// BoundaryConditions::Points keeps the prescribed dofs and their support
// points once per numbering, and values() / velocity_increments() evaluate
// the functions there. Independent answer: deal.II's
// VectorTools::interpolate_boundary_values (BoundaryConditions::interpolate
// and interpolate_velocity_increment, which call it at every time): the same
// dofs and bit-identical values, at several times. Cases: 2D Q1 and Q2
// (edge midpoints), 3D Q1 on a distorted mesh; entries that share corner
// dofs (the later entry writes last), displacement and velocity lists, and a
// velocity depending on x, y and t.
#include <deal.II/base/mpi.h>

#include "check.h"
#include "mechanics_fixture.h"

#include <map>
#include <string>
#include <vector>

using namespace dealii;
using anvil_test::Overrides;

namespace
{
  template <int dim>
  void check_case(anvil::testing::Checks &check, const std::string &name, const Overrides &overrides)
  {
    anvil_test::MechanicsFixture<dim> fixture(std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm", overrides);
    const auto &bc         = fixture.boundary_conditions;
    const auto &dof_handler = fixture.problem->get_dof_handler();
    const auto  points      = bc.points(dof_handler);
    std::vector<double> values, increments;
    unsigned int        differing = 0, missing = 0, n_displacement = 0, n_velocity = 0;
    for (const double t : {0., 0.125, 0.3, 1.})
      {
        std::map<types::global_dof_index, double> reference, reference_increments;
        bc.interpolate(dof_handler, t, reference);
        bc.values(points, t, values);
        missing += reference.size() != points.displacement.size();
        unsigned int k = 0;
        for (const auto &[dof, value] : reference)
          if (k < points.displacement.size())
            {
              missing += points.displacement[k].index != dof;
              differing += values[k++] != value;
            }
        const double t_old = t * 0.5;
        bc.interpolate_velocity_increment(dof_handler, t_old, t, reference_increments);
        bc.velocity_increments(points, t_old, t, increments);
        missing += reference_increments.size() != points.velocity.size();
        k = 0;
        for (const auto &[dof, increment] : reference_increments)
          if (k < points.velocity.size())
            {
              missing += points.velocity[k].index != dof;
              differing += increments[k++] != increment;
            }
        n_displacement = reference.size();
        n_velocity     = reference_increments.size();
      }
    check(missing == 0 && differing == 0 && n_displacement > 0 && n_velocity > 0,
          name + ": " + std::to_string(n_displacement) + " displacement and " +
            std::to_string(n_velocity) + " velocity dofs, " + std::to_string(missing) +
            " dofs not interpolate_boundary_values' (expected 0), " + std::to_string(differing) +
            " values differing from it (expected 0)");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks check;
  // bottom and left share a corner in ux and uy; the later entry (left) writes it last.
  const Overrides plane = {
    {"Boundary conditions/Displacement",
     "bottom: ux = 0.01*x*t, uy = 0; left: ux = 0.02*t + 0.001*y, uy = 0.003*t*y"},
    {"Boundary conditions/Velocity", "top: uy = -0.1 - 0.2*t*x*x, ux = 0.05*sin(3*t + y)"},
    {"Boundary conditions/Pressure", ""}};
  Overrides quadratic = plane;
  quadratic.push_back({"Mechanics/Polynomial degree", "2"});
  quadratic.push_back({"Mechanics/Element", "standard"});
  check_case<2>(check, "2D Q1", plane);
  check_case<2>(check, "2D Q2", quadratic);
  const Overrides solid = {
    {"Dimension", "3"},
    {"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 1, 3, 3, 3"},
    {"Boundary conditions/Displacement",
     "bottom: ux = 0, uy = 0.001*z, uz = 0; front: uz = 0.01*x*t; back: uz = -0.01*y*t"},
    {"Boundary conditions/Velocity", "top: uy = -0.1*(1 + x*z), ux = 0.02*t"},
    {"Boundary conditions/Pressure", ""}};
  check_case<3>(check, "3D Q1, distorted", solid);
  return check.finish();
}
