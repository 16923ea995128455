// ThermalProblem: the heat-balance integrals (boundary flows, sources, heat
// content) and the temperature at points. Serial loops: these are sums of
// doubles whose order a threaded loop would change.
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/kernels.h>
#include <anvil/thermal/thermal_problem.h>

#include "current_weights.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;
  using thermal::stefan_boltzmann;

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
    // Insulated everywhere (the boundary list is the same on every
    // process): no face loop, no FEFaceValues on the moving mapping.
    if (power.empty())
      return power;
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
    // One loop for both weight sources: the configuration's table (no
    // FEValues per cell) and, for thermal-only scenes, an FEValues; the sums
    // are the same products in the same order (s · JxW · ring weight).
    double power = 0;
    auto   sum   = [&](auto &&reinit, auto &&point, auto &&weighted) {
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            if (!source_function && thermal::zero_on_cell<dim>(heat_source, cell, quadrature.size()))
              continue;
            reinit(cell);
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                double s = source_function ? source_function->value(point(q)) : 0.;
                if (heat_source)
                  s += heat_source(cell, q);
                power += weighted(s, q);
              }
          }
    };
    if (current_mapping)
      {
        thermal::CurrentWeights<dim> w([this]() -> const thermal::CellTable & { return *current_cells(); },
                                       get_mapping(), fe, quadrature, parameters.axisymmetric);
        sum([&](const auto &cell) { w.reinit(cell); }, [&](const unsigned int q) { return w.point(q); },
            [&](const double s, const unsigned int q) { return s * w.JxW[q] * w.axis_weight[q]; });
      }
    else
      {
        FEValues<dim> fe_values(get_mapping(), fe, quadrature, update_JxW_values | update_quadrature_points);
        sum([&](const auto &cell) { fe_values.reinit(cell); },
            [&](const unsigned int q) { return fe_values.quadrature_point(q); },
            [&](const double s, const unsigned int q) {
              const double x0 = fe_values.quadrature_point(q)[0];
              return s * fe_values.JxW(q) * (parameters.axisymmetric ? 2 * numbers::PI * x0 : 1.);
            });
      }
    return Utilities::MPI::sum(power, mpi_communicator);
  }

  template <int dim>
  double ThermalProblem<dim>::heat_content(const Vector &T) const
  {
    // ∫ ρ c T dv = ∫ ρ₀ c T dV (mass conservation).
    const auto &table = reference_cells();
    if (table.reads(T.trilinos_vector().Map()))
      {
        // FEValues::get_function_values' sums (zero values skipped), from the table.
        const double       *values = T.trilinos_vector()[0];
        const unsigned int  n_q = table.n_q, n_dofs = table.n_dofs;
        std::vector<double> T_q(n_q);
        double              H = 0;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const unsigned int r = table.row[cell->active_cell_index()];
              std::fill(T_q.begin(), T_q.end(), 0.);
              for (unsigned int j = 0; j < n_dofs; ++j)
                {
                  const double value = values[table.local_dofs[r * n_dofs + j]];
                  if (value == 0)
                    continue;
                  for (unsigned int q = 0; q < n_q; ++q)
                    T_q[q] += value * table.shape[j * n_q + q];
                }
              const auto &m = materials.at(cell->material_id());
              for (unsigned int q = 0; q < n_q; ++q)
                H += m.density * m.heat_capacity * T_q[q] * table.JxW[r * n_q + q] *
                     table.axis_weight[r * n_q + q];
            }
        return Utilities::MPI::sum(H, mpi_communicator);
      }
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
    if (current_mapping)
      {
        thermal::CurrentWeights<dim> w([this]() -> const thermal::CellTable & { return *current_cells(); },
                                       get_mapping(), fe, quadrature, parameters.axisymmetric);
        double                       total = 0;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (thermal::zero_on_cell<dim>(source, cell, quadrature.size()))
                continue;
              w.reinit(cell);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                total += source(cell, q) * w.JxW[q] * w.axis_weight[q];
            }
        return Utilities::MPI::sum(total, mpi_communicator);
      }
    FEValues<dim> fe_values(get_mapping(), fe, quadrature, update_JxW_values | update_quadrature_points);
    double        total = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (thermal::zero_on_cell<dim>(source, cell, quadrature.size()))
            continue;
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
    // step_balance computed it for this very field (NaN: not since it changed).
    if (!std::isnan(solution_heat_content))
      return solution_heat_content;
    return heat_content(temperature_ghosted);
  }

  template <int dim>
  bool ThermalProblem<dim>::point_values_by_table() const
  {
    const auto &table = reference_cells();
    return table.reads(temperature_ghosted.trilinos_vector().Map()) &&
           table.reads(old_temperature_ghosted.trilinos_vector().Map());
  }

  template <int dim>
  void ThermalProblem<dim>::temperature_at_quadrature_points(
    const typename Triangulation<dim>::active_cell_iterator &cell, const Quadrature<dim> &q,
    std::vector<double> &T_new, std::vector<double> &T_old, const bool by_table) const
  {
    const typename DoFHandler<dim>::active_cell_iterator dof_cell(&triangulation, cell->level(),
                                                                  cell->index(), &dof_handler);
    if (!point_values || !(q == *point_quadrature))
      {
        point_quadrature = std::make_unique<Quadrature<dim>>(q);
        point_values = std::make_unique<FEValues<dim>>(reference_mapping, fe, *point_quadrature, update_values);
        point_values->reinit(dof_cell);
      }
    // FE_Q's values at the points do not depend on the cell (nor on the
    // mapping): Σ_j T_j φ_j(x_q) from the first cell's table, summed as
    // FEValues::get_function_values does (same bits), without its reinit.
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    // The dof values by their positions in the local arrays (the reference
    // table's), not by a global look-up each.
    const auto &table = reference_cells();
    const bool  fast  = by_table && dof_cell->is_locally_owned();
    std::vector<types::global_dof_index> dofs(n_dofs);
    if (!fast)
      dof_cell->get_dof_indices(dofs);
    const int *local = fast ? &table.local_dofs[table.row[dof_cell->active_cell_index()] * n_dofs] : nullptr;
    auto values = [&](const Vector &T, std::vector<double> &out) {
      out.assign(q.size(), 0.);
      const double *array = T.trilinos_vector()[0];
      for (unsigned int j = 0; j < n_dofs; ++j)
        {
          const double value = fast ? array[local[j]] : T(dofs[j]);
          if (value == 0)
            continue;
          for (unsigned int k = 0; k < q.size(); ++k)
            out[k] += value * point_values->shape_value(j, k);
        }
    };
    values(temperature_ghosted, T_new);
    values(old_temperature_ghosted, T_old);
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
