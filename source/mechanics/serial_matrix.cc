// The one-process system matrix from kept rows (serial_matrix.h).
#include <anvil/mechanics/serial_matrix.h>

#include "sorted_graph.h"

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <iterator>

namespace anvil
{
  using namespace dealii;

  void make_serial_matrix(std::vector<std::vector<types::global_dof_index>>       &cell_rows,
                          const std::vector<std::vector<types::global_dof_index>> &couplings,
                          const AffineConstraints<double>                        &constraints,
                          const Epetra_Map                                        &map,
                          TrilinosWrappers::SparseMatrix                          &matrix,
                          const bool                                               release_rows)
  {
    const unsigned int n = cell_rows.size();
    AssertThrow(static_cast<int>(n) == map.NumMyElements() && map.LinearMap() && map.MinMyGID() == 0,
                ExcMessage("make_serial_matrix: one process, dofs 0 .. n-1"));
    // The contact rows' extra columns: each group's dofs condensed (a
    // constrained dof gives its masters; AffineConstraints::make_sorted_row_list),
    // every one coupled with every one, and a constrained dof's diagonal.
    std::vector<std::vector<int>> extra(n);
    std::vector<int>              closure;
    for (const auto &group : couplings)
      {
        closure.clear();
        for (const auto i : group)
          if (const auto *masters = constraints.get_constraint_entries(i))
            {
              for (const auto &m : *masters)
                closure.push_back(m.first);
              extra[i].push_back(i);
            }
          else
            closure.push_back(i);
        std::sort(closure.begin(), closure.end());
        closure.erase(std::unique(closure.begin(), closure.end()), closure.end());
        for (const int r : closure)
          extra[r].insert(extra[r].end(), closure.begin(), closure.end());
      }

    // Each row merged with its extra columns straight into the graph (no
    // CRS copy of all rows beside the cells' rows: 324 B/DoF in 3D), the
    // cells' row freed once in when the caller keeps none.
    std::vector<int> lengths(n), columns;
    const auto       merge = [&](const unsigned int r) {
      columns.clear();
      const auto &more = extra[r];
      if (more.empty())
        columns.assign(cell_rows[r].begin(), cell_rows[r].end());
      else
        std::set_union(cell_rows[r].begin(), cell_rows[r].end(), more.begin(), more.end(),
                       std::back_inserter(columns));
    };
    for (unsigned int r = 0; r < n; ++r)
      {
        auto &more = extra[r];
        if (more.empty())
          lengths[r] = cell_rows[r].size();
        else
          {
            std::sort(more.begin(), more.end());
            more.erase(std::unique(more.begin(), more.end()), more.end());
            merge(r);
            lengths[r] = columns.size();
          }
      }
    SortedGraph graph(map, map, lengths.data());
    for (unsigned int r = 0; r < n; ++r)
      {
        merge(r);
        if (release_rows)
          std::vector<types::global_dof_index>().swap(cell_rows[r]);
        if (lengths[r] > 0)
          {
            const int ierr = graph.InsertMyIndices(r, lengths[r], columns.data());
            AssertThrow(ierr >= 0, ExcMessage("make_serial_matrix: Epetra InsertMyIndices " +
                                              std::to_string(ierr)));
          }
      }
    // The graph holds its copy: the rows' arrays go before the values come.
    if (release_rows)
      std::vector<std::vector<types::global_dof_index>>().swap(cell_rows);
    std::vector<std::vector<int>>().swap(extra);
    matrix_on_graph(graph, map, matrix);
  }

  std::string compare_graphs(const TrilinosWrappers::SparseMatrix &a,
                             const TrilinosWrappers::SparseMatrix &b)
  {
    const Epetra_CrsGraph &p = a.trilinos_matrix().Graph(), &q = b.trilinos_matrix().Graph();
    if (p.NumMyRows() != q.NumMyRows() || p.NumMyNonzeros() != q.NumMyNonzeros())
      return "rows " + std::to_string(p.NumMyRows()) + " and " + std::to_string(q.NumMyRows()) +
             ", entries " + std::to_string(p.NumMyNonzeros()) + " and " +
             std::to_string(q.NumMyNonzeros());
    if (!p.RowMap().SameAs(q.RowMap()) || !p.ColMap().SameAs(q.ColMap()))
      return "the row or column maps differ";
    for (int r = 0; r < p.NumMyRows(); ++r)
      {
        int  np = 0, nq = 0;
        int *cp = nullptr, *cq = nullptr;
        p.ExtractMyRowView(r, np, cp);
        q.ExtractMyRowView(r, nq, cq);
        if (np != nq || !std::equal(cp, cp + np, cq))
          return "row " + std::to_string(r) + " differs";
      }
    return "";
  }
} // namespace anvil
