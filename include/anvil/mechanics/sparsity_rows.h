#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <mpi.h>

#include <vector>

namespace anvil
{
  /**
   * The system matrix's rows from the locally owned cells, as
   * DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false)
   * gives them (each cell's dofs condensed like
   * AffineConstraints::add_entries_local_to_global: a constrained dof stands
   * for its masters and keeps its diagonal), without a DynamicSparsityPattern
   * (whose row look-ups cost 547 M instructions on the 48 k-DoF-per-body
   * contact strip at np 1, its loop over the cells 172 M).
   *
   * @p rows: first the owned rows in order (@p owned must be contiguous),
   * their columns sorted and without repeats; then the rows this process
   * touches but does not own, each as {row, its sorted columns...}.
   */
  template <int dim>
  void make_cell_rows(const dealii::DoFHandler<dim>                              &dof_handler,
                      const dealii::AffineConstraints<double>                    &constraints,
                      const dealii::IndexSet                                     &owned,
                      std::vector<std::vector<dealii::types::global_dof_index>> &rows);

  /**
   * The matrix on several processes from make_cell_rows()' rows and the
   * contact couplings (condensed as make_serial_matrix does): rows owned
   * elsewhere go to their owners, then the Epetra graph from the owned rows
   * by global indices, sorted — the graph (rows, column map, order) that
   * deal.II's route makes (SparsityTools::distribute_sparsity_pattern and
   * the matrix from the DynamicSparsityPattern), without that pattern.
   * Entries written into rows owned elsewhere go through Epetra_FECrsMatrix's
   * own off-process store (deal.II's route kept a separate matrix of them).
   * With @p release_rows the caller keeps no rows: each goes once copied,
   * before the graph and the values are made.
   */
  void make_distributed_matrix(std::vector<std::vector<dealii::types::global_dof_index>>       &cell_rows,
                               const std::vector<std::vector<dealii::types::global_dof_index>> &couplings,
                               const dealii::AffineConstraints<double>                        &constraints,
                               const dealii::IndexSet                                          &owned,
                               const MPI_Comm                                                   comm,
                               dealii::TrilinosWrappers::SparseMatrix                          &matrix,
                               bool                                                             release_rows);
} // namespace anvil
