// ThermalProblem: assembly of M, f(T, t) = −K(T) T + F(T, t) and its tangent,
// the heat balance integrals and the linear solvers behind ARKode.
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/thermal/thermal_problem.h>

#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    constexpr double stefan_boltzmann = 5.670374e-11; // mW/(mm² K⁴)
  }

  template <int dim>
  void ThermalProblem<dim>::dirichlet_values(const double t,
                                             std::map<types::global_dof_index, double> &values) const
  {
    values.clear();
    for (const auto &[id, b] : boundary_conditions.boundaries)
      if (b.temperature)
        {
          b.temperature->set_time(t);
          VectorTools::interpolate_boundary_values(get_mapping(), dof_handler, id, *b.temperature, values);
        }
  }

  template <int dim>
  void ThermalProblem<dim>::apply_dirichlet(const double t, Vector &y) const
  {
    std::map<types::global_dof_index, double> values;
    if (has_dirichlet)
      dirichlet_values(t, values);
    for (const auto i : dirichlet_dofs)
      y(i) = values.at(i);
    y.compress(VectorOperation::insert);
  }

  template <int dim>
  void ThermalProblem<dim>::assemble_mass()
  {
    TimerOutput::Scope t(timer, "Heat: mass matrix");
    mass_matrix    = 0;
    lumped_mass    = 0;
    // Mass is conserved: ρ dv = ρ₀ dV, so the capacity is integrated on the
    // reference configuration whatever the current one.
    FEValues<dim> fe_values(reference_mapping, fe, quadrature,
                            update_values | update_JxW_values | update_quadrature_points);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double>                   local(n, n);
    dealii::Vector<double>               row_sums(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          local = 0;
          const auto  &m  = materials.at(cell->material_id());
          const double rc = m.density * m.heat_capacity;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double w = fe_values.JxW(q) *
                               (parameters.axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  local(i, j) += rc * fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * w;
            }
          for (unsigned int i = 0; i < n; ++i)
            {
              row_sums(i) = 0;
              for (unsigned int j = 0; j < n; ++j)
                row_sums(i) += local(i, j);
            }
          cell->get_dof_indices(dofs);
          constraints.distribute_local_to_global(local, dofs, mass_matrix);
          constraints.distribute_local_to_global(row_sums, dofs, lumped_mass);
        }
    mass_matrix.compress(VectorOperation::add);
    lumped_mass.compress(VectorOperation::add);
    // Constrained rows: the diagonal AffineConstraints left in M (Ṫ = ġ rows).
    mass_diagonal = 0;
    for (const auto i : locally_owned_dofs)
      if (constraints.is_constrained(i))
        mass_diagonal(i) = lumped_mass(i) = mass_matrix.diag_element(i);
    mass_diagonal.compress(VectorOperation::insert);
    lumped_mass.compress(VectorOperation::insert);
    mass_jacobi.initialize(mass_matrix);
    current_gamma = -1;
  }

  template <int dim>
  bool ThermalProblem<dim>::linear_residual(const double t, const Vector &y, Vector &rhs)
  {
    // f = −K y + F: K (the tangent, assembled once per configuration) and the
    // step's sources F fixed while the geometry is frozen; only the
    // prescribed fluxes are evaluated at t. Needs: k independent of T, no
    // radiation, no convection (h may depend on t), no Temperature boundary
    // (its ġ terms), no expression source (may depend on t, x).
    if (!(linear && !has_dirichlet && !has_convection && !source_function))
      return false;
    TimerOutput::Scope scope(timer, "Heat: residual (linear)");
    if (!tangent_current)
      {
        assemble(t, y, nullptr, &tangent_matrix);
        tangent_current = true;
      }
    if (!sources_current)
      {
        // F = ∫ s φ dv on the current configuration, s from the mechanics.
        step_sources.reinit(locally_owned_dofs, mpi_communicator);
        if (heat_source)
          {
            FEValues<dim> fe_values(get_mapping(), fe, quadrature,
                                    update_values | update_JxW_values | update_quadrature_points);
            const unsigned int n = fe.n_dofs_per_cell();
            dealii::Vector<double>               local_f(n);
            std::vector<types::global_dof_index> dofs(n);
            for (const auto &cell : dof_handler.active_cell_iterators())
              if (cell->is_locally_owned())
                {
                  fe_values.reinit(cell);
                  cell->get_dof_indices(dofs);
                  local_f = 0;
                  for (unsigned int q = 0; q < quadrature.size(); ++q)
                    {
                      const double w = fe_values.JxW(q) * (parameters.axisymmetric ?
                                                             2 * numbers::PI * fe_values.quadrature_point(q)[0] :
                                                             1.);
                      const double s = heat_source(cell, q);
                      for (unsigned int i = 0; i < n; ++i)
                        local_f(i) += fe_values.shape_value(i, q) * s * w;
                    }
                  constraints.distribute_local_to_global(local_f, dofs, step_sources);
                }
            step_sources.compress(VectorOperation::add);
          }
        sources_current = true;
      }
    {
      Vector owned(y);
      hanging.distribute(owned);
      tangent_matrix.vmult(rhs, owned);
    }
    rhs *= -1.;
    rhs += step_sources;
    if (exchange.add_rhs)
      {
        exchange.add_rhs(t, y, rhs);
        rhs.compress(VectorOperation::add);
      }
    // Prescribed fluxes at t, on their faces only.
    bool any_flux = false;
    for (const auto &[id, b] : boundary_conditions.boundaries)
      if (b.flux)
        {
          any_flux = true;
          b.flux->set_time(t);
        }
    if (any_flux)
      {
        FEFaceValues<dim> fe_face(get_mapping(), fe, face_quadrature,
                                  update_values | update_JxW_values | update_quadrature_points);
        const unsigned int n = fe.n_dofs_per_cell();
        dealii::Vector<double>               local_f(n);
        std::vector<types::global_dof_index> dofs(n);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                {
                  const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
                  if (bc == boundary_conditions.boundaries.end() || !bc->second.flux)
                    continue;
                  fe_face.reinit(cell, f);
                  cell->get_dof_indices(dofs);
                  local_f = 0;
                  for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                    {
                      const Point<dim> &x = fe_face.quadrature_point(q);
                      const double w = fe_face.JxW(q) * (parameters.axisymmetric ? 2 * numbers::PI * x[0] : 1.);
                      const double q_in = bc->second.flux->value(x);
                      for (unsigned int i = 0; i < n; ++i)
                        local_f(i) += fe_face.shape_value(i, q) * q_in * w;
                    }
                  constraints.distribute_local_to_global(local_f, dofs, rhs);
                }
        rhs.compress(VectorOperation::add);
      }
    return true;
  }

  template <int dim>
  void ThermalProblem<dim>::assemble(const double t, const Vector &y, Vector *rhs,
                                     TrilinosWrappers::SparseMatrix *tangent)
  {
    if (rhs && !tangent && linear_residual(t, y, *rhs))
      return;
    TimerOutput::Scope scope(timer, rhs ? "Heat: residual" : "Heat: tangent");
    {
      Vector owned(y);
      hanging.distribute(owned);
      scratch_ghosted = owned;
    }
    const Vector &T = scratch_ghosted;

    // ġ at the Dirichlet dofs (central difference in time), for the rows
    // Ṫ_D = ġ_D and for moving M_fD ġ_D to the free rows.
    std::map<types::global_dof_index, double> g_dot;
    if (rhs && has_dirichlet)
      {
        const double eps = 1e-6 * std::max(step_length, 1e-300);
        std::map<types::global_dof_index, double> plus, minus;
        dirichlet_values(t + eps, plus);
        dirichlet_values(t - eps, minus);
        for (const auto &[i, v] : plus)
          {
            const double d = (v - minus.at(i)) / (2 * eps);
            if (d != 0)
              g_dot[i] = d;
          }
      }
    const bool coupling = !g_dot.empty() && !parameters.lumped_mass;

    if (rhs)
      *rhs = 0;
    if (tangent)
      *tangent = 0;
    if (source_function)
      source_function->set_time(t);
    for (const auto &[id, b] : boundary_conditions.boundaries)
      for (const auto &f : {b.flux, b.h, b.T_convection, b.emissivity, b.T_radiation})
        if (f)
          f->set_time(t);

    const UpdateFlags flags = update_values | update_gradients | update_JxW_values | update_quadrature_points;
    FEValues<dim>     fe_values(get_mapping(), fe, quadrature, flags);
    FEValues<dim>     fe_reference(reference_mapping, fe, quadrature,
                               update_JxW_values | update_quadrature_points);
    FEFaceValues<dim> fe_face(get_mapping(), fe, face_quadrature,
                              update_values | update_JxW_values | update_quadrature_points);
    const unsigned int n = fe.n_dofs_per_cell(), nq = quadrature.size();
    FullMatrix<double>                   local_A(n, n);
    dealii::Vector<double>               local_f(n), local_g_dot(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<double>                  T_q(nq), T_f(face_quadrature.size());
    std::vector<Tensor<1, dim>>          grad_T(nq);
    const bool axi = parameters.axisymmetric;

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          if (coupling)
            fe_reference.reinit(cell);
          cell->get_dof_indices(dofs);
          fe_values.get_function_values(T, T_q);
          fe_values.get_function_gradients(T, grad_T);
          local_A = 0;
          local_f = 0;
          bool any_g_dot = false;
          if (coupling)
            for (unsigned int j = 0; j < n; ++j)
              {
                const auto it  = g_dot.find(dofs[j]);
                local_g_dot(j) = it == g_dot.end() ? 0. : it->second;
                any_g_dot      = any_g_dot || local_g_dot(j) != 0;
              }
          const auto  &m  = materials.at(cell->material_id());
          const double rc = m.density * m.heat_capacity;
          // The capacity per current volume is ρ₀c dV/dv (mass conservation).
          auto reference_weight = [&](const unsigned int q) {
            return fe_reference.JxW(q) *
                   (axi ? 2 * numbers::PI * fe_reference.quadrature_point(q)[0] : 1.);
          };
          for (unsigned int q = 0; q < nq; ++q)
            {
              const Point<dim> &x = fe_values.quadrature_point(q);
              const double w  = fe_values.JxW(q) * (axi ? 2 * numbers::PI * x[0] : 1.);
              const double k  = m.k(T_q[q]), dk = m.dk_dT();
              if (rhs)
                {
                  double s = source_function ? source_function->value(x) : 0.;
                  if (heat_source)
                    s += heat_source(cell, q);
                  double rc_g_dot = 0;
                  if (any_g_dot)
                    for (unsigned int j = 0; j < n; ++j)
                      rc_g_dot += rc * reference_weight(q) / w * fe_values.shape_value(j, q) *
                                  local_g_dot(j);
                  for (unsigned int i = 0; i < n; ++i)
                    local_f(i) += (-k * (fe_values.shape_grad(i, q) * grad_T[q]) +
                                   fe_values.shape_value(i, q) * (s - rc_g_dot)) * w;
                }
              if (tangent)
                for (unsigned int i = 0; i < n; ++i)
                  {
                    const double gi_gT = fe_values.shape_grad(i, q) * grad_T[q];
                    for (unsigned int j = 0; j < n; ++j)
                      local_A(i, j) += (k * (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q)) +
                                        dk * fe_values.shape_value(j, q) * gi_gT) * w;
                  }
            }
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
                if (bc == boundary_conditions.boundaries.end() || bc->second.temperature)
                  continue;
                const auto &b = bc->second;
                fe_face.reinit(cell, f);
                fe_face.get_function_values(T, T_f);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const Point<dim> &x = fe_face.quadrature_point(q);
                    const double w  = fe_face.JxW(q) * (axi ? 2 * numbers::PI * x[0] : 1.);
                    double q_in = 0, dq_dT = 0;
                    if (b.flux)
                      q_in += b.flux->value(x);
                    if (b.h)
                      {
                        const double h = b.h->value(x);
                        q_in += h * (b.T_convection->value(x) - T_f[q]);
                        dq_dT -= h;
                      }
                    if (b.emissivity)
                      {
                        const double es = b.emissivity->value(x) * stefan_boltzmann;
                        const double Ti = b.T_radiation->value(x);
                        q_in += es * (Ti * Ti * Ti * Ti - std::pow(T_f[q], 4));
                        dq_dT -= 4 * es * std::pow(T_f[q], 3);
                      }
                    for (unsigned int i = 0; i < n; ++i)
                      {
                        local_f(i) += fe_face.shape_value(i, q) * q_in * w;
                        for (unsigned int j = 0; j < n; ++j)
                          local_A(i, j) -= dq_dT * fe_face.shape_value(i, q) * fe_face.shape_value(j, q) * w;
                      }
                  }
              }
          if (rhs)
            constraints.distribute_local_to_global(local_f, dofs, *rhs);
          if (tangent)
            constraints.distribute_local_to_global(local_A, dofs, *tangent);
        }
    if (rhs)
      {
        rhs->compress(VectorOperation::add);
        if (exchange.add_rhs)
          {
            exchange.add_rhs(t, y, *rhs);
            rhs->compress(VectorOperation::add);
          }
        for (const auto i : dirichlet_dofs)
          {
            const auto it = g_dot.find(i);
            (*rhs)(i)     = it == g_dot.end() ? 0. : mass_diagonal(i) * it->second;
          }
        rhs->compress(VectorOperation::insert);
      }
    if (tangent)
      {
        tangent->compress(VectorOperation::add);
        // Constrained rows of f do not depend on T: no diagonal there.
        for (const auto i : locally_owned_dofs)
          if (constraints.is_constrained(i))
            tangent->set(i, i, 0.);
        tangent->compress(VectorOperation::insert);
        current_gamma = -1;
      }
  }

  template <int dim>
  void ThermalProblem<dim>::setup_newton(const double gamma)
  {
    // M − γ'J with γ' within 20 % of γ preconditions ARKode's GMRES on M − γJ
    // well (a few iterations): keep the factorisation.
    if (current_gamma > 0 && std::abs(gamma / current_gamma - 1) < 0.2)
      return;
    TimerOutput::Scope t(timer, "Heat: Newton matrix");
    if (parameters.lumped_mass)
      {
        newton_matrix.copy_from(tangent_matrix);
        newton_matrix *= gamma;
        for (const auto i : locally_owned_dofs)
          newton_matrix.add(i, i, lumped_mass(i));
        newton_matrix.compress(VectorOperation::add);
      }
    else
      {
        newton_matrix.copy_from(mass_matrix);
        newton_matrix.add(gamma, tangent_matrix);
      }
    if (exchange.add_diagonal)
      {
        // The exchange's diagonal (its couplings act through GMRES only).
        Vector diagonal(locally_owned_dofs, mpi_communicator);
        exchange.add_diagonal(diagonal);
        for (const auto i : locally_owned_dofs)
          if (diagonal(i) != 0)
            newton_matrix.add(i, i, gamma * diagonal(i));
        newton_matrix.compress(VectorOperation::add);
      }
    if (use_direct)
      {
        newton_direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          direct_control, TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
        newton_direct->initialize(newton_matrix);
      }
    else
      {
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = parameters.polynomial_degree > 1;
        data.smoother_sweeps       = 2;
        newton_amg                 = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        newton_amg->initialize(newton_matrix, data);
      }
    current_gamma = gamma;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_newton(Vector &x, const Vector &b, double)
  {
    if (use_direct)
      {
        newton_direct->solve(x, b);
        return 1;
      }
    newton_amg->vmult(x, b); // one V-cycle: the preconditioner of ARKode's GMRES
    return 1;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_mass(Vector &x, const Vector &b, const double tolerance)
  {
    ++mass_solves;
    if (parameters.lumped_mass)
      {
        x = b;
        for (const auto i : locally_owned_dofs)
          x(i) /= lumped_mass(i);
        x.compress(VectorOperation::insert);
        return 1;
      }
    SolverControl control(1000, std::min(tolerance, 1e-10 * b.l2_norm()));
    SolverCG<Vector> cg(control);
    x = 0;
    cg.solve(mass_matrix, x, b, mass_jacobi);
    linear_iterations += control.last_step();
    return control.last_step();
  }

  template <int dim>
  std::map<types::boundary_id, double> ThermalProblem<dim>::boundary_flows(const double t,
                                                                         const Vector &T) const
  {
    std::map<types::boundary_id, double> power;
    for (const auto &[id, b] : boundary_conditions.boundaries)
      if (!b.temperature)
        {
          power[id] = 0;
          for (const auto &f : {b.flux, b.h, b.T_convection, b.emissivity, b.T_radiation})
            if (f)
              f->set_time(t);
        }
    FEFaceValues<dim> fe_face(get_mapping(), fe, face_quadrature,
                              update_values | update_JxW_values | update_quadrature_points);
    std::vector<double> T_f(face_quadrature.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto it = power.find(cell->face(f)->boundary_id());
              if (it == power.end())
                continue;
              const auto &b = boundary_conditions.boundaries.at(it->first);
              fe_face.reinit(cell, f);
              fe_face.get_function_values(T, T_f);
              for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                {
                  const Point<dim> &x = fe_face.quadrature_point(q);
                  double q_in = 0;
                  if (b.flux)
                    q_in += b.flux->value(x);
                  if (b.h)
                    q_in += b.h->value(x) * (b.T_convection->value(x) - T_f[q]);
                  if (b.emissivity)
                    q_in += b.emissivity->value(x) * stefan_boltzmann *
                            (std::pow(b.T_radiation->value(x), 4) - std::pow(T_f[q], 4));
                  it->second += q_in * fe_face.JxW(q) *
                                (parameters.axisymmetric ? 2 * numbers::PI * x[0] : 1.);
                }
            }
    for (auto &[id, p] : power)
      p = Utilities::MPI::sum(p, mpi_communicator);
    return power;
  }

  template <int dim>
  double ThermalProblem<dim>::source_power(const double t) const
  {
    if (!source_function && !heat_source)
      return 0;
    if (source_function)
      source_function->set_time(t);
    FEValues<dim> fe_values(get_mapping(), fe, quadrature, update_JxW_values | update_quadrature_points);
    double        power = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Point<dim> &x = fe_values.quadrature_point(q);
              double s = source_function ? source_function->value(x) : 0.;
              if (heat_source)
                s += heat_source(cell, q);
              power += s * fe_values.JxW(q) * (parameters.axisymmetric ? 2 * numbers::PI * x[0] : 1.);
            }
        }
    return Utilities::MPI::sum(power, mpi_communicator);
  }

  template <int dim>
  double ThermalProblem<dim>::heat_content(const Vector &T) const
  {
    // ∫ ρ c T dv = ∫ ρ₀ c T dV (mass conservation).
    FEValues<dim> fe_values(reference_mapping, fe, quadrature,
                            update_values | update_JxW_values | update_quadrature_points);
    std::vector<double> T_q(quadrature.size());
    double              H = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(T, T_q);
          const auto &m = materials.at(cell->material_id());
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            H += m.density * m.heat_capacity * T_q[q] * fe_values.JxW(q) *
                 (parameters.axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
        }
    return Utilities::MPI::sum(H, mpi_communicator);
  }

  template <int dim>
  double ThermalProblem<dim>::integrate(const HeatSource &source) const
  {
    FEValues<dim> fe_values(get_mapping(), fe, quadrature, update_JxW_values | update_quadrature_points);
    double        total = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            total += source(cell, q) * fe_values.JxW(q) *
                     (parameters.axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
        }
    return Utilities::MPI::sum(total, mpi_communicator);
  }

  template <int dim>
  double ThermalProblem<dim>::temperature_at(const Point<dim> &point) const
  {
    double value = 0, found = 0;
    try
      {
        const auto cell_and_point =
          GridTools::find_active_cell_around_point(reference_mapping, dof_handler, point);
        const auto &cell = cell_and_point.first;
        if (cell.state() == IteratorState::valid && cell->is_locally_owned())
          {
            const Quadrature<dim> q(GeometryInfo<dim>::project_to_unit_cell(cell_and_point.second));
            FEValues<dim>         fe_values(reference_mapping, fe, q, update_values);
            fe_values.reinit(cell);
            std::vector<double> T(1);
            fe_values.get_function_values(temperature_ghosted, T);
            value = T[0];
            found = 1;
          }
      }
    catch (...)
      {
        // not in this rank's part of the mesh
      }
    const double n = Utilities::MPI::sum(found, mpi_communicator);
    value          = Utilities::MPI::sum(value, mpi_communicator);
    return n > 0 ? value / n : std::numeric_limits<double>::quiet_NaN();
  }

  template <int dim>
  dealii::Vector<double> ThermalProblem<dim>::cell_mean_temperature() const
  {
    dealii::Vector<double> mean(triangulation.n_active_cells());
    FEValues<dim>         fe_values(reference_mapping, fe, quadrature, update_values | update_JxW_values);
    std::vector<double>   T(quadrature.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(temperature_ghosted, T);
          double sum = 0, volume = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            sum += T[q] * fe_values.JxW(q), volume += fe_values.JxW(q);
          mean[cell->active_cell_index()] = sum / volume;
        }
    return mean;
  }

  template <int dim>
  double ThermalProblem<dim>::heat_content() const
  {
    return heat_content(temperature_ghosted);
  }

  template <int dim>
  void ThermalProblem<dim>::temperature_at_quadrature_points(
    const typename Triangulation<dim>::active_cell_iterator &cell, const Quadrature<dim> &q,
    std::vector<double> &T_new, std::vector<double> &T_old) const
  {
    if (!point_values || !(q == *point_quadrature))
      {
        point_quadrature = std::make_unique<Quadrature<dim>>(q);
        point_values = std::make_unique<FEValues<dim>>(reference_mapping, fe, *point_quadrature, update_values);
      }
    const typename DoFHandler<dim>::active_cell_iterator dof_cell(&triangulation, cell->level(),
                                                                  cell->index(), &dof_handler);
    point_values->reinit(dof_cell);
    T_new.resize(q.size());
    T_old.resize(q.size());
    point_values->get_function_values(temperature_ghosted, T_new);
    point_values->get_function_values(old_temperature_ghosted, T_old);
  }

  template class ThermalProblem<2>;
  template class ThermalProblem<3>;
} // namespace anvil
