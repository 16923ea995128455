// ThermalProblem: assembly of M, f(T, t) = −K(T) T + F(T, t) and its
// tangent on all threads of the process (WorkStream), Dirichlet handling.
// The terms themselves are in kernels.cc; here the cell loops compose them.
//
// WorkStream runs the workers (cell integrals, into CopyData) on the threads
// and the copiers (AffineConstraints::distribute_local_to_global into the
// Trilinos objects) one at a time in cell order: the global sums are those of
// a serial loop, bit for bit, whatever the number of threads. Everything a
// worker calls only reads: FEValues (per thread), the ghosted temperature,
// the FunctionParsers (deal.II keeps one muparser per thread; their time is
// set before the loop), the materials, the mechanics' heat sources.
//
// The Dirichlet values, couplings and rates are in thermal_dirichlet.cc.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1_eulerian.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/numerics/vector_tools.h>

#include <Epetra_CrsMatrix.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/assembly_data.h>
#include <anvil/thermal/kernels.h>
#include <anvil/thermal/thermal_problem.h>

#include "current_weights.h"
#include "newton_factorisation.h"
#include "owned_cells.h"
#include "q1_conduction.h"
#include "tangent_adder.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace anvil
{
  using namespace dealii;
  using thermal::for_owned_cells;


  namespace
  {
    /// K += k ∫ ∇φᵢ·∇φⱼ dv of every owned Q1 cell, in cell order (the sums
    /// of the WorkStream copier in assemble()), from @p moved (by vertex
    /// index; nullptr: the reference vertices).
    template <int dim>
    void add_q1_conduction(const DoFHandler<dim> &dofs, const std::map<types::material_id, ThermalMaterial> &materials,
                           const std::vector<Point<dim>> *moved, const thermal::Q1Conduction<dim> &q1,
                           const bool axisymmetric, thermal::TangentAdder &adder,
                           const AffineConstraints<double> &hanging, TrilinosWrappers::SparseMatrix &tangent)
    {
      thermal::CopyData c(dofs.get_fe().n_dofs_per_cell());
      std::array<Point<dim>, thermal::Q1Conduction<dim>::n_vertices> x;
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(c.dofs);
            c.cell_index = cell->active_cell_index();
            c.matrix     = 0;
            for (unsigned int v = 0; v < x.size(); ++v)
              x[v] = moved ? (*moved)[cell->vertex_index(v)] : cell->vertex(v);
            q1.add_cell_matrix(x, materials.at(cell->material_id()).conductivity, axisymmetric, c.matrix);
            if (!adder.add(c))
              hanging.distribute_local_to_global(c.matrix, c.dofs, tangent);
          }
    }
  } // namespace

  template <int dim>
  void ThermalProblem<dim>::assemble_mass()
  {
    TimerOutput::Scope t(timer, "Heat: mass matrix");
    mass_matrix    = 0;
    lumped_mass    = 0;
    // Mass is conserved: ρ dv = ρ₀ dV, so the capacity is integrated on the
    // reference configuration whatever the current one.
    const thermal::ScratchData<dim> scratch(reference_mapping, reference_mapping, fe, quadrature,
                                            face_quadrature,
                                            update_values | update_JxW_values | update_quadrature_points,
                                            update_default, update_default);
    const bool axi = parameters.axisymmetric;
    auto worker = [&](const CellIterator &cell, thermal::ScratchData<dim> &s, thermal::CopyData &c) {
      s.fe_values.reinit(cell);
      thermal::fill_weights<dim>(s.fe_values, axi, s.weight);
      const auto &m = materials.at(cell->material_id());
      thermal::HeatCapacity::cell_matrix(s, m.density * m.heat_capacity, c);
      cell->get_dof_indices(c.dofs);
    };
    auto copier = [&](const thermal::CopyData &c) {
      constraints.distribute_local_to_global(c.matrix, c.dofs, mass_matrix);
      constraints.distribute_local_to_global(c.row_sums, c.dofs, lumped_mass);
    };
    for_owned_cells(dof_handler, worker, copier, scratch);
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
    if (thermal::mass_by_klu(use_direct, parameters.lumped_mass, dof_handler.n_dofs()))
      mass_direct->factorize(mass_matrix);
    current_gamma           = -1;
    mass_in_pattern_current = false;
  }

  template <int dim>
  void ThermalProblem<dim>::assemble_step_sources()
  {
    // F = ∫ s φ dv on the current configuration, s from the mechanics.
    step_sources.reinit(locally_owned_dofs, mpi_communicator);
    if (!heat_source)
      return;
    if (current_mapping)
      {
        // The worker's sums below from the configuration's table (FE_Q's
        // values at the points are the reference ones): no FEValues per cell.
        thermal::CurrentWeights<dim> w([this]() -> const thermal::CellTable & { return *current_cells(); },
                                       get_mapping(), fe, quadrature, parameters.axisymmetric);
        const auto        &shape = reference_cells().shape;
        const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
        thermal::CopyData  c(n_dofs);
        std::vector<double> rate(n_q), weight(n_q);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (thermal::zero_on_cell<dim>(heat_source, cell, n_q))
                continue;
              w.reinit(cell);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  // as VolumeSource::cell_rates with no expression and no ġ_D, and fill_weights
                  double s = 0.;
                  s += heat_source(cell, q);
                  rate[q]   = s - 0.;
                  weight[q] = w.JxW[q] * w.axis_weight[q];
                }
              c.vector = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                for (unsigned int i = 0; i < n_dofs; ++i)
                  c.vector(i) += thermal::VolumeSource::residual(shape[i * n_q + q], rate[q]) * weight[q];
              cell->get_dof_indices(c.dofs);
              constraints.distribute_local_to_global(c.vector, c.dofs, step_sources);
            }
        step_sources.compress(VectorOperation::add);
        return;
      }
    const thermal::ScratchData<dim> scratch(get_mapping(), reference_mapping, fe, quadrature,
                                            face_quadrature,
                                            update_values | update_JxW_values | update_quadrature_points,
                                            update_default, update_default);
    const bool axi = parameters.axisymmetric;
    // A cell without sources (elastic, no expansion) adds zeros: skip it.
    auto worker = [&](const CellIterator &cell, thermal::ScratchData<dim> &s, thermal::CopyData &c) {
      c.n_faces = !thermal::zero_on_cell<dim>(heat_source, cell, quadrature.size());
      if (!c.n_faces)
        return;
      s.fe_values.reinit(cell);
      cell->get_dof_indices(c.dofs);
      thermal::fill_weights<dim>(s.fe_values, axi, s.weight);
      c.vector = 0;
      thermal::VolumeSource::cell_rates<dim>(s, cell, nullptr, &heat_source, 0., axi);
      thermal::VolumeSource::cell_load(s, c);
    };
    auto copier = [&](const thermal::CopyData &c) {
      if (c.n_faces)
        constraints.distribute_local_to_global(c.vector, c.dofs, step_sources);
    };
    for_owned_cells(dof_handler, worker, copier, scratch);
    step_sources.compress(VectorOperation::add);
  }

  template <int dim>
  void ThermalProblem<dim>::add_prescribed_fluxes(const double t, Vector &rhs)
  {
    // Prescribed fluxes and convection loads h T∞ at t, on their faces only,
    // each face added on its own. The convection's −h T is in K: the faces
    // are evaluated at T = 0.
    bool any_flux = false;
    for (const auto &[id, b] : boundary_conditions.boundaries)
      for (const auto &f : {b.flux, b.h, b.T_convection})
        if (f)
          {
            any_flux = true;
            f->set_time(t);
          }
    if (!any_flux)
      return;
    const Vector zero(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    const thermal::ScratchData<dim> scratch(get_mapping(), reference_mapping, fe, quadrature,
                                            face_quadrature, update_default, update_default,
                                            update_values | update_JxW_values | update_quadrature_points);
    const bool axi = parameters.axisymmetric;
    auto worker = [&](const CellIterator &cell, thermal::ScratchData<dim> &s, thermal::CopyData &c) {
      c.n_faces = 0;
      if (!cell->at_boundary())
        return;
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
            if (bc == boundary_conditions.boundaries.end() || !(bc->second.flux || bc->second.h))
              continue;
            c.vector = 0;
            thermal::boundary_face<dim>(s, cell, f, bc->second, &zero, axi, false, c);
            c.face_vectors[c.n_faces++] = c.vector;
          }
      if (c.n_faces > 0)
        cell->get_dof_indices(c.dofs);
    };
    auto copier = [&](const thermal::CopyData &c) {
      for (unsigned int k = 0; k < c.n_faces; ++k)
        constraints.distribute_local_to_global(c.face_vectors[k], c.dofs, rhs);
    };
    for_owned_cells(dof_handler, worker, copier, scratch);
    rhs.compress(VectorOperation::add);
  }

  template <int dim>
  bool ThermalProblem<dim>::linear_residual(const double t, const Vector &y, Vector &rhs)
  {
    // f = −K y + F(t): K (the tangent, assembled once per configuration) and
    // the step's sources fixed while the geometry is frozen; only the
    // prescribed fluxes and the convection loads h T∞(t) are evaluated at t
    // (faces only). Temperature boundaries add −K_fD y_D (columns the tangent
    // keeps) and −M_fD ġ_D (columns the constrained M drops), and their rows
    // Ṫ_D = ġ_D: the same
    // sums as the cell loop of assemble(), in another order. Needs: k
    // independent of T, no radiation, h independent of t (K would change),
    // no expression source (may depend on t, x), no hanging nodes beside
    // Temperature boundaries (a hanging dof's Dirichlet master is a column
    // the couplings below do not see).
    if (!(linear && !convection_varies && !source_function && !(has_dirichlet && has_hanging)))
      return false;
    TimerOutput::Scope scope(timer, "Heat: residual (linear)");
    if (!tangent_current)
      {
        assemble(t, y, nullptr, &tangent_matrix);
        tangent_current = true;
      }
    if (has_dirichlet && !couplings_current)
      {
        assemble_dirichlet_couplings();
        couplings_current = true;
      }
    if (!sources_current)
      {
        assemble_step_sources();
        sources_current = true;
      }
    // The tangent keeps the Dirichlet columns: −K y includes −K_fD y_D.
    if (has_hanging)
      {
        Vector owned(y);
        hanging.distribute(owned);
        tangent_matrix.vmult(rhs, owned);
      }
    else // no copy (distribute() imports a ghosted vector even with no lines)
      tangent_matrix.vmult(rhs, y);
    rhs *= -1.;
    rhs += step_sources;
    if (exchange.add_rhs)
      {
        exchange.add_rhs(t, y, rhs);
        rhs.compress(VectorOperation::add);
      }
    if (loads_vary)
      add_prescribed_fluxes(t, rhs);
    else
      {
        // Constant fluxes and T∞: one face loop per configuration, not one per evaluation.
        if (!loads_current)
          {
            face_loads.reinit(locally_owned_dofs, mpi_communicator);
            add_prescribed_fluxes(t, face_loads);
            loads_current = true;
          }
        rhs += face_loads;
      }
    if (has_dirichlet)
      {
        std::map<types::global_dof_index, double> g_dot;
        if (dirichlet_varies)
          g_dot = dirichlet_rates(t);
        if (!g_dot.empty() && !parameters.lumped_mass)
          {
            Vector rates(locally_owned_dofs, mpi_communicator), lift(locally_owned_dofs, mpi_communicator);
            for (const auto i : dirichlet_dofs)
              {
                const auto it = g_dot.find(i);
                rates(i)      = it == g_dot.end() ? 0. : it->second;
              }
            rates.compress(VectorOperation::insert);
            dirichlet_mass.vmult(lift, rates);
            rhs -= lift;
          }
        for (const auto i : dirichlet_dofs)
          {
            const auto it = g_dot.find(i);
            rhs(i)        = it == g_dot.end() ? 0. : mass_diagonal(i) * it->second;
          }
        rhs.compress(VectorOperation::insert);
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
    // The tangent of a linear problem (k independent of T, no radiation) does
    // not read T: no copy and ghost import of y, no values at the points
    // (the faces' convection reads the last ghosted field and only the
    // residual uses it). Every entry is the same number (cell_tangent).
    const bool tangent_of_linear = linear && tangent && !rhs;
    if (!tangent_of_linear)
      {
        Vector owned(y);
        hanging.distribute(owned);
        scratch_ghosted = owned;
      }
    const Vector &T = scratch_ghosted;

    std::map<types::global_dof_index, double> g_dot;
    if (rhs)
      g_dot = dirichlet_rates(t);
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

    const bool axi = parameters.axisymmetric;
    // The linear tangent of Q1 on a Q1 mapping (the reference one or
    // MappingQ1Eulerian): the cells from their moved vertices, no FEValues.
    std::unique_ptr<thermal::Q1Conduction<dim>> q1;
    const bool moved = current_mapping != nullptr;
    if (tangent_of_linear && fe.degree == 1 && (!moved || !moved_vertices.empty()))
      q1 = std::make_unique<thermal::Q1Conduction<dim>>(fe, quadrature);
    std::unique_ptr<thermal::TangentAdder> adder;
    if (tangent)
      adder = std::make_unique<thermal::TangentAdder>(*tangent, tangent_positions, tangent_positions_values,
                                                      triangulation.n_active_cells(),
                                                      fe.n_dofs_per_cell(), hanging);
    // No face has a tangent (no convection; radiation is not linear) and one
    // thread: a plain loop, without WorkStream's scratch (FEValues nobody
    // reads: ~40 % of the loop on two_blocks) and its std::function calls.
    if (q1 && !has_convection && MultithreadInfo::n_threads() == 1)
      add_q1_conduction<dim>(dof_handler, materials, moved ? &moved_vertices : nullptr, *q1, axi, *adder,
                             hanging, *tangent);
    else
      {
        const thermal::ScratchData<dim> scratch(
          get_mapping(), reference_mapping, fe, quadrature, face_quadrature,
          update_values | update_gradients | update_JxW_values | update_quadrature_points,
          coupling ? update_JxW_values | update_quadrature_points : update_default,
          update_values | update_JxW_values | update_quadrature_points);
        const FunctionParser<dim> *expression = source_function.get();

        auto worker = [&](const CellIterator &cell, thermal::ScratchData<dim> &s, thermal::CopyData &c) {
          const auto &m = materials.at(cell->material_id());
          if (q1 && m.dk_dT() == 0)
            {
              cell->get_dof_indices(c.dofs);
              c.cell_index = cell->active_cell_index();
              c.matrix     = 0;
              std::array<Point<dim>, thermal::Q1Conduction<dim>::n_vertices> x;
              for (unsigned int v = 0; v < x.size(); ++v)
                x[v] = moved ? moved_vertices[cell->vertex_index(v)] : cell->vertex(v);
              q1->add_cell_matrix(x, m.conductivity, axi, c.matrix);
              // Only convection and radiation have a tangent on a face.
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary())
                  {
                    const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
                    if (bc != boundary_conditions.boundaries.end() && !bc->second.temperature &&
                        (bc->second.h || bc->second.emissivity))
                      thermal::boundary_face<dim>(s, cell, f, bc->second, &T, axi, true, c);
                  }
              return;
            }
          c.cell_index = cell->active_cell_index();
          s.fe_values.reinit(cell);
          if (coupling)
            s.fe_reference.reinit(cell);
          cell->get_dof_indices(c.dofs);
          if (!tangent_of_linear)
            {
              s.fe_values.get_function_values(T, s.T);
              s.fe_values.get_function_gradients(T, s.grad_T);
            }
          thermal::fill_weights<dim>(s.fe_values, axi, s.weight);
          c.matrix = 0;
          c.vector = 0;
          bool any_g_dot = false;
          if (coupling)
            for (unsigned int j = 0; j < c.dofs.size(); ++j)
              {
                const auto it = g_dot.find(c.dofs[j]);
                s.g_dot(j)    = it == g_dot.end() ? 0. : it->second;
                any_g_dot     = any_g_dot || s.g_dot(j) != 0;
              }
          if (rhs)
            {
              thermal::VolumeSource::cell_rates<dim>(s, cell, expression, &heat_source,
                                                     any_g_dot ? m.density * m.heat_capacity : 0., axi);
              thermal::volume_residual(s, m, c);
            }
          if (tangent)
            thermal::Conduction::cell_tangent(s, m, c);
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const auto bc = boundary_conditions.boundaries.find(cell->face(f)->boundary_id());
                if (bc == boundary_conditions.boundaries.end() || bc->second.temperature)
                  continue;
                thermal::boundary_face<dim>(s, cell, f, bc->second, &T, axi, tangent != nullptr, c);
              }
        };
        auto copier = [&](const thermal::CopyData &c) {
          if (rhs)
            constraints.distribute_local_to_global(c.vector, c.dofs, *rhs);
          // The tangent keeps the columns of the Dirichlet dofs: f at a free dof
          // depends on the iterate's boundary values (K_IB y_B), and a stage's
          // Newton step moves those values when the boundary temperature changes
          // in time. Condensing them out (as `constraints` would) drops −γ K_IB δy_B
          // and, where ARKode takes one Newton step (a linear problem), leaves an
          // error ~ γ K_IB Δg: 646 K instead of <= 393 K on a strip heated from
          // 293 K at 100 K/s (tests/heat_dirichlet_ramp.py).
          if (tangent && !adder->add(c))
            hanging.distribute_local_to_global(c.matrix, c.dofs, *tangent);
        };
        for_owned_cells(dof_handler, worker, copier, scratch);
      }

    finish_assembly(t, y, g_dot, rhs, tangent);
  }

  template <int dim>
  void ThermalProblem<dim>::finish_assembly(const double t, const Vector &y,
                                            const std::map<types::global_dof_index, double> &g_dot,
                                            Vector *rhs, TrilinosWrappers::SparseMatrix *tangent)
  {
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
        // Constrained rows of f do not depend on T: empty rows.
        tangent->clear_rows(dirichlet_dofs);
        for (const auto i : locally_owned_dofs)
          if (hanging.is_constrained(i))
            tangent->set(i, i, 0.);
        tangent->compress(VectorOperation::insert);
        current_gamma = -1;
      }
  }

  template <int dim>
  typename ThermalProblem<dim>::AssembledSystem
  ThermalProblem<dim>::assemble_system(const double t, const Vector &T, const double gamma, Vector &f)
  {
    assemble_mass();
    operators_current = true;
    update_exchange_pattern();
    assemble(t, T, nullptr, &tangent_matrix);
    tangent_current = true;
    sources_current = false;
    f.reinit(locally_owned_dofs, mpi_communicator);
    assemble(t, T, &f, nullptr);
    if (gamma > 0)
      setup_newton(gamma);
    return {mass_matrix, tangent_matrix, newton_matrix};
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
