// Verification of ThermalProblem (heat equation + ARKode) against closed forms:
//  1. transient conduction into a half-space (erfc), spatial and temporal orders;
//  2. steady slab with a fixed temperature and convection (2D and 3D);
//  3. axisymmetric steady radial conduction through a thick cylinder wall.
// Runs the same under mpirun -np 2. Prints every measured number; exits 1 on a failed check.
#include "check.h"

#include <deal.II/base/function.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/thermal/thermal_problem.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace anvil;

namespace
{
  anvil::testing::Checks check;
  bool                   root = true;

  // Steel-like: rho c = 3.588 N/(mm^2 K), k = 50 N/(s K): kappa = 13.94 mm^2/s.
  constexpr double rho = 7.8e-9, cap = 4.6e8, k0 = 50, kappa = k0 / (rho * cap);

  template <int dim>
  struct Model
  {
    parallel::distributed::Triangulation<dim>     tria{MPI_COMM_WORLD};
    Geometry<dim>                                 geometry;
    ThermalBoundaryConditions<dim>                bcs;
    typename ThermalProblem<dim>::Parameters      parameters;
    std::map<types::material_id, ThermalMaterial> materials;
    TimerOutput timer{MPI_COMM_WORLD, std::cout, TimerOutput::never, TimerOutput::wall_times};
    std::unique_ptr<ThermalProblem<dim>>          problem;
    typename ThermalProblem<dim>::Statistics      total;

    Model(const std::string &text, const bool axisymmetric = false, const double t0 = 0)
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
      parameters.parse_parameters(prm, scene);
      parameters.axisymmetric = axisymmetric;
      bcs.parse_parameters(prm, scene, geometry);
      prm.enter_subsection("Material");
      const auto m = ThermalMaterial::parse_parameters(prm, scene, "Material", rho, cap);
      prm.leave_subsection();
      for (const auto &[name, id] : geometry.body_names())
        materials[id] = m;
      problem = std::make_unique<ThermalProblem<dim>>(tria, parameters, bcs, materials, timer);
      problem->setup(t0);
    }

    /// n_steps coupled-loop steps from t0 to t1 (solve_step + commit).
    bool run(const double t0, const double t1, const unsigned int n_steps)
    {
      for (unsigned int s = 0; s < n_steps; ++s)
        {
          const auto st = problem->solve_step(t0 + (t1 - t0) * s / n_steps, t0 + (t1 - t0) * (s + 1) / n_steps);
          if (!st.converged)
            {
              if (root)
                std::cout << "  ARKode failed: " << st.failure << std::endl;
              return false;
            }
          problem->commit();
          total.internal_steps += st.internal_steps;
          total.attempted_steps += st.attempted_steps;
          total.error_test_failures += st.error_test_failures;
          total.nonlinear_iterations += st.nonlinear_iterations;
          total.nonlinear_failures += st.nonlinear_failures;
          total.linear_setups += st.linear_setups;
          total.linear_solves += st.linear_solves;
          total.linear_iterations += st.linear_iterations;
          total.mass_solves += st.mass_solves;
          total.rhs_evaluations += st.rhs_evaluations;
        }
      return true;
    }

    std::string statistics() const
    {
      std::ostringstream s;
      s << "steps " << total.internal_steps << " (attempts " << total.attempted_steps << ", error-test fails "
        << total.error_test_failures << "), Newton its " << total.nonlinear_iterations << " (conv fails "
        << total.nonlinear_failures << "), lin setups " << total.linear_setups << ", lin solves "
        << total.linear_solves << ", mass solves " << total.mass_solves << ", f evals " << total.rhs_evaluations;
      return s.str();
    }

    double l2_error(const Function<dim> &exact) const
    {
      dealii::Vector<float> cellwise(tria.n_active_cells());
      VectorTools::integrate_difference(problem->get_mapping(), problem->get_dof_handler(),
                                        problem->temperature(), exact, cellwise,
                                        QGauss<dim>(problem->get_dof_handler().get_fe().degree + 3),
                                        VectorTools::L2_norm);
      return VectorTools::compute_global_error(tria, cellwise, VectorTools::L2_norm);
    }

    /// max over the nodes of |T − exact|.
    double nodal_error(const Function<dim> &exact) const
    {
      std::map<types::global_dof_index, Point<dim>> support;
      DoFTools::map_dofs_to_support_points(problem->get_mapping(), problem->get_dof_handler(), support);
      const auto owned = problem->get_dof_handler().locally_owned_dofs();
      double     e     = 0;
      for (const auto &[i, x] : support)
        if (owned.is_element(i))
          e = std::max(e, std::abs(problem->temperature()(i) - exact.value(x)));
      return Utilities::MPI::max(e, MPI_COMM_WORLD);
    }
  };

  template <int dim>
  struct HalfSpace : Function<dim>
  {
    double T0, T1;
    HalfSpace(double T0, double T1, double t)
      : Function<dim>(1, t), T0(T0), T1(T1)
    {}
    double value(const Point<dim> &p, unsigned int = 0) const override
    {
      const double t = this->get_time();
      return t <= 0 ? (p[0] == 0 ? T1 : T0) : T0 + (T1 - T0) * std::erfc(p[0] / (2 * std::sqrt(kappa * t)));
    }
  };

  std::string half_space_prm(const unsigned int n, const double L, const std::string &integration,
                             const std::string &initial = "300")
  {
    return "subsection Geometry\n set Type = blocks\n set Blocks = bar: 0, 0, " + std::to_string(L) +
           ", 1, " + std::to_string(n) + ", 1\nend\n"
           "subsection Heat\n set Initial temperature = " + initial + "\n"
           " subsection Time integration\n" + integration + " end\n"
           " subsection Boundary conditions\n  set Temperature = left: 400\n end\nend\n";
  }

  double order(double e_coarse, double e_fine) { return std::log2(e_coarse / e_fine); }

  // ---------------------------------------------------------------- test 1
  void half_space()
  {
    const double T0 = 300, T1 = 400, t_end = 1, L = 20 * std::sqrt(kappa * t_end);
    if (root)
      std::cout << "\n1. Half-space conduction: kappa = " << kappa << " mm^2/s, L = " << L
                << " mm, T0 = 300 K, T1 = 400 K\n";

    // 1a. Space: meshes, tight adaptive ARKode (order 4), from T = T0 at t = 0.
    if (root)
      std::cout << "  1a. space (Q1, DIRK order 4 adaptive, rtol = atol = 1e-10)\n"
                << "      cells     h(mm)     L2 err(t=1)   order   max nodal err/(T1-T0) at t = 0.25, 0.5, 1\n";
    std::vector<double> errors;
    double              finest_nodal = 0;
    for (const unsigned int n : {80u, 160u, 320u, 640u})
      {
        Model<2> m(half_space_prm(n, L, "  set Method = DIRK order 4\n  set Relative tolerance = 1e-10\n"
                                        "  set Absolute tolerance = 1e-10\n"));
        std::vector<double> nodal;
        double              t = 0;
        for (const double t_next : {0.25, 0.5, 1.0})
          {
            m.run(t, t_next, 2);
            t = t_next;
            nodal.push_back(m.nodal_error(HalfSpace<2>(T0, T1, t)) / (T1 - T0));
          }
        errors.push_back(m.l2_error(HalfSpace<2>(T0, T1, t_end)));
        finest_nodal = *std::max_element(nodal.begin(), nodal.end());
        if (root)
          {
            std::cout << "      " << std::setw(5) << n << "  " << std::setw(8) << L / n << "  " << std::setw(12)
                      << std::scientific << std::setprecision(4) << errors.back() << "  " << std::fixed
                      << std::setprecision(2) << std::setw(6)
                      << (errors.size() > 1 ? order(errors[errors.size() - 2], errors.back()) : 0.)
                      << std::scientific << std::setprecision(3);
            for (const double e : nodal)
              std::cout << "   " << e;
            std::cout << std::fixed << "\n        ARKode: " << m.statistics() << "\n";
          }
      }
    const double space_order = order(errors[errors.size() - 2], errors.back());
    check(space_order > 1.7, "space order " + std::to_string(space_order) + " > 1.7");
    check(finest_nodal < 1e-3, "finest max nodal error / (T1 - T0) = " + std::to_string(finest_nodal) + " < 1e-3");

    // 1b. Time: fixed steps from the exact profile at t = 0.25 to t = 1 on one mesh,
    // error against a reference with 1024 steps of DIRK order 4 on the same mesh.
    const unsigned int n  = 160;
    const double       ts = 0.25;
    std::ostringstream initial;
    initial << std::setprecision(17) << T0 << " + " << (T1 - T0) << " * erfc(x / (2 * sqrt(" << kappa << " * " << ts << ")))";
    const auto fixed = [&](unsigned int method, double dt) {
      std::ostringstream s;
      s << "  set Method = DIRK order " << method << "\n  set Fixed step size = " << std::setprecision(17) << dt
        << "\n  set Relative tolerance = 1e-12\n  set Absolute tolerance = 1e-12\n  set Maximum internal steps = 100000\n";
      return s.str();
    };
    Model<2> reference(half_space_prm(n, L, fixed(4, (t_end - ts) / 256), initial.str()), false, ts);
    reference.run(ts, t_end, 1);
    const double reference_error = reference.l2_error(HalfSpace<2>(T0, T1, t_end)); // collective: not inside if (root)
    if (root)
      std::cout << "  1b. time (fixed steps, " << n << " cells, from the exact profile at t = 0.25 s to 1 s; "
                << "reference: DIRK 4 with 256 steps; its error vs erfc: L2 "
                << reference_error << ")\n";
    for (const unsigned int method : {2u, 3u, 4u})
      {
        std::vector<double> e;
        if (root)
          std::cout << "      DIRK order " << method << ":   steps   max |T - T_ref| (K)   order\n";
        for (const unsigned int steps : {4u, 8u, 16u, 32u})
          {
            Model<2> m(half_space_prm(n, L, fixed(method, (t_end - ts) / steps), initial.str()), false, ts);
            m.run(ts, t_end, 1);
            auto d = m.problem->temperature();
            TrilinosWrappers::MPI::Vector diff(m.problem->get_dof_handler().locally_owned_dofs(), MPI_COMM_WORLD);
            diff = m.problem->temperature();
            TrilinosWrappers::MPI::Vector r(diff);
            r = reference.problem->temperature();
            diff -= r;
            e.push_back(diff.linfty_norm());
            if (root)
              std::cout << "                     " << std::setw(5) << steps << "   " << std::scientific
                        << std::setprecision(4) << e.back() << "          " << std::fixed << std::setprecision(2)
                        << (e.size() > 1 ? order(e[e.size() - 2], e.back()) : 0.) << "   [" << m.statistics()
                        << "]\n";
          }
        const double p = order(e[e.size() - 2], e.back());
        check(std::abs(p - method) < 0.4, "DIRK order " + std::to_string(method) + ": observed time order " +
                                            std::to_string(p) + " within 0.4");
      }
  }

  // ---------------------------------------------------------------- test 2
  template <int dim>
  void convection_slab()
  {
    const double L = 10, h = 0.5, T1 = 500, T_inf = 300;
    const double exact = (k0 * T1 / L + h * T_inf) / (k0 / L + h);
    const std::string blocks = dim == 2 ? "slab: 0, 0, 10, 1, 8, 1" : "slab: 0, 0, 0, 10, 1, 1, 8, 1, 1";
    Model<dim> m("subsection Geometry\n set Type = blocks\n set Blocks = " + blocks + "\nend\n"
                 "subsection Heat\n set Initial temperature = 300\n"
                 " subsection Time integration\n  set Relative tolerance = 1e-6\n  set Absolute tolerance = 1e-6\n end\n"
                 " subsection Boundary conditions\n  set Temperature = left: 500\n"
                 "  set Convection = right: 0.5, 300\n end\nend\n");
    const double tau = L * L / kappa;
    m.run(0, 60 * tau, 20);
    // T at x = L: the largest x among the nodes.
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(m.problem->get_mapping(), m.problem->get_dof_handler(), support);
    double T_L = -1;
    for (const auto &[i, x] : support)
      if (m.problem->get_dof_handler().locally_owned_dofs().is_element(i) && std::abs(x[0] - L) < 1e-9)
        T_L = m.problem->temperature()(i);
    T_L = Utilities::MPI::max(T_L, MPI_COMM_WORLD);
    const double rel = std::abs(T_L - exact) / exact;
    const auto  &q   = m.problem->step_boundary_heat();
    const double dt  = 60 * tau / 20;
    if (root)
      std::cout << "\n2. Steady slab with convection (" << dim << "D): L = 10 mm, k = 50, h = 0.5 mW/(mm^2 K), T1 = 500, "
                << "T_inf = 300; t = 60 L^2/kappa\n   T(L) = " << std::setprecision(10) << T_L << " K, closed form "
                << exact << " K, relative error " << std::scientific << std::setprecision(3) << rel << std::fixed
                << "\n   last step heat: convection " << q.begin()->second / dt << " mW, Dirichlet "
                << m.problem->step_dirichlet_heat() / dt << " mW (steady: equal and opposite; exact flux "
                << h * (T_L - T_inf) << " mW/mm^2 x area " << (dim == 2 ? 1 : 1) << ")\n   ARKode: " << m.statistics()
                << "\n";
    check(rel < 1e-6, std::to_string(dim) + "D slab: relative error of T(L) " + std::to_string(rel) + " < 1e-6");
    check(std::abs(q.begin()->second + m.problem->step_dirichlet_heat()) < 1e-6 * std::abs(q.begin()->second),
          std::to_string(dim) + "D slab: steady heat balance convection + Dirichlet = 0");
  }

  // ---------------------------------------------------------------- test 3
  void cylinder_wall()
  {
    const double ri = 10, ro = 20, Ti = 500, To = 300;
    struct Log : Function<2>
    {
      double ri, ro, Ti, To;
      Log(double a, double b, double c, double d) : ri(a), ro(b), Ti(c), To(d) {}
      double value(const Point<2> &p, unsigned int = 0) const override
      {
        return Ti + (To - Ti) * std::log(p[0] / ri) / std::log(ro / ri);
      }
    } exact(ri, ro, Ti, To);
    if (root)
      std::cout << "\n3. Axisymmetric thick cylinder wall r in [10, 20] mm, T_i = 500 K, T_o = 300 K (steady)\n"
                << "   radial cells   L2 error (K mm)   order   max nodal error (K)\n";
    std::vector<double> e;
    for (const unsigned int cells : {4u, 8u, 16u})
      {
        Model<2> m("subsection Geometry\n set Type = tube\n set Inner radius = 10\n set Outer radius = 20\n"
                   " set Length = 5\n set Radial cells = " + std::to_string(cells) + "\n set Axial cells = 2\nend\n"
                   "subsection Heat\n set Initial temperature = 300\n"
                   " subsection Time integration\n  set Relative tolerance = 1e-6\n  set Absolute tolerance = 1e-6\n end\n"
                   " subsection Boundary conditions\n  set Temperature = inner: 500; outer: 300\n end\nend\n",
                   true);
        const double tau = (ro - ri) * (ro - ri) / kappa;
        m.run(0, 60 * tau, 10);
        e.push_back(m.l2_error(exact));
        const double nodal = m.nodal_error(exact);
        if (root)
          std::cout << "   " << std::setw(12) << cells << "   " << std::scientific << std::setprecision(4) << e.back()
                    << "        " << std::fixed << std::setprecision(2)
                    << (e.size() > 1 ? order(e[e.size() - 2], e.back()) : 0.) << "    " << std::scientific
                    << nodal << std::fixed << "\n     ARKode: " << m.statistics() << "\n";
      }
    check(e[1] < e[0] && e[2] < e[1], "cylinder wall: the error decreases with the mesh");
    check(order(e[1], e[2]) > 1.7, "cylinder wall: L2 order " + std::to_string(order(e[1], e[2])) + " > 1.7");
  }

  // ---------------------------------------------------------------- test 4
  // Adiabatic block heated by an expression source and a per-quadrature-point
  // source (1 K/s each), then moved to a configuration stretched by 2 in x.
  void sources_and_configuration()
  {
    Model<2> m("subsection Geometry\n set Type = blocks\n set Blocks = block: 0, 0, 2, 1, 4, 2\nend\n"
               "subsection Heat\n set Initial temperature = 293\n set Source = " + std::to_string(rho * cap) +
               "\n subsection Time integration\n  set Relative tolerance = 1e-10\n  set Absolute tolerance = 1e-10\n end\nend\n");
    unsigned int calls = 0;
    m.problem->set_heat_source([&](const typename DoFHandler<2>::active_cell_iterator &, unsigned int) {
      ++calls;
      return rho * cap;
    });
    const double H0 = m.problem->heat_content();
    m.run(0, 1, 2);
    const double H1 = m.problem->heat_content();
    std::vector<double> T_new, T_old;
    double              T_max_error = 0;
    const bool          by_table    = m.problem->point_values_by_table();
    for (const auto &cell : m.tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          m.problem->temperature_at_quadrature_points(cell, QGauss<2>(2), T_new, T_old, by_table);
          for (const double T : T_new)
            T_max_error = std::max(T_max_error, std::abs(T - 295));
        }
    T_max_error = Utilities::MPI::max(T_max_error, MPI_COMM_WORLD);
    // Stretch: u = (x, 0) doubles the volume. Mass is conserved (ρ dv = ρ₀ dV),
    // so the heat content is unchanged; the sources, given per current volume,
    // act on twice the volume.
    DoFHandler<2> mech(m.tria);
    FESystem<2>   fe(FE_Q<2>(1), 2);
    mech.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(mech, relevant);
    TrilinosWrappers::MPI::Vector u_owned(mech.locally_owned_dofs(), MPI_COMM_WORLD);
    FunctionParser<2> stretch(2);
    stretch.initialize("x,y", "x; 0", {});
    VectorTools::interpolate(mech, stretch, u_owned);
    TrilinosWrappers::MPI::Vector u(mech.locally_owned_dofs(), relevant, MPI_COMM_WORLD);
    u = u_owned;
    m.problem->set_configuration(mech, u);
    const double H2 = m.problem->heat_content();
    m.run(1, 2, 1);
    const double H3 = m.problem->heat_content();
    m.problem.reset(); // before mech goes
    const double V = 2, expected = 2 * rho * cap * V;
    if (root)
      std::cout << "\n4. Sources and configuration: adiabatic 2 x 1 mm block, 1 K/s from 'Source' + 1 K/s per quadrature point\n"
                << "   max |T - 295| at quadrature points after 1 s: " << std::scientific << T_max_error
                << "\n   heat content gain " << H1 - H0 << " mJ, expected " << expected
                << "\n   stretched x2 in x: heat content " << H2 << " mJ / before " << H1 << " = " << std::fixed
                << H2 / H1 << "; gain in the next second " << std::scientific << H3 - H2 << " mJ, expected "
                << 2 * expected << std::fixed << "\n   source callback calls on this rank: " << calls << "\n";
    check(T_max_error < 1e-6, "uniform heating: T = 295 K at the quadrature points");
    check(std::abs(H1 - H0 - expected) < 1e-8 * expected, "heat content gain = sources");
    check(std::abs(H2 / H1 - 1) < 1e-12, "deformed configuration keeps the heat content (mass conservation)");
    check(std::abs(H3 - H2 - 2 * expected) < 1e-8 * expected, "sources act on the deformed volume");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  check.print_on_this_process(root);
  std::cout << std::unitbuf;
  if (root)
    std::cout << "thermal_conduction on " << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) << " process(es)\n"
              << std::fixed;
  try
    {
      half_space();
      convection_slab<2>();
      convection_slab<3>();
      cylinder_wall();
      sources_and_configuration();
    }
  catch (const std::exception &e)
    {
      std::cerr << "exception: " << e.what() << std::endl;
      return 2;
    }
  return check.finish();
}
