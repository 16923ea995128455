#pragma once

// Adds a cell's heat tangent into the Trilinos matrix (thermal_assembly.cc,
// private header). A cell without hanging dofs whose rows are all owned adds
// its matrix by local row and column numbers, looked up once per dof
// (Epetra's SumIntoGlobalValues, what AffineConstraints calls, looks up every
// column of every row): the same one addition per entry, in cell order (as
// the mechanics' copier, source/mechanics/assembly.cc). Further, such a
// cell's entries are found in Epetra's CRS value array once per pattern
// (ThermalProblem::tangent_positions) and added there: no row search.

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Epetra_CrsMatrix.h>

#include <anvil/thermal/assembly_data.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace anvil::thermal
{
  class TangentAdder
  {
  public:
    /// @p positions (n_cells · n_dofs², by active cell index) and
    /// @p positions_values (the value array they index) persist between
    /// assemblies; they are reset here when the matrix's value array moved.
    TangentAdder(dealii::TrilinosWrappers::SparseMatrix &tangent, std::vector<int> &positions,
                 const double *&positions_values, const std::size_t n_cells, const unsigned int n_dofs,
                 const dealii::AffineConstraints<double> &hanging)
      : matrix(const_cast<Epetra_CrsMatrix &>(tangent.trilinos_matrix()))
      , positions(positions)
      , n_dofs(n_dofs)
      , hanging(hanging)
      , local_rows(n_dofs)
      , local_cols(n_dofs)
    {
      if (matrix.ExtractCrsDataPointers(row_start, row_columns, values) != 0)
        values = nullptr;
      // A new pattern's value array may come back at a freed one's
      // address: the reinit sites also forget the positions.
      if (values && (values != positions_values || positions.size() != n_cells * n_dofs * n_dofs))
        {
          positions.assign(n_cells * n_dofs * n_dofs, -1);
          positions_values = values;
        }
    }

    /// Adds @p c.matrix at @p c.dofs of cell @p c.cell_index; false if the
    /// cell must go through AffineConstraints (hanging dofs, rows not owned).
    bool add(const CopyData &c)
    {
      int *p = values ? &positions[std::size_t(c.cell_index) * n_dofs * n_dofs] : nullptr;
      if (p && p[0] >= 0)
        {
          for (unsigned int i = 0; i < n_dofs; ++i)
            for (unsigned int j = 0; j < n_dofs; ++j)
              values[p[i * n_dofs + j]] += c.matrix(i, j);
          return true;
        }
      if (p && p[0] == -2)
        return false;
      for (unsigned int i = 0; i < c.dofs.size(); ++i)
        {
          const auto g  = static_cast<dealii::TrilinosWrappers::types::int_type>(c.dofs[i]);
          local_rows[i] = matrix.LRID(g);
          local_cols[i] = matrix.LCID(g);
          if (hanging.is_constrained(c.dofs[i]) || local_rows[i] < 0 || local_cols[i] < 0)
            {
              if (p)
                p[0] = -2;
              return false;
            }
        }
      if (p)
        for (unsigned int i = 0; i < n_dofs; ++i)
          for (unsigned int j = 0; j < n_dofs; ++j)
            {
              const int *begin = row_columns + row_start[local_rows[i]],
                        *end   = row_columns + row_start[local_rows[i] + 1];
              const int *found = std::find(begin, end, local_cols[j]);
              AssertThrow(found != end, dealii::ExcMessage("a cell's entry is not in the heat tangent's pattern"));
              p[i * n_dofs + j] = int(found - row_columns);
            }
      for (unsigned int i = 0; i < c.dofs.size(); ++i)
        {
          const int ierr = matrix.SumIntoMyValues(local_rows[i], c.dofs.size(), &c.matrix(i, 0),
                                                  local_cols.data());
          AssertThrow(ierr == 0, dealii::ExcTrilinosError(ierr));
        }
      return true;
    }

  private:
    Epetra_CrsMatrix                        &matrix;
    std::vector<int>                        &positions;
    const unsigned int                       n_dofs;
    const dealii::AffineConstraints<double> &hanging;
    std::vector<int>                         local_rows, local_cols;
    int                                     *row_start = nullptr, *row_columns = nullptr;
    double                                  *values    = nullptr;
  };
} // namespace anvil::thermal
