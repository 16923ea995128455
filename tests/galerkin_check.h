// The comparisons the geometric coarse space tests share (one process): a
// coarse operator from Galerkin products against the stiffness anvil
// assembles on the coarser mesh itself (nested Q1 spaces and exact
// quadrature: Galerkin = rediscretisation), the coarse dofs matched through
// an index map; and two Epetra matrices entry by entry.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace anvil_test
{
  struct GalerkinDifference
  {
    /// max |A_c − K_c| over the free coarse dofs, relative to max |K_c|.
    double free = 0;
    /// max |A_c(i, j)|, i ≠ j, i or j constrained, relative to max |K_c|.
    double constrained_coupling = 0;
  };

  /// @p inverse[k]: the row of @p Kc of coarse dof k.
  inline GalerkinDifference compare_to_rediscretisation(const Epetra_CrsMatrix                      &Ac,
                                                        const std::vector<int>                      &inverse,
                                                        const dealii::TrilinosWrappers::SparseMatrix &Kc,
                                                        const dealii::AffineConstraints<double>     &constraints)
  {
    const unsigned int         N = Kc.m();
    dealii::FullMatrix<double> galerkin(N, N);
    for (int row = 0; row < Ac.NumMyRows(); ++row)
      {
        int     entries;
        double *values;
        int    *columns;
        Ac.ExtractMyRowView(row, entries, values, columns);
        for (int k = 0; k < entries; ++k)
          galerkin(inverse[Ac.RowMap().GID(row)], inverse[Ac.ColMap().GID(columns[k])]) += values[k];
      }
    double             scale = 0;
    GalerkinDifference d;
    for (unsigned int i = 0; i < N; ++i)
      for (unsigned int j = 0; j < N; ++j)
        {
          const double kc = Kc.el(i, j);
          scale           = std::max(scale, std::abs(kc));
          if (!constraints.is_constrained(i) && !constraints.is_constrained(j))
            d.free = std::max(d.free, std::abs(galerkin(i, j) - kc));
          else if (i != j)
            d.constrained_coupling = std::max(d.constrained_coupling, std::abs(galerkin(i, j)));
        }
    d.free /= scale;
    d.constrained_coupling /= scale;
    return d;
  }

  /// max |A − B| / max |A| over the entries of two matrices on the same rows.
  inline double relative_difference(const Epetra_CrsMatrix &A, const Epetra_CrsMatrix &B)
  {
    double scale = 0, difference = 0;
    for (int row = 0; row < A.NumMyRows(); ++row)
      {
        std::map<int, double> entries;
        int                   n;
        double               *values;
        int                  *columns;
        A.ExtractMyRowView(row, n, values, columns);
        for (int k = 0; k < n; ++k)
          {
            entries[A.ColMap().GID(columns[k])] += values[k];
            scale = std::max(scale, std::abs(values[k]));
          }
        B.ExtractMyRowView(B.RowMap().LID(A.RowMap().GID(row)), n, values, columns);
        for (int k = 0; k < n; ++k)
          entries[B.ColMap().GID(columns[k])] -= values[k];
        for (const auto &[column, value] : entries)
          difference = std::max(difference, std::abs(value));
      }
    return difference / scale;
  }

  /// A position (to 1e-6) and a component, as a map key.
  template <int dim>
  std::pair<std::array<long, dim>, unsigned int> position_key(const dealii::Point<dim> &x, const unsigned int c)
  {
    std::array<long, dim> k;
    for (unsigned int d = 0; d < dim; ++d)
      k[d] = std::lround(x[d] * 1e6);
    return {k, c};
  }

  /// Position and component of every dof of @p dof_handler (Q1, one process).
  template <int dim>
  std::vector<std::pair<dealii::Point<dim>, unsigned int>> dof_positions(const dealii::DoFHandler<dim> &dof_handler)
  {
    std::vector<std::pair<dealii::Point<dim>, unsigned int>> at(dof_handler.n_dofs());
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int c = 0; c < dim; ++c)
          at[cell->vertex_dof_index(v, c)] = {cell->vertex(v), c};
    return at;
  }
} // namespace anvil_test
