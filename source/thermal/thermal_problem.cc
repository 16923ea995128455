// ThermalProblem: parameters, setup, the ARKode step and its heat balance, and
// the backward Euler hooks of the monolithic scheme. Long because those hooks
// (~60 lines) joined it; they could move to their own file.
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/expression.h>
#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/core/instantiate.h>
#include <anvil/thermal/thermal_problem.h>

#include "arkode_integrator.h"

#include <cmath>

namespace anvil
{
  using namespace dealii;

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
            if (kind == "Convection")
              b.T_convection = parse(values[1]);
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
                      "T(x, 0) in K: an expression in x, y(, z) (t = start time).");
    prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2),
                      "Degree of the temperature elements: 1 (Q1) or 2 (Q2). Heat sources from the "
                      "mechanics are given at the points of QGauss(degree + 1): use the mechanics' degree.");
    prm.declare_entry("Source", "", Patterns::Anything(),
                      "Volumetric heat source r in mW/mm^3 (= MPa/s), an expression in x, y(, z), t; "
                      "empty: none (the mechanics' dissipation is added separately).");
    prm.enter_subsection("Time integration");
    prm.declare_entry("Method", "DIRK order 3",
                      Patterns::Selection("backward Euler|DIRK order 2|DIRK order 3|DIRK order 4|DIRK order 5"),
                      "ARKode's implicit diagonally implicit Runge-Kutta method of that order "
                      "(SUNDIALS' default table: SDIRK-2-1-2, ARK324L2SA-DIRK-4-2-3, SDIRK-5-3-4, "
                      "ARK548L2SA-DIRK-8-4-5); backward Euler (one stage, no error estimate: "
                      "needs a Fixed step size) is the method of Physics/Coupling = monolithic, "
                      "for comparisons with it.");
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
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type", "automatic", Patterns::Selection("automatic|direct|iterative"),
                      "Newton matrix M + gamma K: direct (Amesos KLU), iterative (GMRES with AMG), "
                      "automatic: direct below 'Direct solver limit' DoFs.");
    prm.declare_entry("Mass matrix", "consistent", Patterns::Selection("consistent|lumped"),
                      "consistent (solved by CG + Jacobi) or lumped (row sums: a diagonal "
                      "mass, cheaper, first-order accurate in space for the capacity).");
    prm.declare_entry("Direct solver limit", "100000", Patterns::Integer(0),
                      "Number of DoFs up to which 'automatic' chooses the direct solver.");
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
    polynomial_degree   = prm.get_integer("Polynomial degree");
    source              = trim(prm.get("Source"));
    prm.enter_subsection("Time integration");
    order = prm.get("Method") == "backward Euler" ? 1 : prm.get("Method").back() - '0';
    relative_tolerance       = prm.get_double("Relative tolerance");
    absolute_tolerance       = prm.get_double("Absolute tolerance");
    fixed_step_size          = prm.get_double("Fixed step size");
    max_internal_steps       = prm.get_integer("Maximum internal steps");
    max_nonlinear_iterations = prm.get_integer("Maximum nonlinear iterations");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    linear_solver       = prm.get("Type");
    lumped_mass         = prm.get("Mass matrix") == "lumped";
    direct_solver_limit = prm.get_integer("Direct solver limit");
    prm.leave_subsection();
    prm.leave_subsection();
    parse_expression<dim>(initial_temperature, scene, "Heat/Initial temperature");
    if (!source.empty())
      parse_expression<dim>(source, scene, "Heat/Source");
    if (order == 1 && !(fixed_step_size > 0))
      scene.fail("Heat/Time integration/Method",
                 "is backward Euler, which has no error estimate: give a Fixed step size > 0 "
                 "(larger than the time step: one step per mechanical step)");
    if (!(relative_tolerance > 0) && !(absolute_tolerance > 0))
      scene.fail("Heat/Time integration/Relative tolerance",
                 "and the absolute tolerance are both 0: at least one must be > 0");
  }

  // ------------------------------------------------------------- the problem

  /// The semi-discrete system as the ARKode adapter sees it.
  template <int dim>
  struct ThermalProblem<dim>::Ode : public thermal::ImplicitSystem
  {
    ThermalProblem<dim> &p;
    explicit Ode(ThermalProblem<dim> &p)
      : p(p)
    {}
    void reinit_vector(Vector &v) const override { v.reinit(p.locally_owned_dofs, p.mpi_communicator); }
    int  rhs(const double t, const Vector &y, Vector &f) override
    {
      p.assemble(t, y, &f, nullptr);
      return 0;
    }
    int setup_jacobian(const double t, const Vector &y) override
    {
      // Linear problems on a frozen geometry: the Jacobian −K is assembled
      // once per configuration (unless a convection coefficient may vary in time).
      if (p.linear && p.tangent_current && !p.has_convection)
        return 0;
      p.assemble(t, y, nullptr, &p.tangent_matrix);
      p.tangent_current = true;
      return 0;
    }
    int jacobian_vmult(const Vector &v, Vector &Jv) override
    {
      p.tangent_matrix.vmult(Jv, v); // J = −∂(K T − F)/∂T
      Jv *= -1.;
      if (p.exchange.add_jacobian)
        {
          p.exchange.add_jacobian(v, Jv);
          Jv.compress(VectorOperation::add);
        }
      return 0;
    }
    int setup_newton_matrix(const double gamma) override
    {
      p.setup_newton(gamma);
      return 0;
    }
    int solve_newton_matrix(Vector &x, const Vector &b) override { return p.solve_newton(x, b, 0); }
    int mass_vmult(const Vector &v, Vector &Mv) override
    {
      if (p.parameters.lumped_mass)
        {
          Mv = v;
          Mv.scale(p.lumped_mass);
        }
      else
        p.mass_matrix.vmult(Mv, v);
      return 0;
    }
    int solve_mass(Vector &x, const Vector &b, const double tol) override
    {
      p.solve_mass(x, b, tol);
      return 0;
    }
  };

  template <int dim>
  ThermalProblem<dim>::ThermalProblem(const parallel::distributed::Triangulation<dim> &triangulation,
                                      const Parameters                                 &parameters,
                                      const ThermalBoundaryConditions<dim> &boundary_conditions,
                                      const std::map<types::material_id, ThermalMaterial> &materials,
                                      TimerOutput                                         &timer)
    : mpi_communicator(triangulation.get_communicator())
    , triangulation(triangulation)
    , parameters(parameters)
    , boundary_conditions(boundary_conditions)
    , materials(materials)
    , timer(timer)
    , fe(parameters.polynomial_degree)
    , reference_mapping(1)
    , dof_handler(triangulation)
    , quadrature(parameters.polynomial_degree + 1)
    , face_quadrature(parameters.polynomial_degree + 1)
    , direct_control(1, 0)
  {
    initial_function = parse_expression<dim>(parameters.initial_temperature, Scene(), "Heat/Initial temperature");
    if (!parameters.source.empty())
      source_function = parse_expression<dim>(parameters.source, Scene(), "Heat/Source");
    linear = true;
    for (const auto &[id, m] : materials)
      linear = linear && m.conductivity_slope == 0;
    for (const auto &[id, b] : boundary_conditions.boundaries)
      {
        linear         = linear && !b.emissivity;
        has_convection = has_convection || b.h;
      }
  }

  template <int dim>
  ThermalProblem<dim>::~ThermalProblem()
  {
    current_mapping.reset(); // it points to configuration
    dof_handler.clear();
  }

  template <int dim>
  const Mapping<dim> &ThermalProblem<dim>::get_mapping() const
  {
    return current_mapping ? *current_mapping : static_cast<const Mapping<dim> &>(reference_mapping);
  }

  template <int dim>
  void ThermalProblem<dim>::setup(const double start_time)
  {
    TimerOutput::Scope t(timer, "Heat: setup");
    dof_handler.distribute_dofs(fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

    hanging.clear();
    hanging.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging);
    hanging.close();

    // Dirichlet dofs: those on Temperature boundaries that no hanging node owns.
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    constraints.merge(hanging);
    std::map<types::global_dof_index, double> values;
    dirichlet_values(start_time, values);
    is_dirichlet.assign(locally_relevant_dofs.n_elements(), false);
    dirichlet_dofs.clear();
    for (const auto &[i, v] : values)
      if (!hanging.is_constrained(i))
        {
          constraints.add_line(i);
          is_dirichlet[locally_relevant_dofs.index_within_set(i)] = true;
          if (locally_owned_dofs.is_element(i))
            dirichlet_dofs.push_back(i);
        }
    constraints.close();
    has_dirichlet = Utilities::MPI::max(dirichlet_dofs.size(), mpi_communicator) > 0;

    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, true);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                               locally_relevant_dofs);
    for (auto *m : {&mass_matrix, &tangent_matrix, &newton_matrix})
      m->reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
    for (auto *v : {&lumped_mass, &mass_diagonal, &solution, &old_solution})
      v->reinit(locally_owned_dofs, mpi_communicator);
    for (auto *v : {&temperature_ghosted, &old_temperature_ghosted, &scratch_ghosted})
      v->reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    use_direct = parameters.linear_solver == "direct" ||
                 (parameters.linear_solver == "automatic" &&
                  dof_handler.n_dofs() <= parameters.direct_solver_limit);
    operators_current = false;
    tangent_current   = false;

    initial_function->set_time(start_time);
    VectorTools::interpolate(get_mapping(), dof_handler, *initial_function, solution);
    // The heat equation (radiation, conductivity slopes, softening) needs
    // absolute temperatures: T <= 0 K at a node is the scene's error.
    throw_recorded_input_error(mpi_communicator);
    const double lowest = Utilities::MPI::min(solution.size() ? solution.min() : 1., mpi_communicator);
    if (!(lowest > 0))
      throw InputError(parameters.initial_temperature_location +
                       ": 'Heat/Initial temperature' = '" + parameters.initial_temperature +
                       "' gives " + Utilities::to_string(lowest) +
                       " K at a node: expected an absolute temperature > 0 K everywhere");
    apply_dirichlet(start_time, solution);
    hanging.distribute(solution);
    old_solution            = solution;
    temperature_ghosted     = solution;
    old_temperature_ghosted = solution;
    committed_time          = start_time;
    total_heat_in.clear();
    total_source = 0;
  }

  template <int dim>
  void ThermalProblem<dim>::set_configuration(const DoFHandler<dim> &mechanics_dofs,
                                              const Vector          &displacement_ghosted)
  {
    current_mapping.reset();
    configuration.reinit(displacement_ghosted);
    configuration = displacement_ghosted;
    current_mapping = std::make_unique<MappingQEulerian<dim, Vector>>(
      mechanics_dofs.get_fe().degree, mechanics_dofs, configuration);
    operators_current = false;
    tangent_current   = false;
  }

  template <int dim>
  void ThermalProblem<dim>::set_heat_source(const HeatSource &source)
  {
    heat_source = source;
  }

  template <int dim>
  typename ThermalProblem<dim>::Statistics ThermalProblem<dim>::solve_step(const double time_old,
                                                                           const double time_new)
  {
    TimerOutput::Scope scope(timer, "Heat: solve");
    Statistics         stats;
    step_length = time_new - time_old;
    if (!operators_current)
      {
        assemble_mass();
        operators_current = true;
      }
    linear_iterations = 0;
    mass_solves       = 0;
    sources_current   = false; // the mechanics' sources are new every step

    Vector y(old_solution);
    apply_dirichlet(time_old, y);
    thermal::IntegratorSettings settings;
    settings.order                    = parameters.order;
    settings.relative_tolerance       = parameters.relative_tolerance;
    settings.absolute_tolerance       = parameters.absolute_tolerance;
    settings.fixed_step_size          = parameters.fixed_step_size;
    settings.max_internal_steps       = parameters.max_internal_steps;
    settings.max_nonlinear_iterations = parameters.max_nonlinear_iterations;
    settings.initial_step_size        = last_internal_step;
    settings.linear                   = linear;
    Ode        ode(*this);
    const auto s = thermal::integrate(ode, y, time_old, time_new, settings);

    stats.converged            = s.success;
    stats.failure              = s.failure;
    stats.internal_steps       = s.steps;
    stats.attempted_steps      = s.attempts;
    stats.error_test_failures  = s.error_test_failures;
    stats.nonlinear_iterations = s.nonlinear_iterations;
    stats.nonlinear_failures   = s.nonlinear_failures;
    stats.linear_setups        = s.linear_setups;
    stats.linear_solves        = s.linear_solves;
    stats.linear_iterations    = s.linear_iterations + linear_iterations;
    stats.mass_solves          = s.mass_solves;
    stats.rhs_evaluations      = s.rhs_evaluations;
    stats.last_internal_step   = s.last_step;
    if (!s.success)
      {
        solution            = old_solution;
        temperature_ghosted = old_temperature_ghosted;
        return stats;
      }
    // The next step starts from the largest step ARKode took here, not from
    // the last one: the end time cuts that one short by an amount that jumps
    // (from ~0 to a full step) with the last digits of the solution, and a
    // tiny initial step makes the next solve take several more steps. So one
    // round-off difference (e.g. 1 vs 2 processes) changed every later step.
    last_internal_step = s.largest_step > 0 ? s.largest_step : s.last_step;
    apply_dirichlet(time_new, y);
    hanging.distribute(y);
    solution            = y;
    temperature_ghosted = solution;

    step_balance(time_old, time_new);
    return stats;
  }

  template <int dim>
  void ThermalProblem<dim>::step_balance(const double time_old, const double time_new)
  {
    // Heat balance of the step (trapezoidal in time).
    const double dt    = time_new - time_old;
    const auto   q_old = boundary_flows(time_old, old_temperature_ghosted);
    const auto   q_new = boundary_flows(time_new, temperature_ghosted);
    step_heat_in.clear();
    double boundary_sum = 0;
    for (const auto &[id, q] : q_new)
      boundary_sum += (step_heat_in[id] = 0.5 * dt * (q + q_old.at(id)));
    step_source = 0.5 * dt * (source_power(time_old) + source_power(time_new));
    step_dirichlet_heat_in = heat_content(temperature_ghosted) -
                             heat_content(old_temperature_ghosted) - step_source - boundary_sum;
  }

  template <int dim>
  void ThermalProblem<dim>::begin_step(const double time_old, const double time_new)
  {
    step_length       = time_new - time_old;
    linear_iterations = 0;
    if (!operators_current || mass_diagonal.size() == 0)
      {
        assemble_mass();
        operators_current = true;
      }
  }

  template <int dim>
  void ThermalProblem<dim>::implicit_residual(const double t, const Vector &T, Vector &f)
  {
    // The mechanics' sources change with every iterate: never the cached ones.
    sources_current = false;
    f.reinit(locally_owned_dofs, mpi_communicator);
    assemble(t, T, &f, nullptr);
  }

  template <int dim>
  const TrilinosWrappers::SparseMatrix &ThermalProblem<dim>::implicit_tangent(const double t,
                                                                             const Vector &T)
  {
    assemble(t, T, nullptr, &tangent_matrix);
    tangent_current = true;
    return tangent_matrix;
  }

  template <int dim>
  void ThermalProblem<dim>::mass_vmult(Vector &Mv, const Vector &v) const
  {
    if (parameters.lumped_mass)
      {
        Mv = v;
        Mv.scale(lumped_mass);
      }
    else
      mass_matrix.vmult(Mv, v);
  }

  template <int dim>
  void ThermalProblem<dim>::set_temperature(const Vector &T_owned)
  {
    Vector y(T_owned);
    hanging.distribute(y);
    solution            = y;
    temperature_ghosted = solution;
  }

  template <int dim>
  void ThermalProblem<dim>::accept_temperature(const Vector &T_owned, const double time_old,
                                               const double time_new)
  {
    set_temperature(T_owned);
    step_balance(time_old, time_new);
  }

  template <int dim>
  void ThermalProblem<dim>::commit()
  {
    old_solution            = solution;
    old_temperature_ghosted = temperature_ghosted;
    for (const auto &[id, q] : step_heat_in)
      total_heat_in[id] += q;
    if (has_dirichlet)
      total_heat_in[numbers::invalid_boundary_id] += step_dirichlet_heat_in;
    total_source += step_source;
  }

  template <int dim>
  void ThermalProblem<dim>::revert()
  {
    solution            = old_solution;
    temperature_ghosted = old_temperature_ghosted;
  }

  template <int dim>
  void ThermalProblem<dim>::attach_output(DataOut<dim> &data_out) const
  {
    data_out.add_data_vector(dof_handler, temperature_ghosted, "temperature");
  }

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
    operators_current       = false;
    tangent_current         = false;
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

  ANVIL_INSTANTIATE_CLASS(ThermalBoundaryConditions)
  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
