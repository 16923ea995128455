#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/material/kinematics.h>
#include <anvil/contact/contact_problem.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <chrono>
#include <limits>
#include <sstream>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void MechanicalProblem<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanics");
    prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2),
                      "Degree of the displacement elements: 1 (Q1) or 2 (Q2).");
    prm.declare_entry("Element", "F-bar", Patterns::Selection("F-bar|standard"),
                      "F-bar: the dilatation of each Q1 cell is its centre's (de Souza Neto et al. "
                      "1996), so isochoric plastic flow does not lock (seed sec. 3.1: constant "
                      "pressure elements); standard: plain displacement elements (Q1 locks in "
                      "plastic flow; Q2 with Polynomial degree = 2).");
    prm.declare_entry("Two-dimensional model", "plane strain",
                      Patterns::Selection("plane strain|axisymmetric"),
                      "For Dimension = 2: plane strain, or axisymmetric about the y axis with x the "
                      "radius (x >= 0; hoop strain u_r/r; forces are per full ring, 2 pi r).");
    prm.declare_entry("Temperature", "293", Patterns::Double(0),
                      "Uniform temperature in K of a scene without a temperature field: the "
                      "material laws are evaluated at it.");
    prm.declare_entry("Gravity", "", Patterns::Anything(),
                      "Body force per unit mass as a vector 'gx, gy[, gz]' in mm/s^2 (e.g. 0, -9810); "
                      "empty: none.");
    prm.declare_entry("Maximum plastic strain increment", "0", Patterns::Double(0),
                      "Cut the step back if any point's equivalent plastic strain grows by more than "
                      "this in one step (dimensionless; 0: no limit).");
    prm.enter_subsection("Dynamics");
    prm.declare_entry("Type", "quasi-static", Patterns::Selection("quasi-static|implicit"),
                      "quasi-static: no inertia; implicit: generalized-alpha time integration of "
                      "M a + f_int = f_ext (Chung & Hulbert 1993) with force averaging.");
    prm.declare_entry("Spectral radius", "1", Patterns::Double(0, 1),
                      "rho_inf in [0, 1]: 1 conserves energy (trapezoidal rule, the seed's mid-point "
                      "member); smaller values damp the highest frequencies (0.8 is common).");
    prm.declare_entry("Mass", "consistent", Patterns::Selection("consistent|lumped"),
                      "Consistent or row-sum lumped mass matrix.");
    prm.declare_entry("Initial velocity", "", Patterns::Anything(),
                      "'ux = expr, uy = expr[, uz = expr]' in mm/s, expressions in x, y, z (mm); "
                      "empty: at rest. An impact is an initial velocity.");
    prm.leave_subsection();
    prm.enter_subsection("Newton");
    prm.declare_entry("Maximum iterations", "15", Patterns::Integer(1),
                      "Newton iterations per time step before the step is cut back.");
    prm.declare_entry("Residual tolerance", "1e-8", Patterns::Double(0),
                      "Relative residual tolerance: |R| <= tol * max(|f_int|, |f_ext|, |M a|, |R_0|), R_0 the first residual of the step (dimensionless).");
    prm.declare_entry("Absolute residual tolerance", "1e-12", Patterns::Double(0),
                      "Residual norm in N below which a step is converged whatever the scale.");
    prm.declare_entry("Displacement tolerance", "1e-8", Patterns::Double(0),
                      "Relative increment tolerance: the next correction, estimated as the last one "
                      "times the residual's contraction, <= tol * |Δu of the step| (dimensionless).");
    prm.declare_entry("Extrapolate", "true", Patterns::Bool(),
                      "Start each step from the last step's increment scaled to the new step "
                      "(linear extrapolation in time) instead of the committed configuration.");
    prm.declare_entry("Check tangent", "false", Patterns::Bool(),
                      "Compare the assembled tangent with central finite differences of the "
                      "residual at every Newton iteration and print the relative error (slow; "
                      "for debugging new material laws).");
    prm.declare_entry("Absolute displacement tolerance", "0", Patterns::Double(0),
                      "Correction norm in mm below which the increment test passes whatever the "
                      "step (0: only the relative test and the round-off floor).");
    prm.declare_entry("Line search", "true", Patterns::Bool(),
                      "Backtrack (halve the Newton update, up to 5 times) while the residual grows.");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type", "automatic", Patterns::Selection("automatic|direct|iterative"),
                      "direct: sparse LU (Amesos KLU); iterative: GMRES with algebraic multigrid "
                      "(Trilinos ML); automatic: direct below 'Direct solver limit' DoFs.");
    prm.declare_entry("Tolerance", "1e-10", Patterns::Double(0),
                      "Relative tolerance of the iterative solver (dimensionless).");
    prm.declare_entry("Maximum iterations", "1000", Patterns::Integer(1),
                      "Iterations of the iterative solver before the step is cut back.");
    prm.declare_entry("Direct solver limit", "200000", Patterns::Integer(0),
                      "Number of DoFs up to which 'automatic' chooses the direct solver.");
    prm.leave_subsection();
    prm.leave_subsection();
  }

  template <int dim>
  void MechanicalProblem<dim>::Parameters::parse_parameters(ParameterHandler &prm, const Scene &scene)
  {
    prm.enter_subsection("Mechanics");
    polynomial_degree = prm.get_integer("Polynomial degree");
    f_bar             = prm.get("Element") == "F-bar";
    axisymmetric      = dim == 2 && prm.get("Two-dimensional model") == "axisymmetric";
    temperature       = prm.get_double("Temperature");
    gravity           = prm.get("Gravity");
    maximum_plastic_increment = prm.get_double("Maximum plastic strain increment");
    prm.enter_subsection("Dynamics");
    dynamic          = prm.get("Type") == "implicit";
    spectral_radius  = prm.get_double("Spectral radius");
    lumped_mass      = prm.get("Mass") == "lumped";
    initial_velocity = prm.get("Initial velocity");
    prm.leave_subsection();
    for (const auto &assignment : split_outside_parentheses(initial_velocity, ','))
      {
        if (assignment.empty())
          continue;
        const std::string path = "Mechanics/Dynamics/Initial velocity";
        const auto        eq   = assignment.find('=');
        const std::string c    = eq == std::string::npos ? "" : trim(assignment.substr(0, eq));
        bool              ok   = false;
        for (unsigned int d = 0; d < dim; ++d)
          ok = ok || c == std::string("u") + "xyz"[d];
        if (!ok)
          scene.fail(path, "'" + assignment + "' should be " +
                             (dim == 2 ? "ux = expr or uy = expr" : "ux, uy or uz = expr") + " (mm/s)");
        parse_expression<dim>(trim(assignment.substr(eq + 1)), scene, path);
      }
    // Check the vectors now (one-line errors before any work).
    if (!gravity.empty())
      {
        const auto parts = split_outside_parentheses(gravity, ',');
        bool       ok    = parts.size() == dim;
        for (const auto &x : parts)
          try
            {
              std::size_t used = 0;
              std::stod(x, &used);
              ok = ok && used == x.size();
            }
          catch (...)
            {
              ok = false;
            }
        if (!ok)
          scene.fail("Mechanics/Gravity", "= '" + gravity + "': expected " + std::to_string(dim) +
                                            " numbers 'gx, gy" + (dim == 3 ? ", gz'" : "'") + " in mm/s^2");
      }
    prm.enter_subsection("Newton");
    max_iterations              = prm.get_integer("Maximum iterations");
    residual_tolerance          = prm.get_double("Residual tolerance");
    absolute_residual_tolerance = prm.get_double("Absolute residual tolerance");
    displacement_tolerance      = prm.get_double("Displacement tolerance");
    absolute_displacement_tolerance = prm.get_double("Absolute displacement tolerance");
    line_search                 = prm.get_bool("Line search");
    check_tangent               = prm.get_bool("Check tangent");
    extrapolate                 = prm.get_bool("Extrapolate");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    linear_solver         = prm.get("Type");
    linear_tolerance      = prm.get_double("Tolerance");
    linear_max_iterations = prm.get_integer("Maximum iterations");
    direct_solver_limit   = prm.get_integer("Direct solver limit");
    prm.leave_subsection();
    prm.leave_subsection();
    if (f_bar && polynomial_degree != 1)
      scene.fail("Mechanics/Element", "is F-bar, which is a Q1 element: use Element = standard "
                                      "with Polynomial degree = 2");
    if (dim == 3 && prm.get("Dimension") == "3")
      axisymmetric = false;
  }

  template <int dim>
  MechanicalProblem<dim>::MechanicalProblem(
    const parallel::distributed::Triangulation<dim>                        &triangulation,
    const Parameters                                                        &parameters,
    const BoundaryConditions<dim>                                           &boundary_conditions,
    const std::map<types::material_id, std::shared_ptr<const MaterialModel>> &materials,
    TimerOutput                                                             &timer)
    : mpi_communicator(triangulation.get_communicator())
    , triangulation(triangulation)
    , parameters(parameters)
    , boundary_conditions(boundary_conditions)
    , materials(materials)
    , timer(timer)
    , axisymmetric(parameters.axisymmetric)
    , f_bar(parameters.f_bar)
    , fe(FE_Q<dim>(parameters.polynomial_degree), dim)
    , mapping(1)
    , dof_handler(triangulation)
    , quadrature(parameters.polynomial_degree + 1)
    , face_quadrature(parameters.polynomial_degree + 1)
  {}

  template <int dim>
  void MechanicalProblem<dim>::setup()
  {
    TimerOutput::Scope t(timer, "Mechanics: setup");
    dof_handler.distribute_dofs(fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

    // The constraints hold lines for the relevant dofs and, with contact, for
    // every contact-surface dof too: a contact element may touch a master node
    // far away, whose constraint only its owner knows (ContactProblem gathers
    // which; add_remote_constraints() makes them lines here, so the element's
    // entries are condensed like any other).
    constraint_lines = locally_relevant_dofs;
    if (contact)
      {
        contact->setup(dof_handler, axisymmetric);
        constraint_lines.add_indices(contact->surface_dofs());
        constraint_lines.compress();
      }
    constraints.clear();
    constraints.reinit(constraint_lines);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    boundary_conditions.make_homogeneous_constraints(dof_handler, constraints);
    make_axis_constraints(constraints);
    if (contact)
      {
        contact->set_constrained([this](const types::global_dof_index i) {
          return locally_owned_dofs.is_element(i) && constraints.is_constrained(i);
        });
        add_remote_constraints(constraints);
      }
    constraints.close();

    if (contact)
      {
        TrilinosWrappers::MPI::Vector zero(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
        contact->begin_step(0, 0, zero);
      }
    setup_matrix();

    previous_time_step = 0;
    previous_increment.reinit(locally_owned_dofs, mpi_communicator);
    {
      // The diagonal of the mesh's bounding box: a length scale for the
      // round-off floor of the Newton test (GridTools::diameter compares all
      // pairs of vertices, O(n²)).
      Point<dim> lo, hi;
      for (unsigned int d = 0; d < dim; ++d)
        lo[d] = std::numeric_limits<double>::max(), hi[d] = -std::numeric_limits<double>::max();
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < dim; ++d)
              {
                lo[d] = std::min(lo[d], cell->vertex(v)[d]);
                hi[d] = std::max(hi[d], cell->vertex(v)[d]);
              }
      double diagonal = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double l = Utilities::MPI::max(hi[d], mpi_communicator) +
                           Utilities::MPI::max(-lo[d], mpi_communicator);
          diagonal += l * l;
        }
      mesh_diameter = std::sqrt(diagonal);
    }
    for (auto *v : {&system_rhs, &internal_force, &internal_force_old, &external_force,
                    &external_force_old, &reaction_force, &reaction_force_old, &owned_solution,
                    &owned_old_solution, &velocity_old, &acceleration_old, &static_residual_old,
                    &inertia_force})
      v->reinit(locally_owned_dofs, mpi_communicator);
    for (auto *v : {&solution, &old_solution, &velocity_ghosted, &velocity_old_ghosted,
                    &acceleration_old_ghosted})
      v->reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);

    gravity = Tensor<1, dim>();
    if (!parameters.gravity.empty())
      {
        const auto parts = split_outside_parentheses(parameters.gravity, ',');
        for (unsigned int d = 0; d < dim; ++d)
          gravity[d] = std::stod(parts[d]);
      }

    setup_quadrature_point_data();
    if (parameters.dynamic)
      setup_dynamics();
  }

  template <int dim>
  void MechanicalProblem<dim>::add_remote_constraints(AffineConstraints<double> &c) const
  {
    // Contact surface dofs constrained by their (far away) owner: homogeneous
    // here (the owner applies any prescribed value).
    if (contact)
      for (const auto i : contact->constrained_dofs())
        if (!locally_relevant_dofs.is_element(i) && !c.is_constrained(i))
          c.add_line(i);
  }

  template <int dim>
  void MechanicalProblem<dim>::setup_matrix()
  {
    // Contact couples dofs of different cells (a slave node with the nodes of
    // the master face below it), possibly owned by other processes: their
    // rows enter the pattern here and go to their owners.
    std::vector<std::vector<types::global_dof_index>> groups;
    IndexSet rows = locally_relevant_dofs;
    if (contact)
      {
        groups = contact->couplings();
        std::vector<types::global_dof_index> extra;
        for (const auto &g : groups)
          extra.insert(extra.end(), g.begin(), g.end());
        std::sort(extra.begin(), extra.end());
        extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
        rows.add_indices(extra.begin(), extra.end());
        rows.compress();
      }
    DynamicSparsityPattern dsp(rows);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    for (const auto &g : groups)
      constraints.add_entries_local_to_global(g, dsp, false);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator, rows);
    system_matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
  }

  template <int dim>
  void MechanicalProblem<dim>::setup_quadrature_point_data()
  {
    const unsigned int n_q = quadrature.size();
    points.clear();
    points.resize(triangulation.n_active_cells() * n_q);
    heat_sources.assign(triangulation.n_active_cells() * n_q, 0.);
    thermoelastic_sources = heat_sources;
    material_temperature.assign(heat_sources.size(), parameters.temperature);
    material_temperature_old = material_temperature;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto m = materials.find(cell->material_id());
          if (m == materials.end())
            throw InputError("internal: no material for body id " +
                             std::to_string(cell->material_id()));
          for (unsigned int q = 0; q < n_q; ++q)
            points[cell->active_cell_index() * n_q + q] = m->second->create_point();
        }
  }

  template <int dim>
  std::string MechanicalProblem<dim>::material_failure_message() const
  {
    // The first rank that failed tells (all ranks return the same text).
    const unsigned int rank  = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int first = Utilities::MPI::min(material_failure.empty() ?
                                                     Utilities::MPI::n_mpi_processes(mpi_communicator) :
                                                     rank,
                                                   mpi_communicator);
    if (first == Utilities::MPI::n_mpi_processes(mpi_communicator))
      return "an element inverted (J <= 0)";
    std::vector<char> text(material_failure.begin(), material_failure.end());
    text = Utilities::MPI::broadcast(mpi_communicator, text, first);
    return std::string(text.begin(), text.end());
  }

  template <int dim>
  double MechanicalProblem<dim>::residual_norm() const
  {
    return system_rhs.l2_norm();
  }

  template <int dim>
  unsigned int MechanicalProblem<dim>::solve_linear_system(TrilinosWrappers::MPI::Vector &du)
  {
    TimerOutput::Scope t(timer, "Mechanics: linear solve");
    const bool direct = parameters.linear_solver == "direct" ||
                        (parameters.linear_solver == "automatic" &&
                         dof_handler.n_dofs() <= parameters.direct_solver_limit);
    if (direct)
      {
        SolverControl                  control(1, 0);
        TrilinosWrappers::SolverDirect solver(control,
                                              TrilinosWrappers::SolverDirect::AdditionalData(
                                                false, "Amesos_Klu"));
        solver.solve(system_matrix, du, system_rhs);
        return 1;
      }
    TrilinosWrappers::PreconditionAMG                 amg;
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    std::vector<std::vector<bool>>                    constant_modes;
    DoFTools::extract_constant_modes(dof_handler, ComponentMask(dim, true), constant_modes);
    data.constant_modes        = constant_modes;
    data.elliptic              = true;
    data.higher_order_elements = parameters.polynomial_degree > 1;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    amg.initialize(system_matrix, data);
    SolverControl control(parameters.linear_max_iterations,
                          parameters.linear_tolerance * system_rhs.l2_norm());
    // Restart 30: AMG converges in 10–40 iterations here, and each Krylov
    // vector costs 8 bytes per DoF (100 would be 800 B/DoF).
    SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
      control, SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(30));
    gmres.solve(system_matrix, du, system_rhs, amg);
    return control.last_step();
  }

  template <int dim>
  void MechanicalProblem<dim>::make_axis_constraints(AffineConstraints<double> &c) const
  {
    // Axisymmetric: nodes on the axis (x = 0) do not move radially.
    if (!axisymmetric)
      return;
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dofs);
          for (const unsigned int v : cell->vertex_indices())
            if (std::abs(cell->vertex(v)[0]) < 1e-12 * cell->diameter())
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (fe.system_to_component_index(i).first == 0 && fe.has_support_points() &&
                    fe.get_unit_support_points()[i].distance(
                      GeometryInfo<dim>::unit_cell_vertex(v)) < 1e-12 &&
                    !c.is_constrained(dofs[i]) && locally_relevant_dofs.is_element(dofs[i]))
                  c.add_line(dofs[i]);
        }
  }

  template <int dim>
  double MechanicalProblem<dim>::tangent_error()
  {
    // Random direction on the free dofs; K is assembled at the current u.
    TrilinosWrappers::MPI::Vector du(locally_owned_dofs, mpi_communicator), Kdu(du), r_plus(du);
    for (const auto i : locally_owned_dofs)
      du(i) = std::sin(1.0 + 7.3 * i);
    du.compress(VectorOperation::insert);
    constraints.set_zero(du);
    assemble(true, current_time);
    system_matrix.vmult(Kdu, du);
    constraints.set_zero(Kdu);
    const TrilinosWrappers::MPI::Vector u0 = owned_solution;
    const double h = 1e-7 * std::max(1.0, u0.l2_norm()) / std::max(du.l2_norm(), 1e-300);
    owned_solution.add(h, du);
    solution = owned_solution;
    assemble(false, current_time);
    r_plus = system_rhs; // −R(u + h du)
    owned_solution = u0;
    owned_solution.add(-h, du);
    solution = owned_solution;
    assemble(false, current_time);
    r_plus -= system_rhs; // −R(u+) + R(u−)
    r_plus /= -2 * h;     // (R(u+) − R(u−)) / 2h ≈ K du
    owned_solution = u0;
    solution       = owned_solution;
    r_plus -= Kdu;
    return r_plus.l2_norm() / std::max(Kdu.l2_norm(), 1e-300);
  }

  template <int dim>
  typename MechanicalProblem<dim>::StepResult
  MechanicalProblem<dim>::solve_step(const double time_old, const double time_new,
                                     const bool from_last_solution)
  {
    StepResult result;
    current_time_step = time_new - time_old;
    current_time      = time_new;
    if (contact)
      {
        contact->begin_step(time_old, time_new, old_solution);
        if (contact->couplings_changed())
          setup_matrix();
      }

    // Predictor: the first Newton iteration starts from the committed
    // configuration and imposes the jump of the prescribed displacements as
    // inhomogeneous constraints, so the whole body follows the boundary
    // (moving only the boundary nodes would invert the cells next to it when
    // the jump exceeds their size).
    //
    // The free dofs start from the last step's increment scaled to this step
    // (linear extrapolation in time), which puts yielding points on their
    // plastic branch from the first iteration; if that inverts an element,
    // from the committed configuration.
    // Again on the same step (iterated staggered): from the last solution,
    // which already satisfies the step's boundary values.
    if (!from_last_solution)
      owned_solution = owned_old_solution;
    if (!from_last_solution && parameters.extrapolate && previous_time_step > 0)
      {
        owned_solution.add(current_time_step / previous_time_step, previous_increment);
        solution = owned_solution;
        if (!assemble(false, time_new))
          owned_solution = owned_old_solution;
      }
    solution = owned_solution;
    predictor_constraints.clear();
    predictor_constraints.reinit(constraint_lines);
    DoFTools::make_hanging_node_constraints(dof_handler, predictor_constraints);
    make_axis_constraints(predictor_constraints);
    {
      std::map<types::global_dof_index, double> values;
      boundary_conditions.interpolate(dof_handler, time_new, values);
      for (const auto &[dof, value] : values)
        if (locally_relevant_dofs.is_element(dof) && !predictor_constraints.is_constrained(dof))
          {
            predictor_constraints.add_line(dof);
            predictor_constraints.set_inhomogeneity(dof, value - solution(dof));
          }
      std::map<types::global_dof_index, double> increments;
      boundary_conditions.interpolate_velocity_increment(dof_handler, time_old, time_new, increments);
      for (const auto &[dof, increment] : increments)
        if (locally_relevant_dofs.is_element(dof) && !predictor_constraints.is_constrained(dof))
          {
            predictor_constraints.add_line(dof);
            predictor_constraints.set_inhomogeneity(dof, increment + old_solution(dof) - solution(dof));
          }
    }
    add_remote_constraints(predictor_constraints);
    predictor_constraints.close();
    active_constraints = &predictor_constraints;
    double largest_jump = 0;
    for (const auto &line : predictor_constraints.get_lines())
      largest_jump = std::max(largest_jump, std::abs(line.inhomogeneity));
    const bool has_jump = Utilities::MPI::max(largest_jump, mpi_communicator) > 0;

    TrilinosWrappers::MPI::Vector du(locally_owned_dofs, mpi_communicator);
    TrilinosWrappers::MPI::Vector u_start(locally_owned_dofs, mpi_communicator);
    double last_increment = -1;

    for (unsigned int it = 0;; ++it)
      {
        if (!assemble(true, time_new))
          {
            result.failure = material_failure_message();
            return result;
          }
        const double r = residual_norm();
        if (!std::isfinite(r))
          {
            result.failure = "the residual is not a number";
            return result;
          }
        result.residuals.push_back(r);
        if (parameters.check_tangent)
          {
            const double e = tangent_error();
            if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
              std::cout << "    tangent check: |K du - FD| / |K du| = " << e << std::endl;
            assemble(true, time_new); // restore K and R at u
          }

        // Force scale: the forces of the step, and the first residual of the
        // step (in dynamics the inertia of the predictor dominates it, and
        // round-off of M ã is relative to it).
        const double scale = std::max({internal_force.l2_norm(), external_force.l2_norm(),
                                       inertia_force.l2_norm(), result.residuals.front()});
        TrilinosWrappers::MPI::Vector step_u(owned_solution);
        step_u -= owned_old_solution;
        const double du_scale = step_u.l2_norm();
        const bool residual_ok =
          r <= parameters.absolute_residual_tolerance || r <= parameters.residual_tolerance * scale;
        // The correction that would come next is about the last one times the
        // residual's contraction (quadratic convergence makes this sharp):
        // test that instead of paying one more solve to see it.
        const double r_previous = result.residuals.size() > 1 ?
                                    result.residuals[result.residuals.size() - 2] : r;
        const double predicted_increment =
          last_increment * std::min(1.0, r / std::max(r_previous, 1e-300));
        // Corrections cannot fall below round-off of the displacement itself.
        // (positions x = X + u carry the digits, so the scale is the mesh size).
        const double increment_floor =
          100 * std::numeric_limits<double>::epsilon() *
          (owned_solution.l2_norm() + std::sqrt(double(dof_handler.n_dofs())) * mesh_diameter);
        const bool   increment_ok =
          (last_increment >= 0 &&
           predicted_increment <= std::max({parameters.displacement_tolerance * du_scale,
                                            parameters.absolute_displacement_tolerance,
                                            increment_floor})) ||
          r <= parameters.absolute_residual_tolerance;
        // Corrections a thousand times below the increment tolerance mean the
        // residual sits on its round-off floor: accept.
        const bool stagnated =
          last_increment >= 0 &&
          last_increment <= std::max(1e-3 * parameters.displacement_tolerance * du_scale,
                                     increment_floor) &&
          r <= 1e3 * parameters.residual_tolerance * scale;
        if ((residual_ok && (increment_ok || it == 0) && !(it == 0 && has_jump)) || stagnated)
          {
            result.converged  = true;
            result.iterations = it;
            return result;
          }
        if (it >= parameters.max_iterations)
          {
            result.iterations = it;
            result.failure    = "Newton did not converge in " + std::to_string(it) +
                             " iterations (|R| = " + Utilities::to_string(r, 3) + " N)";
            return result;
          }

        du = 0;
        try
          {
            result.linear_iterations += solve_linear_system(du);
          }
        catch (const std::exception &e)
          {
            result.failure = "the linear solver failed";
            return result;
          }
        active_constraints->distribute(du);
        active_constraints = &constraints;
        last_increment     = du.l2_norm();
        result.increments.push_back(last_increment);

        // Line search on the energy norm s(α) = δu · R(u + α δu) (Crisfield):
        // the residual norm itself grows in the first iterations of large
        // rotations although the step is good, so it is a poor merit function.
        // A full step is kept unless |s(1)| > 0.8 |s(0)| or an element inverts;
        // then α follows the secant root of s, within [0.1, 1].
        u_start         = owned_solution;
        double       alpha = 1;
        const double s0    = -(du * system_rhs);
        for (unsigned int ls = 0;; ++ls)
          {
            owned_solution = u_start;
            owned_solution.add(alpha, du);
            solution = owned_solution;
            // The first update carries the boundary jump: take it whole.
            // Near convergence (and on the round-off floor) s(α) is noise.
            if (!parameters.line_search || ls == 5 || (it == 0 && has_jump) || residual_ok)
              break;
            const bool ok = assemble(false, time_new);
            if (!ok)
              {
                alpha *= 0.5;
                continue;
              }
            const double s1 = -(du * system_rhs);
            if (!std::isfinite(s1))
              {
                alpha *= 0.5;
                continue;
              }
            if (std::abs(s1) <= 0.8 * std::abs(s0))
              break;
            // Secant root of s between (0, s0) and (α, s1). If s has not changed
            // sign and grows in magnitude the root lies beyond α: keep α.
            const double next = alpha * s0 / (s0 - s1);
            if (!(next > 0) || next >= alpha)
              break;
            alpha = std::max(0.1 * alpha, next);
          }
        result.line_search_steps.push_back(alpha);
      }
  }

  template <int dim>
  void MechanicalProblem<dim>::revert_step()
  {
    for (auto &p : points)
      if (p)
        p->revert();
    owned_solution = owned_old_solution;
    solution       = owned_solution;
  }

  template <int dim>
  Tensor<1, dim> MechanicalProblem<dim>::reaction(const types::boundary_id boundary) const
  {
    Tensor<1, dim> force;
    const IndexSet dofs = DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), {boundary});
    // Component of each boundary dof from the dof's support on a cell.
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    std::vector<bool> seen(locally_owned_dofs.n_elements(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        {
          cell->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < cell_dofs.size(); ++i)
            {
              const auto g = cell_dofs[i];
              if (!locally_owned_dofs.is_element(g) || !dofs.is_element(g))
                continue;
              const auto k = locally_owned_dofs.index_within_set(g);
              if (seen[k])
                continue;
              seen[k] = true;
              force[fe.system_to_component_index(i).first] +=
                internal_force(g) + inertia_force(g) - external_force(g);
            }
        }
    return Utilities::MPI::sum(force, mpi_communicator);
  }

  template <int dim>
  typename MechanicalProblem<dim>::CellFields MechanicalProblem<dim>::cell_fields() const
  {
    CellFields f;
    const char *axes = "xyz";
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        f.names.push_back(std::string("stress_") + axes[i] + axes[j]);
    f.names.insert(f.names.end(), {"von_mises", "pressure", "J", "equivalent_plastic_strain", "body"});
    f.values.assign(f.names.size(), Vector<double>(triangulation.n_active_cells()));

    FEValues<dim> fe_values(mapping, fe, quadrature,
                            update_gradients | update_values | update_quadrature_points);
    const unsigned int n_q = quadrature.size();
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<Tensor<1, dim>> u_values(n_q);
    const FEValuesExtractors::Vector displacements(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements].get_function_gradients(solution, grad_u);
          fe_values[displacements].get_function_values(solution, u_values);
          SymmetricTensor<2, 3> s;
          double J = 0, eqps = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const auto &p = *points[cell->active_cell_index() * n_q + q];
              s += p.stress() / n_q;
              eqps += p.equivalent_plastic_strain() / n_q;
              const double R  = axisymmetric ? fe_values.quadrature_point(q)[0] : 1.;
              const double ur = axisymmetric ? u_values[q][0] : 0.;
              J += determinant(deformation_gradient(grad_u[q], ur, R)) / n_q;
            }
          const unsigned int c = cell->active_cell_index();
          unsigned int       k = 0;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              f.values[k++][c] = s[i][j];
          const auto dev   = deviator(s);
          f.values[k++][c] = std::sqrt(1.5 * (dev * dev));
          f.values[k++][c] = -trace(s) / 3.;
          f.values[k++][c] = J;
          f.values[k++][c] = eqps;
          f.values[k++][c] = cell->material_id();
        }
    return f;
  }

  template <int dim>
  bool MechanicalProblem<dim>::probe(const Point<dim>      &point,
                                     Tensor<1, dim>        &u,
                                     SymmetricTensor<2, 3> &stress,
                                     double                &plastic_strain) const
  {
    u              = Tensor<1, dim>();
    stress         = SymmetricTensor<2, 3>();
    plastic_strain = 0;
    double found = 0;
    try
      {
        const auto cell_and_point =
          GridTools::find_active_cell_around_point(mapping, dof_handler, point);
        const auto &cell = cell_and_point.first;
        // On a process that does not hold the point the search returns an
        // invalid iterator (or an artificial cell).
        if (cell.state() == IteratorState::valid && cell->is_locally_owned())
          {
            found = 1;
            const Quadrature<dim> q(GeometryInfo<dim>::project_to_unit_cell(cell_and_point.second));
            FEValues<dim> fe_values(mapping, fe, q, update_values);
            fe_values.reinit(cell);
            std::vector<Tensor<1, dim>> values(1);
            fe_values[FEValuesExtractors::Vector(0)].get_function_values(solution, values);
            u = values[0];
            const unsigned int n_q = quadrature.size();
            for (unsigned int k = 0; k < n_q; ++k)
              {
                stress += points[cell->active_cell_index() * n_q + k]->stress() / n_q;
                plastic_strain +=
                  points[cell->active_cell_index() * n_q + k]->equivalent_plastic_strain() / n_q;
              }
          }
      }
    catch (...)
      {
        // not in this rank's part of the mesh
      }
    const double n = Utilities::MPI::sum(found, mpi_communicator);
    u              = Utilities::MPI::sum(u, mpi_communicator);
    stress         = Utilities::MPI::sum(stress, mpi_communicator);
    plastic_strain = Utilities::MPI::sum(plastic_strain, mpi_communicator);
    if (n == 0)
      return false;
    u /= n;
    stress /= n;
    plastic_strain /= n;
    return true;
  }

  template <int dim>
  std::size_t MechanicalProblem<dim>::memory_consumption() const
  {
    return dof_handler.memory_consumption() + system_matrix.memory_consumption() +
           8 * solution.memory_consumption() + constraints.memory_consumption() +
           points.size() * (sizeof(void *) + 2 * sizeof(SymmetricTensor<2, 3>) + 16);
  }

  template class MechanicalProblem<2>;
  template class MechanicalProblem<3>;
} // namespace anvil
