// The assembly's rows owned by other processes, sent to their owners in one
// exchange (off_process_rows.h).
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/affine_constraints.templates.h>

#include <anvil/core/instantiate.h>

#include "off_process_rows.h"

#include <Epetra_BlockMap.h>
#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <string>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    OffProcessRows<dim>::OffProcessRows(const AssemblyMapping<dim>       &mapping,
                                        const AffineConstraints<double> &constraints,
                                        Epetra_CrsMatrix                 *matrix,
                                        const std::array<double *, 4>    &vectors,
                                        const Epetra_BlockMap            &owned_map,
                                        const unsigned int                n_dofs,
                                        const bool                        dynamic,
                                        const MPI_Comm                    comm,
                                        OffProcessPlan                   &plan)
      : mapping(mapping)
      , constraints(constraints)
      , matrix(matrix)
      , vectors(vectors)
      , owned_map(owned_map)
      , n_dofs(n_dofs)
      , dynamic(dynamic)
      , comm(comm)
      , constrained_cells(mapping.constrained_cells(constraints.get_lines()))
      , plan(plan)
    {
      AssertThrow(vectors[0] && vectors[1] && vectors[2] && (!dynamic || vectors[3]),
                  ExcInternalError());
      // The rows of the last assembly stay (and the slots into them): their
      // sums start again from nothing.
      for (Row &r : plan.rows)
        {
          r.vectors = {};
          for (auto &e : r.entries)
            e.second = -0.;
        }
    }

    template <int dim>
    bool OffProcessRows<dim>::takes(const CopyData &copy) const
    {
      // The same per-cell records CellScatter keeps (owned local indices,
      // whether a dof is constrained).
      const int *const own = mapping.owned_vector_indices(copy.cell_index, n_dofs, copy.dof_indices, owned_map);
      if (AssemblyMapping<dim>::is_constrained(constrained_cells[copy.cell_index], copy.dof_indices, n_dofs,
                                               constraints))
        return true;
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (own[i] < 0)
          return true;
      return false;
    }

    template <int dim>
    unsigned int OffProcessRows<dim>::remote_row(const Index row)
    {
      const auto [at, added] = plan.row_at.emplace(row, static_cast<unsigned int>(plan.rows.size()));
      if (added)
        {
          plan.rows.push_back(Row{static_cast<int>(row), {}, {}});
          ++plan.version;
        }
      return at->second;
    }

    template <int dim>
    double &OffProcessRows<dim>::remote_entry(Row &row, const int c)
    {
      auto      &entries = row.entries;
      const auto at      = std::lower_bound(entries.begin(), entries.end(), c,
                                       [](const auto &e, const int c) { return e.first < c; });
      if (at != entries.end() && at->first == c)
        return at->second;
      ++plan.version;
      return entries.insert(at, {c, -0.})->second;
    }

    template <int dim>
    void OffProcessRows<dim>::add_remote(const Index row, const unsigned int n, const Index *cols,
                                         const double *values)
    {
      Row &r = plan.rows[remote_row(row)];
      for (unsigned int j = 0; j < n; ++j)
        remote_entry(r, static_cast<int>(cols[j])) += values[j];
    }

    // Per row of the cell owned elsewhere, the pointers to its entries' sums
    // (made first, then pointed to: making one may move a row's others).
    // A new row or entry makes every cell's pointers stale: they are found
    // again (the first assembly of a pattern; the next ones find all made).
    template <int dim>
    std::pair<double *const *, const unsigned int *> OffProcessRows<dim>::cell_slots(const CopyData &copy,
                                                                                 const int *own)
    {
      if (plan.slots_version == plan.version)
        if (const auto at = plan.cell_slots.find(copy.cell_index); at != plan.cell_slots.end())
          return {plan.slots.data() + at->second.first, plan.slot_rows.data() + at->second.second};
      const Index *const dofs = copy.dof_indices.data();
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (own[i] < 0)
          {
            Row &r = plan.rows[remote_row(dofs[i])];
            for (unsigned int j = 0; j < n_dofs; ++j)
              remote_entry(r, static_cast<int>(dofs[j]));
          }
      if (plan.slots_version != plan.version)
        {
          plan.cell_slots.clear();
          plan.slots.clear();
          plan.slot_rows.clear();
          plan.slots_version = plan.version;
        }
      const std::pair<std::size_t, std::size_t> offsets(plan.slots.size(), plan.slot_rows.size());
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (own[i] < 0)
          {
            const unsigned int k = remote_row(dofs[i]);
            plan.slot_rows.push_back(k);
            for (unsigned int j = 0; j < n_dofs; ++j)
              plan.slots.push_back(&remote_entry(plan.rows[k], static_cast<int>(dofs[j])));
          }
      plan.cell_slots[copy.cell_index] = offsets;
      return {plan.slots.data() + offsets.first, plan.slot_rows.data() + offsets.second};
    }

    // As deal.II's SparseMatrix::add puts an owned row (its elide_zero_values
    // = false path): the same addition, the same bits.
    template <int dim>
    void OffProcessRows<dim>::add_owned(const int, const Index row, const unsigned int n,
                                        const Index *cols, const double *values)
    {
      columns.resize(n);
      for (unsigned int j = 0; j < n; ++j)
        columns[j] = static_cast<int>(cols[j]);
      const int ierr = matrix->Epetra_CrsMatrix::SumIntoGlobalValues(
        static_cast<int>(row), static_cast<int>(n), values, columns.data());
      AssertThrow(ierr == 0, ExcMessage("OffProcessRows: an entry outside the matrix's pattern (" +
                                        std::to_string(ierr) + ")"));
    }

    template <int dim>
    double &OffProcessRows<dim>::vector_entry(const unsigned int k, const Index row)
    {
      const int lid = owned_map.LID(static_cast<int>(row));
      return lid >= 0 ? vectors[k][lid] : plan.rows[remote_row(row)].vectors[k];
    }

    template <int dim>
    typename OffProcessRows<dim>::MatrixTarget::size_type OffProcessRows<dim>::MatrixTarget::m() const
    {
      return static_cast<size_type>(rows->owned_map.NumGlobalElements());
    }

    template <int dim>
    void OffProcessRows<dim>::MatrixTarget::add(const size_type row, const size_type n,
                                                const size_type *cols, const double *values, bool, bool)
    {
      const int lid = rows->owned_map.LID(static_cast<int>(row));
      if (lid >= 0)
        rows->add_owned(lid, row, n, cols, values);
      else
        rows->add_remote(row, n, cols, values);
    }

    template <int dim>
    typename OffProcessRows<dim>::VectorTarget::size_type OffProcessRows<dim>::VectorTarget::size() const
    {
      return static_cast<size_type>(rows->owned_map.NumGlobalElements());
    }

    template <int dim>
    double &OffProcessRows<dim>::VectorTarget::operator()(const size_type i)
    {
      return rows->vector_entry(k, i);
    }

    template <int dim>
    void OffProcessRows<dim>::add(const CopyData &copy)
    {
      // CellScatter::add's order: M a, K and −R, f_int, f_ext.
      if (constrained_cells[copy.cell_index])
        {
          const auto add_vector = [&](const unsigned int k, const Vector<double> &local) {
            for (unsigned int i = 0; i < n_dofs; ++i)
              vector_entry(k, copy.dof_indices[i]) += local(i);
          };
          if (dynamic)
            add_vector(3, copy.inertia);
          VectorTarget rhs{this, 0};
          if (matrix)
            {
              MatrixTarget K{this};
              constraints.distribute_local_to_global(copy.matrix, copy.rhs, copy.dof_indices, K, rhs);
            }
          else
            constraints.distribute_local_to_global(copy.rhs, copy.dof_indices, rhs);
          add_vector(1, copy.internal);
          add_vector(2, copy.external);
        }
      else
        {
          // Rows owned elsewhere by the plan's slots (no search per entry:
          // 0.134 G instructions per assembly on the 3D 16³ block's busier
          // rank), the rows' vector entries by their places in the plan.
          const int *const own = mapping.owned_vector_indices(copy.cell_index, n_dofs);
          const auto [slots, slot_rows] = cell_slots(copy, own);
          const auto add_vector = [&, slot_rows = slot_rows](const unsigned int k, const Vector<double> &local) {
            unsigned int r = 0;
            for (unsigned int i = 0; i < n_dofs; ++i)
              if (own[i] >= 0)
                vectors[k][own[i]] += local(i);
              else
                plan.rows[slot_rows[r++]].vectors[k] += local(i);
          };
          if (dynamic)
            add_vector(3, copy.inertia);
          if (matrix)
            {
              // Owned rows by local row and column numbers (the cache
              // CellScatter::add_by_local_indices keeps): no global look-up
              // per entry (SumIntoGlobalValues: 157 M instructions on the
              // 3D 16³ block's interface per rank, 13 assemblies).
              int *const local_rows = mapping.local_indices(copy.cell_index, n_dofs);
              int *const local_cols = local_rows + n_dofs;
              if (local_rows[0] == -2)
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const int g   = static_cast<int>(copy.dof_indices[i]);
                    local_rows[i] = matrix->LRID(g);
                    local_cols[i] = matrix->LCID(g);
                  }
              double *const *slot = slots;
              for (unsigned int i = 0; i < n_dofs; ++i)
                if (own[i] < 0)
                  {
                    const double *const K = &copy.matrix(i, 0);
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      *slot[j] += K[j];
                    slot += n_dofs;
                  }
                else
                  {
                    AssertThrow(local_rows[i] >= 0, ExcInternalError());
                    const int ierr =
                      matrix->SumIntoMyValues(local_rows[i], static_cast<int>(n_dofs), &copy.matrix(i, 0), local_cols);
                    AssertThrow(ierr == 0, ExcMessage("OffProcessRows: an entry outside the matrix's "
                                                      "pattern (" + std::to_string(ierr) + ")"));
                  }
            }
          add_vector(0, copy.rhs);
          add_vector(1, copy.internal);
          add_vector(2, copy.external);
        }
    }

    template <int dim>
    void OffProcessRows<dim>::exchange()
    {
      // Each process's range of owned rows (contiguous: checked by the caller).
      const unsigned int P     = Utilities::MPI::n_mpi_processes(comm);
      const int          n_own = owned_map.NumMyElements();
      const int          range[2] = {n_own > 0 ? owned_map.MinMyGID() : 0,
                                     n_own > 0 ? owned_map.MaxMyGID() + 1 : 0};
      std::vector<int>   ranges(2 * P);
      int ierr = MPI_Allgather(range, 2, MPI_INT, ranges.data(), 2, MPI_INT, comm);
      AssertThrowMPI(ierr);

      // Per process: the plan's version (OffProcessPlan: which rows and
      // entries, in which order), then per row: row, n, the four vector
      // entries, then n (column, value) pairs, all as doubles (indices and
      // versions < 2^31 are exact). Without the matrix no entries are sent.
      std::vector<std::vector<double>> send(P);
      for (const Row &r : plan.rows)
        {
          unsigned int p = 0;
          while (p < P && !(ranges[2 * p] <= r.row && r.row < ranges[2 * p + 1]))
            ++p;
          AssertThrow(p < P, ExcMessage("OffProcessRows: row " + std::to_string(r.row) +
                                        " owned by no process"));
          auto &s = send[p];
          if (s.empty())
            s.push_back(plan.version);
          const std::size_t n = matrix ? r.entries.size() : 0;
          s.push_back(r.row);
          s.push_back(static_cast<double>(n));
          s.insert(s.end(), r.vectors.begin(), r.vectors.end());
          for (std::size_t j = 0; j < n; ++j)
            {
              s.push_back(r.entries[j].first);
              s.push_back(r.entries[j].second);
            }
        }
      std::vector<int> send_counts(P), receive_counts(P), send_offsets(P + 1, 0),
        receive_offsets(P + 1, 0);
      for (unsigned int p = 0; p < P; ++p)
        send_counts[p] = static_cast<int>(send[p].size());
      ierr = MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
      AssertThrowMPI(ierr);
      std::vector<double> flat;
      for (unsigned int p = 0; p < P; ++p)
        {
          send_offsets[p + 1]    = send_offsets[p] + send_counts[p];
          receive_offsets[p + 1] = receive_offsets[p] + receive_counts[p];
          flat.insert(flat.end(), send[p].begin(), send[p].end());
        }
      std::vector<double> received(receive_offsets[P]);
      ierr = MPI_Alltoallv(flat.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE,
                           received.data(), receive_counts.data(), receive_offsets.data(),
                           MPI_DOUBLE, comm);
      AssertThrowMPI(ierr);

      // Added in the senders' order of processes, each row as it was sent.
      if (plan.received_version.size() != P)
        {
          plan.received_version.assign(P, 0);
          plan.received_positions.assign(P, {});
        }
      for (unsigned int p = 0; p < P; ++p)
        if (receive_counts[p] > 0)
          add_received(p, static_cast<unsigned int>(received[receive_offsets[p]]),
                       received.data() + receive_offsets[p] + 1, received.data() + receive_offsets[p + 1]);
    }

    // A sender's rows: by the positions found when its plan last changed
    // (per row its local row and entry count, then each entry's index in the
    // CRS values), else by global look-ups, finding them (with the matrix).
    // Each entry gets one addition, as SumIntoGlobalValues would make it.
    template <int dim>
    void OffProcessRows<dim>::add_received(const unsigned int sender, const unsigned int version,
                                           const double *begin, const double *end)
    {
      int    *row_start = nullptr, *row_columns = nullptr;
      double *values    = nullptr;
      if (matrix && matrix->ExtractCrsDataPointers(row_start, row_columns, values) != 0)
        values = nullptr; // storage not optimised: by global look-ups
      std::vector<int> &positions = plan.received_positions[sender];
      const bool known = plan.received_version[sender] == version && !positions.empty();
      const bool find  = !known && values;
      if (find)
        positions.clear();
      std::size_t q = 0;
      for (const double *at = begin; at < end;)
        {
          const int          row = static_cast<int>(at[0]);
          const unsigned int n   = static_cast<unsigned int>(at[1]);
          int                lid;
          if (known)
            {
              lid = positions[q];
              AssertThrow(static_cast<unsigned int>(positions[q + 1]) == n || n == 0,
                          ExcInternalError());
            }
          else
            {
              lid = owned_map.LID(row);
              AssertThrow(lid >= 0, ExcMessage("OffProcessRows: received row " + std::to_string(row) +
                                               " not owned here"));
            }
          for (unsigned int k = 0; k < 4; ++k)
            if (vectors[k])
              vectors[k][lid] += at[2 + k];
          const double *entry = at + 6;
          at += 6 + 2 * std::size_t(n);
          if (known)
            {
              const unsigned int count = static_cast<unsigned int>(positions[q + 1]);
              if (n > 0)
                for (unsigned int j = 0; j < n; ++j)
                  values[positions[q + 2 + j]] += entry[2 * j + 1];
              q += 2 + count;
              continue;
            }
          if (find)
            {
              positions.push_back(lid);
              positions.push_back(static_cast<int>(n));
            }
          if (!matrix || n == 0)
            continue;
          if (find)
            {
              const int *const row_begin = row_columns + row_start[lid];
              const int *const row_end   = row_columns + row_start[lid + 1];
              for (unsigned int j = 0; j < n; ++j)
                {
                  const int *const c =
                    std::find(row_begin, row_end, matrix->LCID(static_cast<int>(entry[2 * j])));
                  AssertThrow(c != row_end, ExcMessage("OffProcessRows: a received entry outside the "
                                                       "matrix's pattern"));
                  const int position = static_cast<int>(c - row_columns);
                  positions.push_back(position);
                  values[position] += entry[2 * j + 1];
                }
              continue;
            }
          columns.resize(n);
          std::vector<double> row_values(n);
          for (unsigned int j = 0; j < n; ++j)
            {
              columns[j]    = static_cast<int>(entry[2 * j]);
              row_values[j] = entry[2 * j + 1];
            }
          const int ierr = matrix->Epetra_CrsMatrix::SumIntoGlobalValues(row, static_cast<int>(n),
                                                                         row_values.data(), columns.data());
          AssertThrow(ierr == 0, ExcMessage("OffProcessRows: a received entry outside the "
                                            "matrix's pattern (" + std::to_string(ierr) + ")"));
        }
      // Positions found without the matrix's entries (a residual first)
      // would not serve an assembly with them.
      if (find)
        {
          bool with_entries = false;
          for (std::size_t k = 0; k < positions.size(); k += 2 + positions[k + 1])
            with_entries = with_entries || positions[k + 1] > 0;
          if (with_entries)
            plan.received_version[sender] = version;
          else
            positions.clear();
        }
    }

    ANVIL_INSTANTIATE_CLASS(OffProcessRows)
  } // namespace MechanicsAssembly
} // namespace anvil
