#pragma once

// JxW, the ring weight 2πx₀ (1 unless axisymmetric) and the points of a cell
// on the current configuration, read from ThermalProblem's current cell table
// where it holds the cell (include/anvil/thermal/cell_table.h), else from an
// FEValues of the same mapping, quadrature and flags made on first need. The
// moving mappings (MappingQ1Eulerian, MappingQEulerian) compute every cell
// afresh (no cell similarity), so both give the same numbers bit for bit.
// A Q1 mechanics' table (from the moved vertices) holds every owned cell:
// the FEValues here is then never made. The table is asked for at the first
// cell a loop reinits, not before: a loop whose cells all skip (no
// mechanical source anywhere: two_blocks, 36 M instructions of 611 M in the
// heat step) builds none.

#include <deal.II/base/numbers.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/thermal/cell_table.h>

#include <functional>
#include <memory>
#include <vector>

namespace anvil
{
  namespace thermal
  {
    template <int dim>
    class CurrentWeights
    {
    public:
      /// @p table_of: the configuration's table, built on its first call.
      CurrentWeights(std::function<const CellTable &()> table_of, const dealii::Mapping<dim> &mapping,
                     const dealii::FiniteElement<dim> &fe, const dealii::Quadrature<dim> &quadrature,
                     const bool axisymmetric)
        : table_of(std::move(table_of))
        , mapping(mapping)
        , fe(fe)
        , quadrature(quadrature)
        , axisymmetric(axisymmetric)
        , own_JxW(quadrature.size())
        , own_axis(quadrature.size())
        , own_points(quadrature.size() * dim)
      {}

      void reinit(const typename dealii::DoFHandler<dim>::active_cell_iterator &cell)
      {
        if (!table)
          table = &table_of();
        const int r = table->row[cell->active_cell_index()];
        if (r >= 0)
          {
            const std::size_t k = std::size_t(r) * quadrature.size();
            JxW                 = &table->JxW[k];
            axis_weight         = &table->axis_weight[k];
            points              = &table->points[k * dim];
            return;
          }
        if (!fe_values)
          fe_values = std::make_unique<dealii::FEValues<dim>>(
            mapping, fe, quadrature, dealii::update_JxW_values | dealii::update_quadrature_points);
        fe_values->reinit(cell);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const dealii::Point<dim> &x = fe_values->quadrature_point(q);
            own_JxW[q]                  = fe_values->JxW(q);
            own_axis[q]                 = axisymmetric ? 2 * dealii::numbers::PI * x[0] : 1.;
            for (unsigned int d = 0; d < dim; ++d)
              own_points[q * dim + d] = x[d];
          }
        JxW         = own_JxW.data();
        axis_weight = own_axis.data();
        points      = own_points.data();
      }

      dealii::Point<dim> point(const unsigned int q) const
      {
        dealii::Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = points[q * dim + d];
        return x;
      }

      const double *JxW = nullptr, *axis_weight = nullptr, *points = nullptr;

    private:
      std::function<const CellTable &()>            table_of;
      const CellTable                              *table = nullptr;
      const dealii::Mapping<dim>                   &mapping;
      const dealii::FiniteElement<dim>             &fe;
      const dealii::Quadrature<dim>                &quadrature;
      const bool                                    axisymmetric;
      std::vector<double>                           own_JxW, own_axis, own_points;
      std::unique_ptr<dealii::FEValues<dim>>        fe_values;
    };
  } // namespace thermal
} // namespace anvil
