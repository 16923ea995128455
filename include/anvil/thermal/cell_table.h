#pragma once

// What the heat-balance loops (heat content, source power, the audit's
// integrals, the temperatures at the mechanics' points) read per locally owned
// cell, computed once per mesh (reference configuration) or per configuration
// (current one) instead of an FEValues reinit per cell and call, and the
// positions of each cell's dofs in a ghosted vector's local array instead of
// a global-to-local look-up per value read.
//
// The numbers are those an FEValues loop over all owned cells in cell order
// with the same mapping, quadrature and flags computes (the table is filled
// by exactly that loop), so sums over them are bit for bit the sums of the
// loops they replace.

#include <Epetra_BlockMap.h>

#include <memory>
#include <vector>

namespace anvil
{
  namespace thermal
  {
    struct CellTable
    {
      unsigned int n_q = 0, n_dofs = 0;
      /// Row of each active cell (by active_cell_index), −1 where not owned
      /// or not in the table (the current configuration's holds the cells
      /// with mechanical sources: thermal/current_weights.h computes others).
      std::vector<int> row;
      /// JxW and 2π x₀ (axisymmetric weight; 1 otherwise) at (row, q), and
      /// the quadrature points (dim doubles each) where asked for.
      std::vector<double> JxW, axis_weight, points;
      /// Position of dof j of row r in the local array of a vector with
      /// `map`'s layout, at r · n_dofs + j (dofs in the cell's order).
      std::vector<int> local_dofs;
      /// Shape function j at point q (j · n_q + q) where values were asked
      /// for: FE_Q's do not depend on the cell.
      std::vector<double> shape;
      /// The layout local_dofs refers to (a ghosted vector's).
      std::unique_ptr<Epetra_BlockMap> map;

      bool empty() const { return row.empty(); }
      void clear() { *this = CellTable(); }
      /// Whether @p vector_map is the layout of local_dofs (same data, or the
      /// same owned and ghost elements in the same order). Local on purpose:
      /// Epetra's SameAs/PointSameAs reduce over all processes. O(n) where the
      /// maps do not share their data: ask once per loop over the cells, not
      /// per cell.
      bool reads(const Epetra_BlockMap &vector_map) const
      {
        if (!map)
          return false;
        if (vector_map.DataPtr() == map->DataPtr())
          return true;
        const int n = map->NumMyElements();
        if (vector_map.NumMyElements() != n)
          return false;
        for (int i = 0; i < n; ++i)
          if (vector_map.GID64(i) != map->GID64(i))
            return false;
        return true;
      }
    };
  } // namespace thermal
} // namespace anvil
