#pragma once

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Epetra_Map.h>

#include <string>
#include <vector>

namespace anvil
{
  /**
   * The system matrix on one process, its Epetra graph built straight from
   * the cells' rows (sorted columns of each dof, constraints condensed, as
   * DoFTools::make_sparsity_pattern gives them) and the contact couplings
   * (each group condensed like AffineConstraints::add_entries_local_to_global
   * does: a constrained dof stands for its masters and keeps its diagonal).
   * The rows go in by local index, already sorted and without repeats, so
   * Epetra neither translates nor sorts them; the graph is the one deal.II's
   * DynamicSparsityPattern route makes (@p map: the owned dofs' contiguous
   * map, row, column, domain and range alike). With @p release_rows the
   * caller keeps no rows: each goes once in the graph, before the values
   * are made.
   */
  void make_serial_matrix(std::vector<std::vector<dealii::types::global_dof_index>>       &cell_rows,
                          const std::vector<std::vector<dealii::types::global_dof_index>> &couplings,
                          const dealii::AffineConstraints<double>                        &constraints,
                          const Epetra_Map                                                &map,
                          dealii::TrilinosWrappers::SparseMatrix                          &matrix,
                          bool                                                             release_rows);

  /// "" if @p a and @p b have the same rows, columns and entries (local
  /// indices of one process), else the first difference, one line.
  std::string compare_graphs(const dealii::TrilinosWrappers::SparseMatrix &a,
                             const dealii::TrilinosWrappers::SparseMatrix &b);
} // namespace anvil
