// The copier of the mechanical assembly (include/anvil/mechanics/cell_scatter.h):
// where each cell's entries go, by the cheapest path that gives the same bits.
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/cell_scatter.h>

#include <Epetra_BlockMap.h>
#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <array>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;
    using TrilinosIndex = TrilinosWrappers::types::int_type;

    bool same_local_map(const Epetra_BlockMap &a, const Epetra_BlockMap &b)
    {
      return a.DataPtr() == b.DataPtr() ||
             (a.NumMyElements() == b.NumMyElements() &&
              std::equal(a.MyGlobalElements(), a.MyGlobalElements() + a.NumMyElements(),
                         b.MyGlobalElements()));
    }

    template <int dim>
    CellScatter<dim>::CellScatter(const AssemblyMapping<dim>       &mapping,
                                  const AffineConstraints<double> &constraints,
                                  const AssemblyTargets           &targets,
                                  const unsigned int               n_dofs,
                                  const bool                       dynamic)
      : mapping(mapping)
      , constraints(constraints)
      , targets(targets)
      , n_dofs(n_dofs)
      , dynamic(dynamic)
      , owned_map(targets.rhs.trilinos_vector().Map())
    {
      if (targets.matrix)
        {
          // deal.II 9.4 gives only const access to the Epetra matrix; ours is not const.
          matrix = const_cast<Epetra_CrsMatrix *>(&targets.matrix->trilinos_matrix());
          if (matrix->ExtractCrsDataPointers(row_start, row_columns, matrix_values) != 0)
            matrix_values = nullptr; // storage not optimised: add by local indices
        }
      rhs_values      = owned_values(targets.rhs);
      internal_values = owned_values(targets.internal);
      external_values = owned_values(targets.external);
      inertia_values  = owned_values(targets.inertia);
      // Whether a cell has a constrained dof, once per set of constrained dofs
      // (the predictor's and the iterations' alternate: both kept).
      constrained_cells = mapping.constrained_cells(constraints.get_lines());
    }

    template <int dim>
    double *CellScatter<dim>::owned_values(Vector &v) const
    {
      return same_local_map(v.trilinos_vector().Map(), owned_map) ? v.trilinos_vector()[0] :
                                                                    nullptr;
    }

    // The cell's dofs in the owned vectors (null if one is owned elsewhere).
    template <int dim>
    const int *CellScatter<dim>::owned_indices(const CopyData &copy) const
    {
      int *const own = mapping.owned_vector_indices(copy.cell_index, n_dofs, copy.dof_indices, owned_map);
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (own[i] < 0)
          return nullptr;
      return own;
    }

    // The slots of the cell's matrix entries in its rows (null: add otherwise).
    template <int dim>
    const unsigned char *CellScatter<dim>::matrix_slots(const CopyData &copy, const int *own) const
    {
      if (!matrix_values)
        return nullptr;
      unsigned char *const slot = mapping.matrix_slots(copy.cell_index, n_dofs);
      if (!slot)
        return nullptr;
      if (slot[0] == AssemblyMapping<dim>::slot_unknown && !find_slots(copy, own, slot))
        slot[0] = AssemblyMapping<dim>::slot_refused;
      return slot[0] != AssemblyMapping<dim>::slot_refused ? slot : nullptr;
    }

    // The cell's local column numbers once, in increasing order, then each
    // row walked once beside them (FillComplete sorts a row's columns; an
    // entry the walk passed is searched for). Found anew for every cell at
    // each of the tube's ~180 new patterns: a search per entry cost 5400
    // instructions per cell, this ~1500. The row is the owned vectors' entry
    // own[i] (checked), so that a slot within it is all that is kept.
    template <int dim>
    bool CellScatter<dim>::find_slots(const CopyData &copy, const int *own, unsigned char *slot) const
    {
      std::array<std::pair<int, unsigned int>, 64> column;
      AssertIndexRange(n_dofs, column.size() + 1);
      for (unsigned int j = 0; j < n_dofs; ++j)
        if ((column[j] = {matrix->LCID(static_cast<TrilinosIndex>(copy.dof_indices[j])), j})
              .first < 0)
          return false;
      std::sort(column.begin(), column.begin() + n_dofs);
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const int row = matrix->LRID(static_cast<TrilinosIndex>(copy.dof_indices[i]));
          if (row < 0 || row != own[i])
            return false;
          const int *const begin = row_columns + row_start[row];
          const int *const end   = row_columns + row_start[row + 1];
          const int       *at    = begin;
          for (unsigned int j = 0; j < n_dofs; ++j)
            {
              while (at != end && *at < column[j].first)
                ++at;
              if (at == end || *at != column[j].first)
                at = std::find(begin, end, column[j].first);
              if (at == end || at - begin >= AssemblyMapping<dim>::slot_refused)
                return false;
              slot[i * n_dofs + column[j].second] = static_cast<unsigned char>(at - begin);
            }
        }
      return true;
    }

    template <int dim>
    bool CellScatter<dim>::add_by_local_indices(const CopyData &copy)
    {
      int *const local_rows = mapping.local_indices(copy.cell_index, n_dofs);
      int *const local_cols = local_rows + n_dofs;
      if (local_rows[0] == -2)
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const auto g  = static_cast<TrilinosIndex>(copy.dof_indices[i]);
            local_rows[i] = matrix->LRID(g);
            local_cols[i] = matrix->LCID(g);
          }
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (local_rows[i] < 0 || local_cols[i] < 0)
          return false;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const int ierr =
            matrix->SumIntoMyValues(local_rows[i], n_dofs, &copy.matrix(i, 0), local_cols);
          AssertThrow(ierr == 0, ExcTrilinosError(ierr));
        }
      targets.rhs.add(copy.dof_indices, copy.rhs);
      return true;
    }

    // The cell's K and −R where no constraint is involved; false: not added.
    template <int dim>
    bool CellScatter<dim>::add_unconstrained(const CopyData &copy, const int *own)
    {
      if (AssemblyMapping<dim>::is_constrained(constrained_cells[copy.cell_index], copy.dof_indices, n_dofs,
                                               constraints))
        return false;
      if (!matrix)
        {
          if (!own || !rhs_values)
            return false;
          for (unsigned int i = 0; i < n_dofs; ++i)
            rhs_values[own[i]] += copy.rhs(i);
          return true;
        }
      if (const unsigned char *slot = own && rhs_values ? matrix_slots(copy, own) : nullptr)
        {
          const double *K = &copy.matrix(0, 0);
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              double *const row = matrix_values + row_start[own[i]];
              for (unsigned int j = 0; j < n_dofs; ++j)
                row[slot[i * n_dofs + j]] += K[i * n_dofs + j];
            }
          for (unsigned int i = 0; i < n_dofs; ++i)
            rhs_values[own[i]] += copy.rhs(i);
          return true;
        }
      return add_by_local_indices(copy);
    }

    // A force vector: by owned local index, or deal.II's add.
    template <int dim>
    void CellScatter<dim>::add_force(Vector &v, double *values, const int *own,
                                     const CopyData &copy, const dealii::Vector<double> &local)
    {
      if (own && values)
        for (unsigned int i = 0; i < n_dofs; ++i)
          values[own[i]] += local(i);
      else
        v.add(copy.dof_indices, local);
    }

    template <int dim>
    void CellScatter<dim>::add(const CopyData &copy)
    {
      const int *const own = owned_indices(copy);
      if (dynamic)
        add_force(targets.inertia, inertia_values, own, copy, copy.inertia);
      if (!add_unconstrained(copy, own))
        {
          if (matrix)
            constraints.distribute_local_to_global(copy.matrix, copy.rhs, copy.dof_indices,
                                                   *targets.matrix, targets.rhs);
          else
            constraints.distribute_local_to_global(copy.rhs, copy.dof_indices, targets.rhs);
        }
      add_force(targets.internal, internal_values, own, copy, copy.internal);
      add_force(targets.external, external_values, own, copy, copy.external);
    }

    ANVIL_INSTANTIATE_CLASS(CellScatter)
  } // namespace MechanicsAssembly
} // namespace anvil
