// The coarse spaces below the first (geometric_coarse_space.h): level ℓ + 1
// from level ℓ as level 1 from the fine mesh, on the box path (halved
// subdivisions) or on the hierarchy path (the cells' grandparents, …).
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe.h>

#include <anvil/core/instantiate.h>

#include "geometric_coarse_space.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <limits>
#include <map>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// Box path: the dofs of @p level (lexicographic dim·node + component) as the finer grid of the next.
    template <int dim>
    bool coarsen_box_level(CoarseSpace &level)
    {
      std::array<unsigned int, dim> cells;
      for (unsigned int d = 0; d < dim; ++d)
        {
          cells[d] = level.box_cells[d];
          if (cells[d] < 2 || cells[d] % 2 != 0)
            return false;
        }
      const Epetra_Map                                &map = *level.coarse_map;
      std::vector<coarse_space_internal::GridDof<dim>> fine(map.NumMyElements());
      for (int row = 0; row < map.NumMyElements(); ++row)
        {
          const int    gid  = map.GID(row);
          unsigned int node = gid / dim;
          auto        &f    = fine[row];
          f.row             = row;
          f.component       = gid % dim;
          f.constrained     = level.box_constrained[gid] != 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              f.index[d] = node % (cells[d] + 1);
              node /= cells[d] + 1;
            }
        }
      level.coarser        = std::make_unique<CoarseSpace>(coarse_space_internal::coarsen_box<dim>(fine, cells, map, map));
      level.coarser->depth = level.depth + 1;
      return true;
    }

    /// The child number of @p cell in its parent.
    template <class Iterator>
    unsigned int child_number(const Iterator &cell)
    {
      const auto parent = cell->parent();
      for (unsigned int k = 0; k < parent->n_children(); ++k)
        if (parent->child(k)->index() == cell->index())
          return k;
      AssertThrow(false, ExcInternalError());
      return 0;
    }

    /// Vertex @p v of the active @p cell is a vertex of its ancestor @p k
    /// generations up: the cell and its ancestors below that one are each
    /// their parent's child @p v (hexahedral refinement puts the parent's
    /// vertex v in child v, at its vertex v).
    template <int dim>
    bool is_node(typename DoFHandler<dim>::cell_iterator cell, const unsigned int v, const unsigned int k)
    {
      for (unsigned int a = 0; a < k; ++a, cell = cell->parent())
        if (child_number(cell) != v)
          return false;
      return true;
    }

    template <int dim>
    typename DoFHandler<dim>::cell_iterator ancestor(typename DoFHandler<dim>::cell_iterator cell, const unsigned int k)
    {
      for (unsigned int a = 0; a < k; ++a)
        cell = cell->parent();
      return cell;
    }

    /// Every active cell on one level >= @p generations (a uniform hierarchy that deep).
    template <int dim>
    bool has_generations(const DoFHandler<dim> &dof_handler, const unsigned int generations)
    {
      unsigned int lowest = std::numeric_limits<unsigned int>::max(), highest = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            lowest  = std::min(lowest, static_cast<unsigned int>(cell->level()));
            highest = std::max(highest, static_cast<unsigned int>(cell->level()));
          }
      const MPI_Comm comm = dof_handler.get_communicator();
      lowest              = Utilities::MPI::min(lowest, comm);
      highest             = Utilities::MPI::max(highest, comm);
      return lowest >= generations && lowest == highest;
    }

    /// (ancestor's CellId, its vertex, component) → the coarse dof there (−k − 2: constrained).
    using NodeKey = std::array<unsigned int, 6>;

    /// Every process's (key, corner, component, id) records (7 ints each), as one map.
    std::map<NodeKey, int> gather(const std::vector<int> &mine, const MPI_Comm comm)
    {
      const int        n_here = mine.size();
      const unsigned   np     = Utilities::MPI::n_mpi_processes(comm);
      std::vector<int> counts(np), offsets(np + 1, 0);
      AssertThrowMPI(MPI_Allgather(&n_here, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
      for (unsigned int p = 0; p < np; ++p)
        offsets[p + 1] = offsets[p] + counts[p];
      std::vector<int> all(offsets[np]);
      AssertThrowMPI(MPI_Allgatherv(mine.data(), n_here, MPI_INT, all.data(), counts.data(), offsets.data(), MPI_INT, comm));
      std::map<NodeKey, int> published;
      for (std::size_t k = 0; k + 7 <= all.size(); k += 7)
        published[NodeKey{{static_cast<unsigned int>(all[k]), static_cast<unsigned int>(all[k + 1]),
                           static_cast<unsigned int>(all[k + 2]), static_cast<unsigned int>(all[k + 3]),
                           static_cast<unsigned int>(all[k + 4]), static_cast<unsigned int>(all[k + 5])}}] = all[k + 6];
      return published;
    }

    /**
     * Hierarchy path: the next space's nodes are the vertices of the cells'
     * ancestors depth + 1 generations up; a coarse dof is the fine dof there
     * (its owner, its Dirichlet status), numbered as level 1's. P's row of a
     * dof of @p level (at vertex v of ancestor Q, depth generations up) is the
     * FE's prolongation matrix of Q's child number in its parent G. G's far
     * vertices may lie beyond the ghost layer (one fine cell): each process
     * publishes, for every cell around a node it owns, (G's CellId, corner,
     * component) → coarse dof, gathered on all processes (the coarse levels
     * are ≤ 1/64 of the fine dofs).
     */
    template <int dim>
    bool coarsen_hierarchy_level(const DoFHandler<dim> &dof_handler, const AffineConstraints<double> &constraints,
                                 const Epetra_Map &rows, CoarseSpace &level)
    {
      const unsigned int depth = level.depth;
      if (!has_generations(dof_handler, depth + 1))
        return false;
      const MPI_Comm            comm  = dof_handler.get_communicator();
      const FiniteElement<dim> &fe    = dof_handler.get_fe();
      const IndexSet           &owned = dof_handler.locally_owned_dofs();

      std::vector<types::global_dof_index> nodes; // owned fine dofs at the next space's nodes
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            if (is_node<dim>(cell, v, depth + 1))
              for (unsigned int c = 0; c < dim; ++c)
                if (owned.is_element(cell->vertex_dof_index(v, c)))
                  nodes.push_back(cell->vertex_dof_index(v, c));
      auto next                 = std::make_unique<CoarseSpace>();
      next->depth               = depth + 1;
      const unsigned int first  = coarse_space_internal::number_coarse_nodes(nodes, comm, rows, *next);
      const unsigned int n_mine = nodes.size();
      for (unsigned int i = 0; i < n_mine; ++i)
        next->fine_nodes.emplace_back(rows.LID(static_cast<int>(nodes[i])), first + i);
      // The signed id of an owned fine dof at a node, −1 elsewhere.
      const auto id_of = [&](const types::global_dof_index dof) -> long long {
        const auto it = std::lower_bound(nodes.begin(), nodes.end(), dof);
        if (it == nodes.end() || *it != dof)
          return -1;
        const long long k = first + (it - nodes.begin());
        return constraints.is_constrained(dof) ? -k - 2 : k;
      };

      // Published: every cell around an owned node (owned or ghost: the
      // owner of a dof sees all the cells at its vertex) names its ancestor.
      std::vector<int> mine;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int v : cell->vertex_indices())
            if (owned.is_element(cell->vertex_dof_index(v, 0)) && is_node<dim>(cell, v, depth + 1))
              {
                const auto key = ancestor<dim>(cell, depth + 1)->id().template to_binary<dim>();
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    mine.insert(mine.end(), key.begin(), key.end());
                    mine.push_back(v);
                    mine.push_back(c);
                    mine.push_back(static_cast<int>(id_of(cell->vertex_dof_index(v, c))));
                  }
              }
      const std::map<NodeKey, int> published = gather(mine, comm);
      mine                                   = std::vector<int>();

      // This level's dof of each owned fine dof at its nodes.
      std::vector<int> level_dof(rows.NumMyElements(), -1);
      for (const auto &[row, k] : depth == 1 ? level.injection : level.fine_nodes)
        level_dof[row] = k;

      const Epetra_Map   &level_map = *level.coarse_map;
      std::vector<bool>   seen(level_map.NumMyElements(), false);
      std::vector<int>    columns;
      std::vector<double> values;
      next->P = std::make_unique<Epetra_CrsMatrix>(Copy, level_map, 1 << dim);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            if (is_node<dim>(cell, v, depth))
              {
                const auto         Q   = ancestor<dim>(cell, depth);
                const unsigned int m   = child_number(Q);
                const auto         key = Q->parent()->id().template to_binary<dim>();
                const FullMatrix<double> &R = fe.get_prolongation_matrix(m);
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const types::global_dof_index dof = cell->vertex_dof_index(v, c);
                    if (!owned.is_element(dof))
                      continue;
                    const int k = level_dof[rows.LID(static_cast<int>(dof))];
                    AssertThrow(k >= 0, ExcMessage("geometric coarse space: a node without a coarse dof"));
                    const int row = level_map.LID(k);
                    if (seen[row])
                      continue;
                    seen[row]          = true;
                    const long long me = id_of(dof);
                    if (me != -1)
                      next->injection.emplace_back(row, static_cast<int>(me >= 0 ? me : -me - 2));
                    columns.clear();
                    values.clear();
                    // As level 1: a constrained dof keeps 1 at its own coarse
                    // dof (if at a node), a free one drops the constrained ones.
                    if (constraints.is_constrained(dof))
                      {
                        if (me != -1)
                          {
                            columns.push_back(static_cast<int>(me >= 0 ? me : -me - 2));
                            values.push_back(1.);
                          }
                      }
                    else
                      {
                        const unsigned int i = fe.component_to_system_index(c, v);
                        for (const unsigned int w : cell->vertex_indices())
                          {
                            const unsigned int j = fe.component_to_system_index(c, w);
                            if (R(i, j) == 0)
                              continue;
                            const auto it = published.find(NodeKey{{key[0], key[1], key[2], key[3], w, c}});
                            AssertThrow(it != published.end(),
                                        ExcMessage("geometric coarse space: a grandparent's vertex without a coarse dof"));
                            if (it->second >= 0)
                              {
                                columns.push_back(it->second);
                                values.push_back(R(i, j));
                              }
                          }
                      }
                    if (!columns.empty())
                      AssertThrow(next->P->InsertGlobalValues(k, columns.size(), values.data(), columns.data()) == 0,
                                  ExcMessage("geometric coarse space: P's insertion failed"));
                  }
              }
      // The owner of a dof owns a cell at its vertex: every owned row was seen.
      AssertThrow(std::count(seen.begin(), seen.end(), true) == level_map.NumMyElements(),
                  ExcMessage("geometric coarse space: a coarse dof without a cell"));
      AssertThrow(next->P->FillComplete(*next->coarse_map, level_map) == 0,
                  ExcMessage("geometric coarse space: P's FillComplete failed"));
      level.coarser = std::move(next);
      return true;
    }
  } // namespace

  template <int dim>
  unsigned int add_coarse_levels(const DoFHandler<dim> &dof_handler, const AffineConstraints<double> &constraints,
                                 const TrilinosWrappers::SparseMatrix &K, CoarseSpace &first,
                                 const unsigned int max_levels, const unsigned int min_rows)
  {
    unsigned int levels = 2;
    for (CoarseSpace *level = &first; levels < max_levels && level->n_coarse_dofs >= min_rows;
         level = level->coarser.get(), ++levels)
      {
        const bool made = level->box_cells[0] > 0 ?
                            coarsen_box_level<dim>(*level) :
                            coarsen_hierarchy_level(dof_handler, constraints, K.trilinos_matrix().RowMap(), *level);
        if (!made)
          break;
      }
    return levels;
  }

#define INSTANTIATE(dim)                                                                                     \
  template unsigned int add_coarse_levels(const DoFHandler<dim> &, const AffineConstraints<double> &,        \
                                          const TrilinosWrappers::SparseMatrix &, CoarseSpace &, unsigned int, \
                                          unsigned int);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
