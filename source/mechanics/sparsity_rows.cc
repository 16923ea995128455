// The system matrix's rows from the owned cells, and the matrix on several
// processes from each process's own rows (sparsity_rows.h).
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/sparsity_rows.h>

#include "sorted_graph.h"

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Util.h>

#include <algorithm>
#include <map>
#include <string>

namespace anvil
{
  using namespace dealii;
  using Index = types::global_dof_index;

  namespace
  {
    void sort_unique(std::vector<Index> &v)
    {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    }

    /**
     * @p dofs condensed as AffineConstraints::add_entries_local_to_global
     * (keep_constrained_entries = false) does: @p closure the unconstrained
     * dofs and the masters of the constrained ones, sorted without repeats;
     * @p diagonal the constrained dofs (each keeps its diagonal entry).
     */
    void condense(const std::vector<Index> &dofs, const AffineConstraints<double> &constraints,
                  std::vector<Index> &closure, std::vector<Index> &diagonal)
    {
      closure.clear();
      diagonal.clear();
      for (const auto i : dofs)
        if (constraints.is_constrained(i))
          {
            diagonal.push_back(i);
            if (const auto *masters = constraints.get_constraint_entries(i))
              for (const auto &m : *masters)
                closure.push_back(m.first);
          }
        else
          closure.push_back(i);
      sort_unique(closure);
    }

    /// A process's rows: the owned ones by position, the others by dof.
    struct Rows
    {
      Index                                first = 0;
      unsigned int                         cells_per_dof = 1; // a first touch reserves for them
      std::vector<std::vector<Index>>      mine;
      std::map<Index, std::vector<Index>> away;

      std::vector<Index> &operator[](const Index row)
      {
        return row - first < mine.size() ? mine[row - first] : away[row];
      }
      void add(const std::vector<Index> &closure, const std::vector<Index> &diagonal)
      {
        for (const auto r : closure)
          {
            auto &columns = (*this)[r];
            if (columns.empty())
              columns.reserve(cells_per_dof * closure.size());
            columns.insert(columns.end(), closure.begin(), closure.end());
          }
        for (const auto i : diagonal)
          (*this)[i].push_back(i);
      }
    };
  } // namespace

  template <int dim>
  void make_cell_rows(const DoFHandler<dim> &dof_handler, const AffineConstraints<double> &constraints,
                      const IndexSet &owned, std::vector<std::vector<Index>> &rows)
  {
    AssertThrow(owned.is_contiguous(), ExcMessage("make_cell_rows: owned dofs not contiguous"));
    Rows r;
    r.first         = owned.n_elements() > 0 ? *owned.begin() : 0;
    r.cells_per_dof = 1u << dim; // a vertex's cells in a structured mesh
    r.mine.resize(owned.n_elements());
    std::vector<Index> dofs, closure, diagonal;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          dofs.resize(cell->get_fe().n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          condense(dofs, constraints, closure, diagonal);
          r.add(closure, diagonal);
        }
    rows = std::move(r.mine);
    for (auto &columns : rows)
      sort_unique(columns);
    for (auto &[row, columns] : r.away)
      {
        sort_unique(columns);
        columns.insert(columns.begin(), row);
        rows.push_back(std::move(columns));
      }
  }

  void make_distributed_matrix(std::vector<std::vector<Index>>       &cell_rows,
                               const std::vector<std::vector<Index>> &couplings,
                               const AffineConstraints<double> &constraints, const IndexSet &owned,
                               const MPI_Comm comm, TrilinosWrappers::SparseMatrix &matrix,
                               const bool release_rows)
  {
    const unsigned int n_owned = owned.n_elements();
    AssertThrow(owned.is_contiguous() && cell_rows.size() >= n_owned,
                ExcMessage("make_distributed_matrix: rows as make_cell_rows gives them"));
    // What this process adds beyond its cells' owned rows.
    Rows extra;
    extra.first = n_owned > 0 ? *owned.begin() : 0;
    extra.mine.resize(n_owned);
    for (std::size_t k = n_owned; k < cell_rows.size(); ++k)
      extra.away[cell_rows[k][0]].assign(cell_rows[k].begin() + 1, cell_rows[k].end());
    std::vector<Index> closure, diagonal;
    for (const auto &group : couplings)
      {
        condense(group, constraints, closure, diagonal);
        extra.add(closure, diagonal);
      }

    // Rows owned elsewhere to their owners (each process's range from all),
    // as {row, n, columns...}.
    const unsigned int P = Utilities::MPI::n_mpi_processes(comm);
    const Index        range[2] = {extra.first, extra.first + n_owned};
    std::vector<Index> ranges(2 * P);
    int ierr = MPI_Allgather(range, 2, Utilities::MPI::mpi_type_id_for_type<Index>, ranges.data(), 2,
                             Utilities::MPI::mpi_type_id_for_type<Index>, comm);
    AssertThrowMPI(ierr);
    std::vector<std::vector<Index>> send(P);
    for (auto &[row, columns] : extra.away)
      {
        unsigned int p = 0;
        while (p < P && !(ranges[2 * p] <= row && row < ranges[2 * p + 1]))
          ++p;
        AssertThrow(p < P, ExcMessage("make_distributed_matrix: row " + std::to_string(row) +
                                      " owned by no process"));
        sort_unique(columns);
        send[p].push_back(row);
        send[p].push_back(columns.size());
        send[p].insert(send[p].end(), columns.begin(), columns.end());
      }
    std::vector<int> send_counts(P), receive_counts(P), send_offsets(P + 1, 0), receive_offsets(P + 1, 0);
    for (unsigned int p = 0; p < P; ++p)
      send_counts[p] = static_cast<int>(send[p].size());
    ierr = MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
    AssertThrowMPI(ierr);
    std::vector<Index> flat;
    for (unsigned int p = 0; p < P; ++p)
      {
        send_offsets[p + 1]    = send_offsets[p] + send_counts[p];
        receive_offsets[p + 1] = receive_offsets[p] + receive_counts[p];
        flat.insert(flat.end(), send[p].begin(), send[p].end());
      }
    std::vector<Index> received(receive_offsets[P]);
    ierr = MPI_Alltoallv(flat.data(), send_counts.data(), send_offsets.data(),
                         Utilities::MPI::mpi_type_id_for_type<Index>, received.data(),
                         receive_counts.data(), receive_offsets.data(),
                         Utilities::MPI::mpi_type_id_for_type<Index>, comm);
    AssertThrowMPI(ierr);
    for (std::size_t i = 0; i < received.size(); i += 2 + received[i + 1])
      {
        const Index row = received[i];
        AssertThrow(row - extra.first < n_owned, ExcMessage("make_distributed_matrix: a row not mine"));
        auto &columns = extra.mine[row - extra.first];
        columns.insert(columns.end(), received.begin() + i + 2, received.begin() + i + 2 + received[i + 1]);
      }

    // The owned rows: cells' and extra columns merged.
    std::vector<int> offsets(n_owned + 1, 0), columns, lengths(n_owned);
    for (unsigned int k = 0; k < n_owned; ++k)
      {
        auto &more = extra.mine[k];
        if (more.empty())
          columns.insert(columns.end(), cell_rows[k].begin(), cell_rows[k].end());
        else
          {
            sort_unique(more);
            std::set_union(cell_rows[k].begin(), cell_rows[k].end(), more.begin(), more.end(),
                           std::back_inserter(columns));
          }
        offsets[k + 1] = columns.size();
        lengths[k]     = offsets[k + 1] - offsets[k];
        if (release_rows)
          std::vector<Index>().swap(cell_rows[k]);
      }
    // The cells' rows go before the graph and the values come.
    if (release_rows)
      std::vector<std::vector<Index>>().swap(cell_rows);
    std::vector<std::vector<Index>>().swap(extra.mine);

    // deal.II's graph on several processes is made without a column map:
    // Epetra's FillComplete makes it (Epetra_CrsGraph::MakeColMap), then
    // translates and sorts every row (127 M instructions per rank on the
    // 48 k-DoF-per-body strip at np 2). The same map made here: the owned
    // columns present in the domain map's order, then the others in order of
    // first appearance (rows in order, each row ascending, as deal.II inserts
    // them) grouped by owner with Epetra's own sort over the owners; the rows
    // then go in by local index, sorted.
    const int          first = static_cast<int>(extra.first);
    std::vector<int>   local(n_owned, -1), remote;
    std::map<int, int> remote_at; // global -> position in `remote`
    for (const int c : columns)
      if (static_cast<unsigned int>(c - first) < n_owned)
        local[c - first] = 0;
      else if (remote_at.emplace(c, static_cast<int>(remote.size())).second)
        remote.push_back(c);
    std::vector<int> column_gids;
    for (unsigned int k = 0; k < n_owned; ++k)
      if (local[k] == 0)
        {
          local[k] = static_cast<int>(column_gids.size());
          column_gids.push_back(first + static_cast<int>(k));
        }
    const int        n_local_columns = static_cast<int>(column_gids.size());
    std::vector<int> owners(remote.size());
    for (std::size_t i = 0; i < remote.size(); ++i)
      {
        unsigned int p = 0;
        while (!(ranges[2 * p] <= static_cast<Index>(remote[i]) && static_cast<Index>(remote[i]) < ranges[2 * p + 1]))
          ++p;
        owners[i] = static_cast<int>(p);
      }
    if (!remote.empty())
      {
        int *companions[1] = {remote.data()};
        Epetra_Util::Sort(true, static_cast<int>(remote.size()), owners.data(), 0, nullptr, 1, companions);
      }
    for (std::size_t i = 0; i < remote.size(); ++i)
      remote_at[remote[i]] = n_local_columns + static_cast<int>(i);
    column_gids.insert(column_gids.end(), remote.begin(), remote.end());
    const Epetra_Map map = owned.make_trilinos_map(comm, false);
    const Epetra_Map column_map(-1, static_cast<int>(column_gids.size()), column_gids.data(), 0, map.Comm());
    for (unsigned int k = 0; k < n_owned; ++k)
      {
        int *const begin = columns.data() + offsets[k], *const end = columns.data() + offsets[k + 1];
        bool       away  = false;
        for (int *c = begin; c != end; ++c)
          if (static_cast<unsigned int>(*c - first) < n_owned)
            *c = local[*c - first];
          else
            {
              *c   = remote_at[*c];
              away = true;
            }
        if (away)
          std::sort(begin, end);
      }
    SortedGraph graph(map, column_map, lengths.data());
    for (unsigned int k = 0; k < n_owned; ++k)
      if (lengths[k] > 0)
        {
          const int e = graph.InsertMyIndices(static_cast<int>(k), lengths[k], columns.data() + offsets[k]);
          AssertThrow(e >= 0, ExcMessage("make_distributed_matrix: Epetra InsertMyIndices " +
                                         std::to_string(e)));
        }
    std::vector<int>().swap(columns);
    matrix_on_graph(graph, map, matrix);
  }

#define INSTANTIATE(dim)                                                                         \
  template void make_cell_rows<dim>(const DoFHandler<dim> &, const AffineConstraints<double> &, \
                                    const IndexSet &, std::vector<std::vector<Index>> &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
