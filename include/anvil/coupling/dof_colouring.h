#pragma once
// Distance-2 colouring of the columns of a finite-difference Jacobian
// (Curtis, Powell & Reid 1974), generic over what couples rows and columns:
// "cells", each a list of columns and the rows (links) they reach.
#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <vector>

namespace anvil
{
  using DofList  = std::vector<dealii::types::global_dof_index>;
  using CellDofs = std::vector<DofList>;

  /**
   * Greedy colouring of @p n_columns columns: two columns share a colour only
   * if no cell holding one (in @p columns) shares a link (in @p links, same
   * cell index) with a cell holding the other, so no row sees two
   * perturbations of one colour. A "cell" may be a mesh cell or any group of
   * dofs that couple (a contact node with the face below it). Deterministic:
   * every process colouring the same lists gets the same colours.
   */
  std::vector<unsigned int> colour_columns(const CellDofs &columns, const CellDofs &links,
                                           std::size_t n_columns, std::size_t n_links,
                                           unsigned int &n_colours);

  /// Every process's list, concatenated in rank order (collective).
  CellDofs gather_cells(const CellDofs &local, MPI_Comm comm);
} // namespace anvil
