// ThermalProblem: the per-cell tables of the balance loops
// (include/anvil/thermal/cell_table.h).
#include <deal.II/base/numbers.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/kernels.h>
#include <anvil/thermal/thermal_problem.h>

#include "q1_conduction.h"

#include <array>
#include <functional>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// Fill @p table by the loop the balance functions ran themselves: one
    /// FEValues over the locally owned cells in order (cell similarity, where
    /// the mapping uses it, then follows the same sequence of cells: the
    /// reference table has all of them), those @p include accepts.
    template <int dim>
    void fill_table(thermal::CellTable &table, const Mapping<dim> &mapping, const FiniteElement<dim> &fe,
                    const Quadrature<dim> &quadrature, const UpdateFlags flags,
                    const DoFHandler<dim> &dofs, const TrilinosWrappers::MPI::Vector &layout,
                    const bool axisymmetric, const bool with_points,
                    const std::function<bool(const typename DoFHandler<dim>::active_cell_iterator &)> &include)
    {
      table.clear();
      table.n_q    = quadrature.size();
      table.n_dofs = fe.n_dofs_per_cell();
      table.row.assign(dofs.get_triangulation().n_active_cells(), -1);
      const Epetra_BlockMap &map = layout.trilinos_vector().Map();
      table.map                  = std::make_unique<Epetra_BlockMap>(map);
      FEValues<dim>                        fe_values(mapping, fe, quadrature, flags);
      std::vector<types::global_dof_index> indices(table.n_dofs);
      int                                  rows = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned() && include(cell))
          {
            table.row[cell->active_cell_index()] = rows++;
            fe_values.reinit(cell);
            if (rows == 1 && (flags & update_values))
              for (unsigned int j = 0; j < table.n_dofs; ++j)
                for (unsigned int q = 0; q < table.n_q; ++q)
                  table.shape.push_back(fe_values.shape_value(j, q));
            for (unsigned int q = 0; q < table.n_q; ++q)
              {
                const Point<dim> &x = fe_values.quadrature_point(q);
                table.JxW.push_back(fe_values.JxW(q));
                table.axis_weight.push_back(axisymmetric ? 2 * numbers::PI * x[0] : 1.);
                if (with_points)
                  for (unsigned int d = 0; d < dim; ++d)
                    table.points.push_back(x[d]);
              }
            cell->get_dof_indices(indices);
            for (const auto i : indices)
              {
                const int local = map.LID(static_cast<TrilinosWrappers::types::int_type>(i));
                AssertThrow(local >= 0, ExcMessage("a cell's dof is not in the ghosted temperature's layout"));
                table.local_dofs.push_back(local);
              }
          }
    }

    /// The current configuration's table of a Q1 mapping from the moved
    /// vertices (Q1Conduction::cell_weights), every owned cell: no
    /// MappingQ1Eulerian, which interpolates each cell's vertices with an
    /// FEValues of the mechanics (the tube to 0.25 ms: 90 M instructions per
    /// 19 configurations). Round-off from the FEValues numbers, the same
    /// Jacobians as the conduction tangent.
    template <int dim>
    void fill_table_q1(thermal::CellTable &table, const std::vector<Point<dim>> &moved_vertices,
                       const Quadrature<dim> &quadrature, const unsigned int n_dofs,
                       const DoFHandler<dim> &dofs, const TrilinosWrappers::MPI::Vector &layout,
                       const bool axisymmetric, const thermal::CellTable &reference)
    {
      table.clear();
      table.n_q    = quadrature.size();
      table.n_dofs = n_dofs;
      table.row.assign(dofs.get_triangulation().n_active_cells(), -1);
      const Epetra_BlockMap &map = layout.trilinos_vector().Map();
      table.map                  = std::make_unique<Epetra_BlockMap>(map);
      std::size_t n_cells = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        n_cells += cell->is_locally_owned();
      table.JxW.reserve(n_cells * table.n_q);
      table.axis_weight.reserve(n_cells * table.n_q);
      table.points.reserve(n_cells * table.n_q * dim);
      // The reference table has every owned cell in this order, its dofs in
      // this layout: the positions are the same (a look-up per dof each
      // configuration cost ~4.5 M instructions per 79 on two_blocks).
      const bool same_dofs = reference.n_dofs == n_dofs && reference.reads(map) &&
                             reference.local_dofs.size() == n_cells * n_dofs;
      if (same_dofs)
        table.local_dofs = reference.local_dofs;
      // FE_Q(1)'s shape functions are the Q1 mapping's (built once: its
      // constructor costs ~0.4 M instructions, more than the table).
      static const FE_Q<dim>               linear(1);
      const thermal::Q1Conduction<dim>     geometry(linear, quadrature);
      std::vector<types::global_dof_index> indices(n_dofs);
      std::array<Point<dim>, thermal::Q1Conduction<dim>::n_vertices> x;
      int rows = 0;
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            table.row[cell->active_cell_index()] = rows++;
            for (unsigned int v = 0; v < x.size(); ++v)
              x[v] = moved_vertices[cell->vertex_index(v)];
            const std::size_t k = table.JxW.size();
            table.JxW.resize(k + table.n_q);
            table.axis_weight.resize(k + table.n_q);
            table.points.resize((k + table.n_q) * dim);
            geometry.cell_weights(x, axisymmetric, &table.JxW[k], &table.axis_weight[k], &table.points[k * dim]);
            if (same_dofs)
              continue;
            cell->get_dof_indices(indices);
            for (const auto i : indices)
              {
                const int local = map.LID(static_cast<TrilinosWrappers::types::int_type>(i));
                AssertThrow(local >= 0, ExcMessage("a cell's dof is not in the ghosted temperature's layout"));
                table.local_dofs.push_back(local);
              }
          }
    }
  } // namespace

  template <int dim>
  const thermal::CellTable &ThermalProblem<dim>::reference_cells() const
  {
    if (reference_table.empty())
      fill_table<dim>(reference_table, reference_mapping, fe, quadrature,
                      update_values | update_JxW_values | update_quadrature_points, dof_handler,
                      temperature_ghosted, parameters.axisymmetric, false, [](const auto &) { return true; });
    return reference_table;
  }

  template <int dim>
  const thermal::CellTable *ThermalProblem<dim>::current_cells() const
  {
    if (!current_mapping)
      return nullptr;
    if (current_table.empty() && !moved_vertices.empty())
      fill_table_q1<dim>(current_table, moved_vertices, quadrature, fe.n_dofs_per_cell(), dof_handler,
                         temperature_ghosted, parameters.axisymmetric, reference_cells());
    else if (current_table.empty())
      fill_table<dim>(current_table, *current_mapping, fe, quadrature,
                      update_JxW_values | update_quadrature_points, dof_handler, temperature_ghosted,
                      parameters.axisymmetric, true, [this](const CellIterator &cell) {
                        // The cells the sources' integrals visit (CurrentWeights computes others).
                        return heat_source && !thermal::zero_on_cell<dim>(heat_source, cell, quadrature.size());
                      });
    return &current_table;
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
