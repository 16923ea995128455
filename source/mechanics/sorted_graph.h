// The Epetra graph whose rows go in sorted and without repeats, and the
// matrix made on it: the route make_serial_matrix (serial_matrix.cc, one
// process) and make_distributed_matrix (sparsity_rows.cc, several) share,
// private to source/mechanics.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>

namespace anvil
{
  /**
   * A graph whose rows the caller inserts sorted and without repeats:
   * FillComplete() then skips its per-row shell sort (Epetra keeps these
   * flags protected; deal.II's trilinos_sparse_matrix.cc derives from
   * Epetra_CrsGraph to set one the same way). Repeats are private to Epetra:
   * its merge pass stays, a linear scan.
   */
  class SortedGraph : public Epetra_CrsGraph
  {
  public:
    SortedGraph(const Epetra_Map &rows, const Epetra_Map &columns, const int *row_lengths)
      : Epetra_CrsGraph(Copy, rows, columns, row_lengths, true)
    {}
    void declare_sorted() { SetSorted(true); }
  };

  /**
   * @p graph (every row inserted, the caller's row arrays freed) completed on
   * @p map and @p matrix made on it: deal.II's matrix takes an Epetra matrix's
   * graph (reinit from the matrix, its values not copied), the one way in
   * without a sparsity pattern.
   */
  inline void matrix_on_graph(SortedGraph &graph, const Epetra_Map &map,
                              dealii::TrilinosWrappers::SparseMatrix &matrix)
  {
    graph.declare_sorted();
    graph.FillComplete(map, map);
    graph.OptimizeStorage();
    // deal.II's reinit reads only the graph, its maps and Filled() (the
    // graph's) from the matrix given and makes its own zeroed values: a View
    // matrix holds no values of its own. A Copy one held a second zeroed copy
    // of K's values while deal.II's were made: 648 B/DoF in 3D, the 1 M-DoF
    // run's resident peak (doc/memory.md, session 23).
    const Epetra_CrsMatrix on_graph(View, graph);
    matrix.reinit(on_graph, false);
  }
} // namespace anvil
