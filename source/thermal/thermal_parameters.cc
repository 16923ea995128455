// The heat problem's input: its material block, its boundary conditions and
// its time integration entries, each checked against the scene before any work.
#include <anvil/core/dof_limit.h>
#include <anvil/core/expression.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/thermal/thermal_problem.h>

#include <cctype>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// Whether a formula names the time t (a token "t", not a letter of a
    /// longer name such as sqrt or tanh): without it, it is constant in time.
    bool names_time(const std::string &formula)
    {
      auto part_of_name = [](const char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
      for (std::size_t i = formula.find('t'); i != std::string::npos; i = formula.find('t', i + 1))
        if ((i == 0 || !part_of_name(formula[i - 1])) &&
            (i + 1 == formula.size() || !part_of_name(formula[i + 1])))
          return true;
      return false;
    }

    /// Heat DoFs up to which KLU on M + γK costs less than GMRES with one
    /// AMG V-cycle (contrib/bench/heat_scaling.py and the heat plate with its
    /// consistent mass to 20 s, one core; doc/thermal.md, session 24). 2D:
    /// KLU 8 % cheaper over the run at 15 625 DoFs, AMG 2.4 times cheaper at
    /// 62 001: the two meet near 18 000 (KLU's work grows as N^1.5, AMG's as
    /// N: 5.2 to 6.3 GMRES iterations per solve from 4 k to 1 M). 3D: KLU
    /// wins at 1331, AMG by 6.4 times at 4913 (the factor fills as N^4/3),
    /// as the mechanics' (linear_solver.h). Before: 100 000 unmeasured, with
    /// KLU 2.4 times slower at 62 001 in 2D and 13 times at 15 625 in 3D.
    constexpr unsigned int measured_heat_direct_solver_limit(const int dim)
    {
      return dim == 2 ? 20000 : 2000;
    }
  } // namespace

  // ---------------------------------------------------------------- material

  void ThermalMaterial::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Thermal");
    prm.declare_entry("Conductivity", "50", Patterns::Double(0),
                      "Thermal conductivity k0 at the reference temperature, N/(s K) = mW/(mm K) "
                      "(= W/(m K)); steel about 50.");
    prm.declare_entry("Conductivity temperature coefficient", "0", Patterns::Double(),
                      "a in k(T) = k0 (1 + a (T - Reference temperature)), 1/K; 0: constant k.");
    prm.declare_entry("Reference temperature", "293", Patterns::Double(0),
                      "T_ref of the conductivity law, K.");
    prm.leave_subsection();
  }

  ThermalMaterial ThermalMaterial::parse_parameters(ParameterHandler &prm, const Scene &scene,
                                                    const std::string &path, const double density,
                                                    const double heat_capacity)
  {
    ThermalMaterial m;
    m.density       = density;
    m.heat_capacity = heat_capacity;
    prm.enter_subsection("Thermal");
    m.conductivity          = prm.get_double("Conductivity");
    m.conductivity_slope    = prm.get_double("Conductivity temperature coefficient");
    m.reference_temperature = prm.get_double("Reference temperature");
    prm.leave_subsection();
    if (!(m.reference_temperature > 0))
      scene.fail(path + "/Thermal/Reference temperature",
                 "= " + std::to_string(m.reference_temperature) +
                   " K: expected an absolute temperature > 0 K");
    if (!(density > 0) || !(heat_capacity > 0))
      scene.fail(path, "has density " + std::to_string(density) + " and heat capacity " +
                         std::to_string(heat_capacity) + ": both must be > 0 for a temperature field");
    return m;
  }

  // ------------------------------------------------------ boundary conditions

  template <int dim>
  void ThermalBoundaryConditions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("Temperature", "", Patterns::Anything(),
                      "Prescribed temperature: 'boundary: expr; ...' in K, expressions in x, y(, z), t.");
    prm.declare_entry("Flux", "", Patterns::Anything(),
                      "Heat flux into the body: 'boundary: expr; ...' in mW/mm^2 (= N/(mm s)).");
    prm.declare_entry("Convection", "", Patterns::Anything(),
                      "q = h (T_inf - T): 'boundary: h, T_inf; ...', h in mW/(mm^2 K), T_inf in K.");
    prm.declare_entry("Radiation", "", Patterns::Anything(),
                      "q = emissivity sigma (T_inf^4 - T^4), sigma = 5.670374e-11 mW/(mm^2 K^4): "
                      "'boundary: emissivity, T_inf; ...'.");
    prm.leave_subsection();
  }

  template <int dim>
  void ThermalBoundaryConditions<dim>::parse_parameters(ParameterHandler &prm, const Scene &scene,
                                                        const Geometry<dim> &geometry)
  {
    boundaries.clear();
    prm.enter_subsection("Heat");
    prm.enter_subsection("Boundary conditions");
    const std::vector<std::pair<std::string, unsigned int>> kinds = {
      {"Temperature", 1}, {"Flux", 1}, {"Convection", 2}, {"Radiation", 2}};
    std::map<std::string, std::string> texts;
    for (const auto &k : kinds)
      texts[k.first] = prm.get(k.first);
    prm.leave_subsection();
    prm.leave_subsection();

    for (const auto &[kind, n_values] : kinds)
      {
        const std::string path = "Heat/Boundary conditions/" + kind;
        const std::string form = n_values == 1 ? "'boundary: expr'" :
                                 kind == "Convection" ? "'boundary: h, T_inf'" :
                                                        "'boundary: emissivity, T_inf'";
        for (const auto &item : split_outside_parentheses(texts[kind], ';'))
          {
            if (item.empty())
              continue;
            const auto colon = item.find(':');
            if (colon == std::string::npos || trim(item.substr(0, colon)).empty())
              scene.fail(path, "has '" + item + "' without a boundary name: expected " + form);
            const std::string name = trim(item.substr(0, colon));
            const auto id = geometry.boundary_id(name, scene.where(path) + ": '" + path + "'");
            const auto values = split_outside_parentheses(item.substr(colon + 1), ',');
            if (values.size() != n_values || values[0].empty())
              scene.fail(path, "has '" + item + "': expected " + form);
            Boundary &b = boundaries[id];
            b.name      = name;
            auto parse  = [&](const std::string &text) { return parse_expression<dim>(text, scene, path); };
            auto &slot  = kind == "Temperature" ? b.temperature :
                          kind == "Flux"        ? b.flux :
                          kind == "Convection"  ? b.h : b.emissivity;
            if (slot)
              scene.fail(path, "names the boundary '" + name + "' twice");
            slot = parse(values[0]);
            if (kind == "Temperature")
              b.temperature_varies = names_time(values[0]);
            if (kind == "Flux")
              b.flux_varies = names_time(values[0]);
            if (kind == "Convection")
              {
                b.T_convection        = parse(values[1]);
                b.h_varies            = names_time(values[0]);
                b.T_convection_varies = names_time(values[1]);
              }
            if (kind == "Radiation")
              b.T_radiation = parse(values[1]);
            if (b.temperature && (b.flux || b.h || b.emissivity))
              scene.fail(path, "gives the boundary '" + name +
                                 "' a Temperature and a flux, convection or radiation: a prescribed "
                                 "temperature takes nothing else");
          }
      }
  }

  // -------------------------------------------------------------- parameters

  template <int dim>
  void ThermalProblem<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Heat");
    prm.declare_entry("Initial temperature", "293", Patterns::Anything(),
                      "T(x, 0) in K: an expression in x, y(, z) (t = start time). With a steady "
                      "initial field (or Method = steady): Newton's first guess.");
    prm.declare_entry("Initial temperature field", "expression",
                      Patterns::Selection("expression|steady"),
                      "expression: T(x, 0) = Initial temperature; steady: the steady temperature "
                      "of the Heat boundary conditions and Source at t = 0 (-K(T) T + F = 0, no "
                      "mechanics' or contact heat), e.g. a part in equilibrium with a furnace or "
                      "a cooled die before forming starts (doc/thermal.md).");
    prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2),
                      "Degree of the temperature elements: 1 (Q1) or 2 (Q2). Heat sources from the "
                      "mechanics are given at the points of QGauss(degree + 1): use the mechanics' degree.");
    prm.declare_entry("Source", "", Patterns::Anything(),
                      "Volumetric heat source r in mW/mm^3 (= MPa/s), an expression in x, y(, z), t; "
                      "empty: none (the mechanics' dissipation is added separately).");
    prm.enter_subsection("Time integration");
    prm.declare_entry("Method", "DIRK order 3",
                      Patterns::Selection("backward Euler|DIRK order 2|DIRK order 3|DIRK order 4|DIRK order 5|steady"),
                      "ARKode's implicit diagonally implicit Runge-Kutta method of that order "
                      "(SUNDIALS' default table: SDIRK-2-1-2, ARK324L2SA-DIRK-4-2-3, SDIRK-5-3-4, "
                      "ARK548L2SA-DIRK-8-4-5); backward Euler (one stage, no error estimate: "
                      "needs a Fixed step size) is the method of Physics/Coupling = monolithic, "
                      "for comparisons with it. steady (Physics/Coupling = thermal only): no "
                      "time integration, each step (and t = 0) is the steady state of the loads "
                      "at its end time, solved by Newton (Heat/Steady state): a sequence of "
                      "steady states, as Abaqus' *HEAT TRANSFER, STEADY STATE.");
    prm.declare_entry("Relative tolerance", "1e-6", Patterns::Double(0),
                      "ARKode's relative local error tolerance (dimensionless).");
    prm.declare_entry("Absolute tolerance", "1e-6", Patterns::Double(0),
                      "ARKode's absolute local error tolerance, K.");
    prm.declare_entry("Fixed step size", "0", Patterns::Double(0),
                      "Internal step of ARKode in s (rounded down to divide each mechanical step); "
                      "0: adaptive steps from the tolerances.");
    prm.declare_entry("Maximum internal steps", "5000", Patterns::Integer(1),
                      "ARKode steps per mechanical time step before it gives up (the step is cut back).");
    prm.declare_entry("Maximum nonlinear iterations", "10", Patterns::Integer(1),
                      "Newton iterations per stage before ARKode retries with a smaller step.");
    prm.leave_subsection();
    prm.enter_subsection("Steady state");
    prm.declare_entry("Maximum iterations", "30", Patterns::Integer(1),
                      "Newton iterations of one steady solve before it fails (a step is then "
                      "cut back, the loads moved less; at t = 0 the run stops with exit 3).");
    prm.declare_entry("Tolerance", "1e-8", Patterns::Double(0),
                      "Newton stops after a full step whose largest temperature change is at most "
                      "this, K (convergence is quadratic: the error left is ~ its square).");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type", "automatic", Patterns::Selection("automatic|direct|iterative"),
                      "Newton matrix M + gamma K: direct (Amesos KLU), iterative (GMRES with AMG), "
                      "automatic: direct below 'Direct solver limit' DoFs.");
    prm.declare_entry("Mass matrix", "consistent", Patterns::Selection("consistent|lumped"),
                      "consistent (solved by CG + Jacobi) or lumped (row sums: a diagonal "
                      "mass, cheaper, first-order accurate in space for the capacity).");
    prm.declare_entry("Direct solver limit", "measured", Patterns::Anything(),
                      "Number of DoFs up to which 'automatic' chooses the direct solver; measured: "
                      "where KLU and GMRES + AMG cost the same on the heat plate (contrib/bench/"
                      "heat_scaling.py, doc/thermal.md), " +
                        std::to_string(measured_heat_direct_solver_limit(2)) + " in 2D, " +
                        std::to_string(measured_heat_direct_solver_limit(3)) + " in 3D.");
    prm.leave_subsection();
    ThermalBoundaryConditions<dim>::declare_parameters(prm);
    prm.leave_subsection();
  }

  template <int dim>
  void ThermalProblem<dim>::Parameters::parse_parameters(ParameterHandler &prm, const Scene &scene)
  {
    prm.enter_subsection("Heat");
    initial_temperature = prm.get("Initial temperature");
    initial_temperature_location = scene.where("Heat/Initial temperature");
    steady_initial = prm.get("Initial temperature field") == "steady";
    polynomial_degree   = prm.get_integer("Polynomial degree");
    source              = trim(prm.get("Source"));
    prm.enter_subsection("Time integration");
    steady = prm.get("Method") == "steady";
    order  = prm.get("Method") == "backward Euler" ? 1 : steady ? 3 : prm.get("Method").back() - '0';
    relative_tolerance       = prm.get_double("Relative tolerance");
    absolute_tolerance       = prm.get_double("Absolute tolerance");
    fixed_step_size          = prm.get_double("Fixed step size");
    max_internal_steps       = prm.get_integer("Maximum internal steps");
    max_nonlinear_iterations = prm.get_integer("Maximum nonlinear iterations");
    prm.leave_subsection();
    prm.enter_subsection("Steady state");
    steady_max_iterations = prm.get_integer("Maximum iterations");
    steady_tolerance      = prm.get_double("Tolerance");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    linear_solver       = prm.get("Type");
    lumped_mass         = prm.get("Mass matrix") == "lumped";
    direct_solver_limit = parse_dof_limit(prm.get("Direct solver limit"), measured_heat_direct_solver_limit(dim),
                                          scene, "Heat/Linear solver/Direct solver limit");
    prm.leave_subsection();
    prm.leave_subsection();
    parse_expression<dim>(initial_temperature, scene, "Heat/Initial temperature");
    if (!source.empty())
      parse_expression<dim>(source, scene, "Heat/Source");
    if (order == 1 && !(fixed_step_size > 0))
      scene.fail("Heat/Time integration/Method",
                 "is backward Euler, which has no error estimate: give a Fixed step size > 0 "
                 "(larger than the time step: one step per mechanical step)");
    if ((steady || steady_initial) && !(steady_tolerance > 0))
      scene.fail("Heat/Steady state/Tolerance", "= 0 K: expected a temperature change > 0 K "
                                                "(round-off never reaches 0)");
    if (!(relative_tolerance > 0) && !(absolute_tolerance > 0))
      scene.fail("Heat/Time integration/Relative tolerance",
                 "and the absolute tolerance are both 0: at least one must be > 0");
  }

  ANVIL_INSTANTIATE_CLASS(ThermalBoundaryConditions)
#define ANVIL_INSTANTIATE_PARAMETERS(dim) template struct ThermalProblem<dim>::Parameters;
  ANVIL_INSTANTIATE(ANVIL_INSTANTIATE_PARAMETERS)
#undef ANVIL_INSTANTIATE_PARAMETERS
} // namespace anvil
