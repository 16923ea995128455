// The heat-balance integrals from ThermalProblem's per-cell tables
// (include/anvil/thermal/cell_table.h) against closed forms and, bit for bit,
// against the plain FEValues loops they replaced: heat content ∫ρ₀cT dV, the
// integral of a per-point source on a moved configuration (some cells zero),
// the temperatures at quadrature points. Plane and axisymmetric; runs the
// same under mpirun -np 2.
#include "check.h"

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/thermal/thermal_problem.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace anvil;

namespace
{
  anvil::testing::Checks check;
  bool                   root = true;

  constexpr double rho = 7.8e-9, cap = 4.6e8;

  void run(const bool axisymmetric)
  {
    ParameterHandler prm;
    Geometry<2>::declare_parameters(prm);
    ThermalProblem<2>::Parameters::declare_parameters(prm);
    prm.enter_subsection("Material");
    ThermalMaterial::declare_parameters(prm);
    prm.leave_subsection();
    // [1, 3] x [0, 1]: the ring weight 2πr stays away from the axis.
    prm.parse_input_from_string("subsection Geometry\n set Type = blocks\n set Blocks = block: 1, 0, 3, 1, 6, 3\nend\n"
                                "subsection Heat\n set Initial temperature = 293 + x + 2*y\nend\n");
    const Scene                                    scene;
    parallel::distributed::Triangulation<2>        tria(MPI_COMM_WORLD);
    Geometry<2>                                    geometry;
    ThermalBoundaryConditions<2>                   bcs;
    ThermalProblem<2>::Parameters                  parameters;
    std::map<types::material_id, ThermalMaterial> materials;
    TimerOutput timer(MPI_COMM_WORLD, std::cout, TimerOutput::never, TimerOutput::wall_times);
    geometry.parse_parameters(prm, scene);
    geometry.create(tria);
    parameters.parse_parameters(prm, scene);
    parameters.axisymmetric = axisymmetric;
    bcs.parse_parameters(prm, scene, geometry);
    prm.enter_subsection("Material");
    const auto m = ThermalMaterial::parse_parameters(prm, scene, "Material", rho, cap);
    prm.leave_subsection();
    for (const auto &[name, id] : geometry.body_names())
      materials[id] = m;
    auto problem = std::make_unique<ThermalProblem<2>>(tria, parameters, bcs, materials, timer);
    problem->setup(0);

    // A distorted configuration: u = (0.3 x y, 0.1 x y), bilinear: the Q1 mapping is exact.
    DoFHandler<2> mech(tria);
    FESystem<2>   mech_fe(FE_Q<2>(1), 2);
    mech.distribute_dofs(mech_fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(mech, relevant);
    TrilinosWrappers::MPI::Vector u_owned(mech.locally_owned_dofs(), MPI_COMM_WORLD);
    FunctionParser<2>             motion(2);
    motion.initialize("x,y", "0.3*x*y; 0.1*x*y", {});
    VectorTools::interpolate(mech, motion, u_owned);
    TrilinosWrappers::MPI::Vector u(mech.locally_owned_dofs(), relevant, MPI_COMM_WORLD);
    u = u_owned;
    problem->set_configuration(mech, u);

    const auto  &dofs = problem->get_dof_handler();
    const auto  &q    = problem->get_quadrature();
    const double pi2  = 2 * numbers::PI;
    // The loops the tables replaced, as they were written.
    double H_loop = 0, S_loop = 0;
    {
      const MappingQ<2>   reference(1);
      FEValues<2>         fe_values(reference, dofs.get_fe(), q, update_values | update_JxW_values | update_quadrature_points);
      std::vector<double> T_q(q.size());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values.get_function_values(problem->temperature(), T_q);
            for (unsigned int k = 0; k < q.size(); ++k)
              H_loop += rho * cap * T_q[k] * fe_values.JxW(k) *
                        (axisymmetric ? pi2 * fe_values.quadrature_point(k)[0] : 1.);
          }
      H_loop = Utilities::MPI::sum(H_loop, MPI_COMM_WORLD);
    }
    // A source of 1 mW/mm³ on the cells left of x = 2 (reference), 0 elsewhere.
    const ThermalProblem<2>::HeatSource source = [](const DoFHandler<2>::active_cell_iterator &cell, unsigned int) {
      return cell->center()[0] < 2 ? 1. : 0.;
    };
    // The source's integral on the current configuration, as the loop was written.
    const auto source_loop = [&]() {
      double        sum = 0;
      FEValues<2> fe_values(problem->get_mapping(), dofs.get_fe(), q, update_JxW_values | update_quadrature_points);
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center()[0] < 2)
          {
            fe_values.reinit(cell);
            for (unsigned int k = 0; k < q.size(); ++k)
              sum += source(cell, k) * fe_values.JxW(k) * (axisymmetric ? pi2 * fe_values.quadrature_point(k)[0] : 1.);
          }
      return Utilities::MPI::sum(sum, MPI_COMM_WORLD);
    };
    S_loop = source_loop();
    problem->set_heat_source(source);
    const double H = problem->heat_content(), S = problem->integrate(source);

    // Closed forms. Heat content on the reference block (mass conservation),
    // T linear: plane ρc ∫(293 + x + 2y) dA = ρc (586 + 4 + 2) = 592 ρc;
    // axisymmetric 2π ρc ∫(293 + x + 2y) x dA = 2π ρc (293·4 + 26/3 + 4).
    const double H_exact = axisymmetric ? pi2 * rho * cap * (293 * 4 + 26. / 3 + 4) : rho * cap * 592;
    // Source: the image of [1, 2] x [0, 1] under x' = x (1 + 0.3 y), y' = y (1 + 0.1 x):
    // det F = (1 + 0.3 y)(1 + 0.1 x) − (0.3 x)(0.1 y) = 1 + 0.1 x + 0.3 y; plane
    // ∫∫ det F = 1 + 0.15 + 0.15 = 1.3; axisymmetric 2π ∫∫ x' det F
    // = 2π [∫x dx ∫(1 + 0.3y)² dy + 0.1 ∫x² dx ∫(1 + 0.3y) dy] = 2π (1.5·1.33 + 0.1·7/3·1.15).
    const double S_exact = axisymmetric ? pi2 * (1.5 * 1.33 + 0.1 * 7. / 3 * 1.15) : 1.3;
    if (root)
      std::cout << std::scientific << std::setprecision(15) << (axisymmetric ? "axisymmetric" : "plane")
                << ":\n   heat content " << H << " mJ, loop " << H_loop << ", closed form " << H_exact
                << "\n   source integral " << S << " mW, loop " << S_loop << ", closed form " << S_exact << "\n";
    check(H == H_loop, "heat content = the FEValues loop, bit for bit");
    check(std::abs(H - H_exact) < 1e-12 * H_exact, "heat content = closed form");
    check(S == S_loop, "source integral on the moved configuration = the FEValues loop, bit for bit");
    check(std::abs(S - S_exact) < 1e-12 * S_exact, "source integral = closed form");

    // Temperatures at a quadrature rule's points: = FEValues::get_function_values, bit for bit.
    const QGauss<2>     q3(3);
    const MappingQ<2>   reference(1);
    FEValues<2>         fe_values(reference, dofs.get_fe(), q3, update_values);
    std::vector<double> T_new, T_old, T_fe(q3.size());
    // Both paths: by the table's dof positions (the fields have its layout)
    // and by global look-ups.
    const bool by_table = problem->point_values_by_table();
    check(by_table, "the temperature fields have the reference table's layout");
    for (const bool table_path : {true, false})
      {
        bool same = true;
        for (const auto &cell : dofs.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              problem->temperature_at_quadrature_points(cell, q3, T_new, T_old, table_path);
              fe_values.reinit(cell);
              fe_values.get_function_values(problem->temperature(), T_fe);
              same = same && T_new == T_fe;
            }
        same = Utilities::MPI::min(same ? 1 : 0, MPI_COMM_WORLD) == 1;
        check(same, std::string("temperatures at quadrature points = FEValues::get_function_values, bit "
                                "for bit (") + (table_path ? "table" : "look-ups") + ")");
      }
    // A second configuration in the same layout (the vertices' dof
    // positions are kept from the first): the bilinear motion plus a
    // translation by 0.5 in x. Plane: the area is unchanged, 1.3;
    // axisymmetric: x' grows by 0.5, + 2π · 0.5 · 1.3.
    motion.initialize("x,y", "0.3*x*y + 0.5; 0.1*x*y", {});
    VectorTools::interpolate(mech, motion, u_owned);
    u = u_owned;
    problem->set_configuration(mech, u);
    const double S2_loop = source_loop();
    const double S2 = problem->integrate(source), S2_exact = axisymmetric ? S_exact + pi2 * 0.5 * 1.3 : 1.3;
    // A source zero everywhere: no cell is visited (no table is built), 0.
    const double zero = problem->integrate([](const DoFHandler<2>::active_cell_iterator &, unsigned int) { return 0.; });
    if (root)
      std::cout << "   moved again: source integral " << S2 << " mW, loop " << S2_loop << ", closed form "
                << S2_exact << "; zero source " << zero << "\n";
    check(std::abs(S2 - S2_exact) < 1e-12 * S2_exact, "second configuration: source integral = closed form");
    check(std::abs(S2 - S2_loop) <= 1e-14 * S2_exact, "second configuration: source integral = the FEValues loop");
    check(zero == 0, "a source zero everywhere integrates to 0");
    problem.reset(); // before mech goes
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  check.print_on_this_process(root);
  try
    {
      run(false);
      run(true);
    }
  catch (const std::exception &e)
    {
      std::cerr << "exception: " << e.what() << std::endl;
      return 2;
    }
  return check.finish();
}
