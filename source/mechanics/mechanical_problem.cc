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
#include <anvil/mechanics/kinematics.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <chrono>
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
    prm.declare_entry("Temperature", "293", Patterns::Double(0),
                      "Uniform temperature in K of a scene without a temperature field: the "
                      "material laws are evaluated at it.");
    prm.enter_subsection("Newton");
    prm.declare_entry("Maximum iterations", "15", Patterns::Integer(1),
                      "Newton iterations per time step before the step is cut back.");
    prm.declare_entry("Residual tolerance", "1e-8", Patterns::Double(0),
                      "Relative residual tolerance: |R| <= tol * max(|f_int|, |f_ext|) (dimensionless).");
    prm.declare_entry("Absolute residual tolerance", "1e-12", Patterns::Double(0),
                      "Residual norm in N below which a step is converged whatever the scale.");
    prm.declare_entry("Displacement tolerance", "1e-8", Patterns::Double(0),
                      "Relative increment tolerance: |δu| <= tol * |Δu of the step| (dimensionless).");
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
  void MechanicalProblem<dim>::Parameters::parse_parameters(ParameterHandler &prm, const Scene &)
  {
    prm.enter_subsection("Mechanics");
    polynomial_degree = prm.get_integer("Polynomial degree");
    temperature       = prm.get_double("Temperature");
    prm.enter_subsection("Newton");
    max_iterations              = prm.get_integer("Maximum iterations");
    residual_tolerance          = prm.get_double("Residual tolerance");
    absolute_residual_tolerance = prm.get_double("Absolute residual tolerance");
    displacement_tolerance      = prm.get_double("Displacement tolerance");
    line_search                 = prm.get_bool("Line search");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    linear_solver         = prm.get("Type");
    linear_tolerance      = prm.get_double("Tolerance");
    linear_max_iterations = prm.get_integer("Maximum iterations");
    direct_solver_limit   = prm.get_integer("Direct solver limit");
    prm.leave_subsection();
    prm.leave_subsection();
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

    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    boundary_conditions.make_homogeneous_constraints(dof_handler, constraints);
    constraints.close();

    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                               locally_relevant_dofs);
    system_matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);

    for (auto *v : {&system_rhs, &internal_force, &internal_force_old, &external_force,
                    &owned_solution, &owned_old_solution})
      v->reinit(locally_owned_dofs, mpi_communicator);
    solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    old_solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);

    setup_quadrature_point_data();
  }

  template <int dim>
  void MechanicalProblem<dim>::setup_quadrature_point_data()
  {
    const unsigned int n_q = quadrature.size();
    points.clear();
    points.resize(triangulation.n_active_cells() * n_q);
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
  bool MechanicalProblem<dim>::assemble(const bool with_matrix, const double time)
  {
    TimerOutput::Scope t(timer, with_matrix ? "Mechanics: assembly" : "Mechanics: residual");
    const auto start = std::chrono::steady_clock::now();

    if (with_matrix)
      system_matrix = 0;
    system_rhs      = 0;
    internal_force  = 0;
    external_force  = 0;

    FEValues<dim> fe_values(mapping, fe, quadrature,
                            update_gradients | update_JxW_values);
    FEFaceValues<dim> fe_face_values(mapping, fe, face_quadrature,
                                     update_values | update_gradients | update_normal_vectors |
                                       update_JxW_values | update_quadrature_points);

    const unsigned int n_dofs = fe.n_dofs_per_cell();
    const unsigned int n_q    = quadrature.size();
    FullMatrix<double> cell_matrix(n_dofs, n_dofs);
    Vector<double>     cell_internal(n_dofs), cell_external(n_dofs), cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<Tensor<2, dim>>          grad_u(n_q), grad_u_old(n_q);
    std::vector<double>                  local_u(n_dofs), local_u_old(n_dofs);
    std::vector<Tensor<2, dim>>          face_grad_u(face_quadrature.size());
    std::vector<unsigned int>            component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;
    std::vector<Tensor<1, dim>>              grad_N(n_dofs);
    std::vector<std::array<Tensor<1, dim>, dim>> A_grad_N(n_dofs);

    const FEValuesExtractors::Vector displacements(0);
    IncrementalKinematics            kin;
    MaterialIncrement                increment;
    MaterialResponse                 response;
    const MaterialRequest request = with_matrix ? (request_stress | request_tangent) : request_stress;

    bool   inverted          = false;
    material_failure.clear();
    double min_J             = 1;
    unsigned int n_cells     = 0;
    step_internal_work       = 0;

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        ++n_cells;
        fe_values.reinit(cell);
        // ∇u and ∇uₙ from the local dof values (cheaper than
        // get_function_gradients, which allocates per call).
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            local_u[i]     = solution(dof_indices[i]);
            local_u_old[i] = old_solution(dof_indices[i]);
          }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            grad_u[q]     = 0;
            grad_u_old[q] = 0;
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const Tensor<1, dim> g = fe_values.shape_grad_component(i, q, component[i]);
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    grad_u[q][component[i]][d] += local_u[i] * g[d];
                    grad_u_old[q][component[i]][d] += local_u_old[i] * g[d];
                  }
              }
          }
        if (with_matrix)
          cell_matrix = 0;
        cell_internal = 0;
        cell_external = 0;

        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Tensor<2, 3> F     = embed<dim>(unit_symmetric_tensor<dim>() + grad_u[q], 1.);
            const Tensor<2, 3> F_old = embed<dim>(unit_symmetric_tensor<dim>() + grad_u_old[q], 1.);
            const double       J     = determinant(F);
            min_J                    = std::min(min_J, J);
            if (!(J > 0) || !(determinant(0.5 * (F + F_old)) > 0))
              {
                inverted = true;
                break;
              }
            kin.reinit(F, F_old);
            increment.strain_increment      = kin.strain_increment;
            increment.rotation_increment    = kin.rotation_increment;
            increment.temperature           = parameters.temperature;
            increment.temperature_increment = 0;
            increment.time_step             = current_time_step;
            MaterialPoint &point = *points[cell->active_cell_index() * n_q + q];
            try
              {
                point.update(increment, request, response);
              }
            catch (const MaterialPointError &e)
              {
                // Say where; the step is cut back (all ranks learn it below).
                std::ostringstream where;
                where << e.what() << " (material point " << q << " of the cell at "
                      << cell->center() << ", body id " << cell->material_id() << ")";
                material_failure = where.str();
                inverted         = true;
                break;
              }

            const Tensor<2, 3> P   = first_piola_stress(kin, response.stress);
            const double       JxW = fe_values.JxW(q);
            // Stress power over the step at the mid-point volume (energy audit).
            step_internal_work += 0.5 * ((response.stress + point.committed_stress()) *
                                         kin.strain_increment) *
                                  determinant(0.5 * (F + F_old)) * JxW;

            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                grad_N[i] = fe_values.shape_grad_component(i, q, component[i]);
                double f  = 0;
                for (unsigned int J_ = 0; J_ < dim; ++J_)
                  f += P[component[i]][J_] * grad_N[i][J_];
                cell_internal(i) += f * JxW;
              }

            if (with_matrix)
              {
                const Tensor<4, dim> A =
                  first_piola_tangent<dim>(kin, point.committed_stress(), response);
                // (A : ∇N_j)[i][J] for the component of j, then contract with ∇N_i.
                for (unsigned int j = 0; j < n_dofs; ++j)
                  for (unsigned int i_ = 0; i_ < dim; ++i_)
                    for (unsigned int J_ = 0; J_ < dim; ++J_)
                      {
                        double s = 0;
                        for (unsigned int L = 0; L < dim; ++L)
                          s += A[i_][J_][component[j]][L] * grad_N[j][L];
                        A_grad_N[j][i_][J_] = s * JxW;
                      }
                for (unsigned int i = 0; i < n_dofs; ++i)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += grad_N[i] * A_grad_N[j][component[i]];
              }
          }
        if (inverted)
          break;

        // Follower pressure: f_ext = −∫ p n da N, n da = J F⁻ᵀ N dA (Nanson).
        if (boundary_conditions.has_pressure())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              for (const auto &load : boundary_conditions.pressures())
                if (face->boundary_id() == load.boundary)
                  {
                    fe_face_values.reinit(cell, face);
                    fe_face_values[displacements].get_function_gradients(solution, face_grad_u);
                    load.value->set_time(time);
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      {
                        const double p = load.value->value(fe_face_values.quadrature_point(q));
                        const Tensor<2, dim> F = unit_symmetric_tensor<dim>() + face_grad_u[q];
                        const double         J = determinant(F);
                        const Tensor<2, dim> F_inv   = invert(F);
                        const Tensor<1, dim> FiT_N   = transpose(F_inv) * fe_face_values.normal_vector(q);
                        const double         JxW     = fe_face_values.JxW(q);
                        for (unsigned int i = 0; i < n_dofs; ++i)
                          {
                            const unsigned int ci = component[i];
                            const double       Ni = fe_face_values.shape_value(i, q);
                            cell_external(i) -= p * J * FiT_N[ci] * Ni * JxW;
                            if (with_matrix)
                              for (unsigned int j = 0; j < n_dofs; ++j)
                                {
                                  const unsigned int   cj = component[j];
                                  const Tensor<1, dim> g =
                                    fe_face_values.shape_grad_component(j, q, cj);
                                  double tr = 0; // tr(F⁻¹ δF) with δF = e_cj ⊗ g
                                  for (unsigned int m = 0; m < dim; ++m)
                                    tr += F_inv[m][cj] * g[m];
                                  const Tensor<1, dim> FiT_g = transpose(F_inv) * g;
                                  const double d_nda = J * (tr * FiT_N[ci] - FiT_g[ci] * FiT_N[cj]);
                                  // K = ∂f_int/∂u − ∂f_ext/∂u
                                  cell_matrix(i, j) += p * d_nda * Ni * JxW;
                                }
                          }
                      }
                  }

        for (unsigned int i = 0; i < n_dofs; ++i)
          cell_rhs(i) = cell_external(i) - cell_internal(i);
        if (with_matrix)
          active_constraints->distribute_local_to_global(cell_matrix, cell_rhs, dof_indices,
                                                         system_matrix, system_rhs);
        else
          active_constraints->distribute_local_to_global(cell_rhs, dof_indices, system_rhs);
        internal_force.add(dof_indices, cell_internal);
        external_force.add(dof_indices, cell_external);
      }

    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    step_internal_work = Utilities::MPI::sum(step_internal_work, mpi_communicator);

    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (with_matrix && seconds > 0)
      assembly_rate = n_cells / seconds;
    return Utilities::MPI::max(inverted ? 1 : 0, mpi_communicator) == 0;
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
  typename MechanicalProblem<dim>::StepResult
  MechanicalProblem<dim>::solve_step(const double time_old, const double time_new)
  {
    StepResult result;
    current_time_step = time_new - time_old;

    // Predictor: the first Newton iteration starts from the committed
    // configuration and imposes the jump of the prescribed displacements as
    // inhomogeneous constraints, so the whole body follows the boundary
    // (moving only the boundary nodes would invert the cells next to it when
    // the jump exceeds their size).
    owned_solution = owned_old_solution;
    solution       = owned_solution;
    predictor_constraints.clear();
    predictor_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, predictor_constraints);
    {
      std::map<types::global_dof_index, double> values;
      boundary_conditions.interpolate(dof_handler, time_new, values);
      for (const auto &[dof, value] : values)
        if (locally_relevant_dofs.is_element(dof) && !predictor_constraints.is_constrained(dof))
          {
            predictor_constraints.add_line(dof);
            predictor_constraints.set_inhomogeneity(dof, value - old_solution(dof));
          }
    }
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

        const double scale = std::max(internal_force.l2_norm(), external_force.l2_norm());
        TrilinosWrappers::MPI::Vector step_u(owned_solution);
        step_u -= owned_old_solution;
        const double du_scale = step_u.l2_norm();
        const bool residual_ok =
          r <= parameters.absolute_residual_tolerance || r <= parameters.residual_tolerance * scale;
        const bool increment_ok =
          (last_increment >= 0 && last_increment <= parameters.displacement_tolerance * du_scale) ||
          r <= parameters.absolute_residual_tolerance;
        if (residual_ok && (increment_ok || it == 0) && !(it == 0 && has_jump))
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
            if (!parameters.line_search || ls == 5 || (it == 0 && has_jump))
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
  void MechanicalProblem<dim>::commit_step()
  {
    // Trapezoidal work of the forces that hold the body in equilibrium:
    // at equilibrium f_int = f_ext + reactions at every dof.
    TrilinosWrappers::MPI::Vector du(owned_solution);
    du -= owned_old_solution;
    TrilinosWrappers::MPI::Vector mean_force(internal_force);
    mean_force += internal_force_old;
    work_external += 0.5 * (mean_force * du);
    work_internal += step_internal_work;

    for (auto &p : points)
      if (p)
        p->commit();
    owned_old_solution = owned_solution;
    old_solution       = owned_solution;
    internal_force_old = internal_force;
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
              force[fe.system_to_component_index(i).first] += internal_force(g) - external_force(g);
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

    FEValues<dim> fe_values(mapping, fe, quadrature, update_gradients);
    const unsigned int n_q = quadrature.size();
    std::vector<Tensor<2, dim>> grad_u(n_q);
    const FEValuesExtractors::Vector displacements(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements].get_function_gradients(solution, grad_u);
          SymmetricTensor<2, 3> s;
          double J = 0, eqps = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const auto &p = *points[cell->active_cell_index() * n_q + q];
              s += p.stress() / n_q;
              eqps += p.equivalent_plastic_strain() / n_q;
              J += determinant(unit_symmetric_tensor<dim>() + grad_u[q]) / n_q;
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
                                     SymmetricTensor<2, 3> &stress) const
  {
    u      = Tensor<1, dim>();
    stress = SymmetricTensor<2, 3>();
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
              stress += points[cell->active_cell_index() * n_q + k]->stress() / n_q;
          }
      }
    catch (...)
      {
        // not in this rank's part of the mesh
      }
    const double n = Utilities::MPI::sum(found, mpi_communicator);
    u              = Utilities::MPI::sum(u, mpi_communicator);
    stress         = Utilities::MPI::sum(stress, mpi_communicator);
    if (n == 0)
      return false;
    u /= n;
    stress /= n;
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
