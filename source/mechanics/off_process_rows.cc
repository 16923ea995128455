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
                                        const MPI_Comm                    comm)
      : mapping(mapping)
      , constraints(constraints)
      , matrix(matrix)
      , vectors(vectors)
      , owned_map(owned_map)
      , n_dofs(n_dofs)
      , dynamic(dynamic)
      , comm(comm)
      , constrained_cells(mapping.constrained_cells(constraints.get_lines()))
    {
      AssertThrow(vectors[0] && vectors[1] && vectors[2] && (!dynamic || vectors[3]),
                  ExcInternalError());
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
    typename OffProcessRows<dim>::Row &OffProcessRows<dim>::remote_row(const Index row)
    {
      const auto [at, added] = row_at.emplace(row, static_cast<unsigned int>(rows.size()));
      if (added)
        rows.push_back(Row{static_cast<int>(row), {}, {}});
      return rows[at->second];
    }

    template <int dim>
    void OffProcessRows<dim>::add_remote(const Index row, const unsigned int n, const Index *cols,
                                         const double *values)
    {
      auto &entries = remote_row(row).entries;
      for (unsigned int j = 0; j < n; ++j)
        {
          const int  c  = static_cast<int>(cols[j]);
          const auto at = std::lower_bound(entries.begin(), entries.end(), c,
                                           [](const auto &e, const int c) { return e.first < c; });
          if (at != entries.end() && at->first == c)
            at->second += values[j];
          else
            entries.insert(at, {c, values[j]});
        }
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
      return lid >= 0 ? vectors[k][lid] : remote_row(row).vectors[k];
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
      const auto add_vector = [&](const unsigned int k, const Vector<double> &local) {
        for (unsigned int i = 0; i < n_dofs; ++i)
          vector_entry(k, copy.dof_indices[i]) += local(i);
      };
      if (dynamic)
        add_vector(3, copy.inertia);
      if (constrained_cells[copy.cell_index])
        {
          VectorTarget rhs{this, 0};
          if (matrix)
            {
              MatrixTarget K{this};
              constraints.distribute_local_to_global(copy.matrix, copy.rhs, copy.dof_indices, K, rhs);
            }
          else
            constraints.distribute_local_to_global(copy.rhs, copy.dof_indices, rhs);
        }
      else
        {
          const int *const own = mapping.owned_vector_indices(copy.cell_index, n_dofs);
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
              const Index *const dofs = copy.dof_indices.data();
              for (unsigned int i = 0; i < n_dofs; ++i)
                if (own[i] < 0)
                  add_remote(dofs[i], n_dofs, dofs, &copy.matrix(i, 0));
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
        }
      add_vector(1, copy.internal);
      add_vector(2, copy.external);
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

      // Per row: row, n, the four vector entries, then n (column, value)
      // pairs, all as doubles (indices < 2^31 are exact).
      std::vector<std::vector<double>> send(P);
      for (const Row &r : rows)
        {
          unsigned int p = 0;
          while (p < P && !(ranges[2 * p] <= r.row && r.row < ranges[2 * p + 1]))
            ++p;
          AssertThrow(p < P, ExcMessage("OffProcessRows: row " + std::to_string(r.row) +
                                        " owned by no process"));
          auto &s = send[p];
          s.push_back(r.row);
          s.push_back(static_cast<double>(r.entries.size()));
          s.insert(s.end(), r.vectors.begin(), r.vectors.end());
          for (const auto &[c, v] : r.entries)
            {
              s.push_back(c);
              s.push_back(v);
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
      std::vector<double> values;
      for (std::size_t i = 0; i < received.size();)
        {
          const int          row = static_cast<int>(received[i]);
          const unsigned int n   = static_cast<unsigned int>(received[i + 1]);
          const int          lid = owned_map.LID(row);
          AssertThrow(lid >= 0, ExcMessage("OffProcessRows: received row " + std::to_string(row) +
                                           " not owned here"));
          for (unsigned int k = 0; k < 4; ++k)
            if (vectors[k])
              vectors[k][lid] += received[i + 2 + k];
          i += 6;
          if (matrix && n > 0)
            {
              columns.resize(n);
              values.resize(n);
              for (unsigned int j = 0; j < n; ++j)
                {
                  columns[j] = static_cast<int>(received[i + 2 * j]);
                  values[j]  = received[i + 2 * j + 1];
                }
              ierr = matrix->Epetra_CrsMatrix::SumIntoGlobalValues(row, static_cast<int>(n),
                                                                   values.data(), columns.data());
              AssertThrow(ierr == 0, ExcMessage("OffProcessRows: a received entry outside the "
                                                "matrix's pattern (" + std::to_string(ierr) + ")"));
            }
          i += 2 * std::size_t(n);
        }
      rows.clear();
      row_at.clear();
    }

    ANVIL_INSTANTIATE_CLASS(OffProcessRows)
  } // namespace MechanicsAssembly
} // namespace anvil
