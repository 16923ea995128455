// ThermalProblem: setup, the ARKode step and its heat balance (parameters in
// thermal_parameters.cc, the monolithic scheme's hooks in implicit_step.cc,
// the checkpoint in thermal_checkpoint.cc).
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1_eulerian.h>
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
#include <anvil/core/klu_factorization.h>

#include <Epetra_BlockMap.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// @p to = @p from in the rows @p rows (DynamicSparsityPattern's copy and
    /// assignment only take empty patterns).
    void copy_pattern(const DynamicSparsityPattern &from, DynamicSparsityPattern &to, const IndexSet &rows)
    {
      to.reinit(from.n_rows(), from.n_cols(), rows);
      // Row by row (sorted): one insertion each, not one search per entry.
      std::vector<types::global_dof_index> columns;
      for (const auto r : rows)
        {
          columns.resize(from.row_length(r));
          for (unsigned int k = 0; k < columns.size(); ++k)
            columns[k] = from.column_number(r, k);
          to.add_entries(r, columns.begin(), columns.end(), true);
        }
    }
  } // namespace

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
    bool rhs_independent_of_time() const override
    {
      // What linear_residual() evaluates at t: fluxes and T∞(t), ġ_D(t), a
      // tool's temperature; the full assembly (an expression source) too.
      return p.linear && !p.convection_varies && !p.source_function &&
             !(p.has_dirichlet && p.has_hanging) && !p.loads_vary && !p.dirichlet_varies &&
             (!p.exchange.add_rhs || !p.exchange.rhs_depends_on_time);
    }
    int setup_jacobian(const double t, const Vector &y) override
    {
      // Linear problems on a frozen geometry: the Jacobian −K is assembled
      // once per configuration (unless a convection coefficient h(t) varies).
      if (p.linear && p.tangent_current && !p.convection_varies)
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
    bool can_solve_exactly() const override
    {
      return p.use_direct && (!p.exchange.add_jacobian || p.exchange.add_matrix);
    }
    int setup_exact_newton_matrix(const double gamma) override
    {
      p.setup_newton(gamma, /*exact*/ true);
      return 0;
    }
    int solve_newton_matrix(Vector &x, const Vector &b) override { return p.solve_newton(x, b, 0); }
    bool newton_matrix_is_exact(const double gamma) const override
    {
      // KLU of M + γA with ARKode's γ and every coupling of J in it (the
      // exchange's too: setup_newton adds them).
      return can_solve_exactly() && p.current_gamma == gamma;
    }
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
  ThermalProblem<dim>::ThermalProblem(const parallel::DistributedTriangulationBase<dim> &triangulation,
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
    , newton_direct(std::make_unique<KluFactorization>())
    , mass_direct(std::make_unique<KluFactorization>())
  {
    initial_function = parse_expression<dim>(parameters.initial_temperature, Scene(), "Heat/Initial temperature");
    if (!parameters.source.empty())
      source_function = parse_expression<dim>(parameters.source, Scene(), "Heat/Source");
    linear = true;
    for (const auto &[id, m] : materials)
      linear = linear && m.conductivity_slope == 0;
    for (const auto &[id, b] : boundary_conditions.boundaries)
      {
        linear            = linear && !b.emissivity;
        has_convection    = has_convection || b.h;
        convection_varies = convection_varies || (b.h && b.h_varies);
        dirichlet_varies  = dirichlet_varies || (b.temperature && b.temperature_varies);
        loads_vary        = loads_vary || (b.flux && b.flux_varies) ||
                     (b.h && (b.h_varies || b.T_convection_varies));
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
    has_hanging   = Utilities::MPI::max(hanging.n_constraints(), mpi_communicator) > 0;

    {
      const DynamicSparsityPattern dsp = sparsity();
      copy_pattern(dsp, cell_pattern, locally_relevant_dofs);
    }
    for (auto *m : {&mass_matrix, &tangent_matrix, &newton_matrix})
      m->reinit(locally_owned_dofs, locally_owned_dofs, cell_pattern, mpi_communicator);
    tangent_positions_values = nullptr; // its entries moved (thermal_assembly.cc)
    exchange_pattern_current = false;
    covered_groups.clear();
    for (auto *v : {&lumped_mass, &mass_diagonal, &solution, &old_solution})
      v->reinit(locally_owned_dofs, mpi_communicator);
    for (auto *v : {&temperature_ghosted, &old_temperature_ghosted, &scratch_ghosted})
      v->reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    reference_table.clear(); // a new mesh or numbering
    current_table.clear();
    newton_direct->clear(); // a new pattern
    mass_direct->clear();
    use_direct = parameters.linear_solver == "direct" ||
                 (parameters.linear_solver == "automatic" &&
                  dof_handler.n_dofs() <= parameters.direct_solver_limit);
    operators_current = false;
    tangent_current   = false;
    couplings_current = false;
    loads_current     = false;

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
    solution_heat_content = old_heat_content = std::numeric_limits<double>::quiet_NaN();
    total_heat_in.clear();
    total_source = 0;
  }

  template <int dim>
  DynamicSparsityPattern ThermalProblem<dim>::sparsity() const
  {
    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, true);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                               locally_relevant_dofs);
    return dsp;
  }

  template <int dim>
  void ThermalProblem<dim>::exchange_sparsity(const std::vector<std::vector<types::global_dof_index>> &groups,
                                              DynamicSparsityPattern &dsp) const
  {
    // The groups are known on every process: each adds its own rows, the
    // columns wherever they live (another process's: ghost columns). A group
    // is a slave and the nodes of the master face it touches (eq. 30); the
    // slave is the one that shares no cell with the others. The group couples
    // all-to-all; beside it, the slave couples with the nodes within `rings`
    // cell layers of the master face (both ways): the faces a slave sliding on
    // reaches in the next steps are then in the pattern already, so a new
    // pattern (and a new KLU analysis) is needed every few faces, not at
    // every face (two_blocks: 17 rebuilds in 79 steps with one layer of the
    // masters' cells all-to-all). Only the slave's row and column grow (not
    // the layers among themselves: no fill-in between interior nodes); in 3D
    // the layers grow as their square, so one. Where a row is not known here
    // the group alone: a rebuild later, not a wrong pattern.
    const unsigned int rings = dim == 2 ? 3 : 1;
    copy_pattern(cell_pattern, dsp, locally_relevant_dofs);
    auto known = [&](const types::global_dof_index i) { return locally_relevant_dofs.is_element(i); };
    auto owned = [&](const types::global_dof_index i) { return locally_owned_dofs.is_element(i); };
    // Per slave the master nodes of all its groups: the layers around their
    // union are the union of the layers around each (one expansion per slave,
    // not per group: the groups only grow, two_blocks ends with 211 of 11 slaves).
    std::map<types::global_dof_index, std::vector<types::global_dof_index>> masters_of;
    std::vector<types::global_dof_index> block, next;
    for (const auto &group : groups)
      {
        block.assign(group.begin(), group.end());
        std::sort(block.begin(), block.end());
        for (const auto i : block)
          if (owned(i))
            dsp.add_entries(i, block.begin(), block.end(), true);
        for (const auto j : group)
          {
            bool slave = known(j);
            for (const auto k : group)
              slave = slave && (k == j || !cell_pattern.exists(j, k));
            if (slave)
              for (const auto k : group)
                if (k != j)
                  masters_of[j].push_back(k);
          }
      }
    for (auto &[j, region] : masters_of)
      {
        std::sort(region.begin(), region.end());
        region.erase(std::unique(region.begin(), region.end()), region.end());
        for (unsigned int r = 0; r < rings; ++r)
          {
            next = region;
            for (const auto k : region)
              if (known(k))
                {
                  // By position (DynamicSparsityPattern's iterators cost ~10× more).
                  const unsigned int n = cell_pattern.row_length(k);
                  for (unsigned int e = 0; e < n; ++e)
                    next.push_back(cell_pattern.column_number(k, e));
                }
            std::sort(next.begin(), next.end());
            next.erase(std::unique(next.begin(), next.end()), next.end());
            region.swap(next);
          }
        if (owned(j))
          dsp.add_entries(j, region.begin(), region.end(), true);
        for (const auto k : region)
          if (owned(k))
            dsp.add(k, j);
      }
  }

  template <int dim>
  bool ThermalProblem<dim>::covers(const std::vector<std::vector<types::global_dof_index>> &groups)
  {
    // One look-up per group; the new ones join the known after the vote.
    bool                                                  covered = true;
    std::vector<const std::vector<types::global_dof_index> *> fresh;
    for (const auto &group : groups)
      {
        const auto known = covered_groups.lower_bound(group);
        if (known != covered_groups.end() && *known == group)
          continue;
        fresh.push_back(&group);
        for (const auto i : group)
          if (locally_owned_dofs.is_element(i))
            for (const auto j : group)
              covered = covered && exchange_pattern.exists(i, j);
      }
    covered = Utilities::MPI::min(covered ? 1 : 0, mpi_communicator) == 1;
    if (covered)
      for (const auto *group : fresh)
        covered_groups.insert(*group);
    return covered;
  }

  template <int dim>
  void ThermalProblem<dim>::set_configuration(const DoFHandler<dim> &mechanics_dofs,
                                              const Vector          &displacement_ghosted)
  {
    current_mapping.reset();
    configuration.reinit(displacement_ghosted);
    configuration = displacement_ghosted;
    // Q1 mechanics: the support points are the moved vertices, read off the
    // vertex dofs (the same numbers MappingQEulerian interpolates with an
    // FEValues per cell; two_blocks' tangent loop: 6.7 → 3.6 M instructions).
    moved_vertices.clear();
    if (mechanics_dofs.get_fe().degree == 1)
      {
        current_mapping = std::make_unique<MappingQ1Eulerian<dim, Vector>>(mechanics_dofs, configuration);
        moved_vertices.resize(triangulation.n_vertices());
        // Each vertex's dofs by their positions in the ghosted vector's
        // local array, found once per mechanics numbering (a global-to-local
        // look-up per value read: 14 of two_blocks' 27 M here).
        const Epetra_BlockMap &map = configuration.trilinos_vector().Map();
        if (!vertex_dofs_map || vertex_dofs_map->DataPtr() != map.DataPtr() || vertex_dofs_of != &mechanics_dofs ||
            vertex_dofs_n != mechanics_dofs.n_dofs())
          {
            vertex_dofs.assign(triangulation.n_vertices(), {});
            for (auto &positions : vertex_dofs)
              positions.fill(-1);
            for (const auto &cell : mechanics_dofs.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int v : cell->vertex_indices())
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      const int local = map.LID(
                        static_cast<TrilinosWrappers::types::int_type>(cell->vertex_dof_index(v, d)));
                      AssertThrow(local >= 0, ExcMessage("a vertex dof is not in the ghosted displacement"));
                      vertex_dofs[cell->vertex_index(v)][d] = local;
                    }
            vertex_dofs_map = std::make_unique<Epetra_BlockMap>(map);
            vertex_dofs_of  = &mechanics_dofs;
            vertex_dofs_n   = mechanics_dofs.n_dofs();
          }
        const double *u        = configuration.trilinos_vector()[0];
        const auto   &vertices = triangulation.get_vertices();
        for (unsigned int v = 0; v < vertex_dofs.size(); ++v)
          if (vertex_dofs[v][0] >= 0)
            {
              Point<dim> x = vertices[v];
              for (unsigned int d = 0; d < dim; ++d)
                x[d] += u[vertex_dofs[v][d]];
              moved_vertices[v] = x;
            }
      }
    else
      current_mapping = std::make_unique<MappingQEulerian<dim, Vector>>(
        mechanics_dofs.get_fe().degree, mechanics_dofs, configuration);
    // Conduction and the face loads live on the current configuration; M and
    // M_fD on the reference one (ρ dv = ρ₀ dV) stay as they are.
    tangent_current = false;
    loads_current   = false;
    current_table.clear();
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
    if (parameters.steady)
      {
        // A sequence of steady states: the one at the step's end, from the last.
        solution              = old_solution;
        temperature_ghosted   = old_temperature_ghosted;
        solution_heat_content = std::numeric_limits<double>::quiet_NaN();
        const auto stats      = solve_steady(time_new);
        if (!stats.converged)
          revert();
        // No heat content balance between two steady states (steady_balance instead).
        step_heat_in.clear();
        step_source = step_dirichlet_heat_in = 0;
        return stats;
      }
    TimerOutput::Scope scope(timer, "Heat: solve");
    Statistics         stats;
    solution_heat_content = std::numeric_limits<double>::quiet_NaN();
    step_length = time_new - time_old;
    if (!operators_current)
      {
        assemble_mass();
        operators_current = true;
      }
    update_exchange_pattern();
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
    settings.jacobian_constant        = !convection_varies;
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
    // The next step starts from ARKode's proposal after this one (or the
    // largest step taken, if larger), not from the last step: the end time
    // cuts that one short by an amount that jumps (from ~0 to a full step)
    // with the last digits of the solution, and a tiny initial step made the
    // next solve take several more steps (one round-off difference, e.g. 1 vs
    // 2 processes, changed every later step). The adapter cuts the next span
    // into equal steps near it (arkode_integrator.cc, first_step).
    last_internal_step = s.next_step > 0 ? s.next_step : s.last_step;
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
    // The mechanics' sources are held over the step: only an expression source depends on t.
    const double source_new = source_power(time_new);
    step_source = 0.5 * dt * ((source_function ? source_power(time_old) : source_new) + source_new);
    // The committed content is the one of the last accepted step's end.
    if (std::isnan(old_heat_content))
      old_heat_content = heat_content(old_temperature_ghosted);
    solution_heat_content  = heat_content(temperature_ghosted);
    step_dirichlet_heat_in = solution_heat_content - old_heat_content - step_source - boundary_sum;
  }

  template <int dim>
  void ThermalProblem<dim>::commit()
  {
    old_solution            = solution;
    old_temperature_ghosted = temperature_ghosted;
    old_heat_content        = solution_heat_content;
    for (const auto &[id, q] : step_heat_in)
      total_heat_in[id] += q;
    if (has_dirichlet)
      total_heat_in[numbers::invalid_boundary_id] += step_dirichlet_heat_in;
    total_source += step_source;
  }

  template <int dim>
  void ThermalProblem<dim>::revert()
  {
    solution              = old_solution;
    temperature_ghosted   = old_temperature_ghosted;
    solution_heat_content = old_heat_content;
  }

  template <int dim>
  void ThermalProblem<dim>::attach_output(DataOut<dim> &data_out) const
  {
    data_out.add_data_vector(dof_handler, temperature_ghosted, "temperature");
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
