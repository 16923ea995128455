// A_c = Pᵀ A P one coarse row at a time (geometric_coarse_space.h). EpetraExt
// forms A P first: ~47 entries per fine row in 3D (a fine node couples to
// 2.5³ coarse nodes on average), ~600 B/DoF held at once beside K, which at
// 1 M DoFs set the run's peak once ML's set-up on A_1 no longer did
// (doc/memory.md, session 22). Here coarse row I is
//   A_c(I, ·) = Σ_{i: P(i,I) ≠ 0} P(i,I) Σ_j A(i,j) P(j, ·),
// summed in a dense accumulator over the coarse columns this process
// touches: the transients are Pᵀ of the owned rows and P's rows at A's
// columns (each of P's size, ~40 B/DoF), A_c itself and the accumulator; A
// P's rows are formed once per entry of P's column (~3.4 times), twice
// EpetraExt's multiplications.
#include <deal.II/base/exceptions.h>

#include "geometric_coarse_space.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <unordered_map>
#include <vector>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_FECrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  std::unique_ptr<Epetra_CrsMatrix> galerkin_product_by_rows(const Epetra_CrsMatrix &A, const Epetra_CrsMatrix &P)
  {
    AssertThrow(A.RowMap().SameAs(P.RowMap()), ExcMessage("geometric coarse space: P's rows are not A's"));
    const Epetra_Map &coarse = P.DomainMap();
    const Epetra_Map &cols   = A.ColMap();
    const int         n_rows = A.NumMyRows(), n_cols = A.NumMyCols();

    // The coarse columns this process touches, numbered locally: P's column
    // map first, then those of P's rows at A's ghost columns.
    std::vector<int> gid_of(P.ColMap().MyGlobalElements(), P.ColMap().MyGlobalElements() + P.ColMap().NumMyElements());
    std::unordered_map<int, int> extra;
    const auto local_of = [&](const int gid) {
      const int lid = P.ColMap().LID(gid);
      if (lid >= 0)
        return lid;
      const auto [it, added] = extra.emplace(gid, static_cast<int>(gid_of.size()));
      if (added)
        gid_of.push_back(gid);
      return it->second;
    };

    // P's rows at A's columns (local coarse numbers).
    std::unique_ptr<Epetra_CrsMatrix> remote;
    if (A.Comm().NumProc() > 1)
      {
        std::vector<int> ghosts;
        for (int j = 0; j < n_cols; ++j)
          if (A.RowMap().LID(cols.GID(j)) < 0)
            ghosts.push_back(cols.GID(j));
        const Epetra_Map    ghost_map(-1, static_cast<int>(ghosts.size()), ghosts.data(), 0, A.Comm());
        const Epetra_Import importer(ghost_map, P.RowMap());
        remote = std::make_unique<Epetra_CrsMatrix>(Copy, ghost_map, 0);
        AssertThrow(remote->Import(P, importer, Insert) == 0, ExcMessage("geometric coarse space: P's import failed"));
      }
    std::vector<int>    p_start(n_cols + 1, 0), p_column;
    std::vector<double> p_value;
    {
      std::vector<int>    g_index(P.MaxNumEntries() + (remote ? remote->MaxNumEntries() : 0));
      std::vector<double> g_value(g_index.size());
      for (int j = 0; j < n_cols; ++j)
        {
          const int gid = cols.GID(j), row = P.RowMap().LID(gid);
          if (row >= 0)
            {
              int     n;
              double *v;
              int    *c;
              P.ExtractMyRowView(row, n, v, c);
              p_column.insert(p_column.end(), c, c + n);
              p_value.insert(p_value.end(), v, v + n);
            }
          else
            {
              int n = 0;
              if (remote->NumGlobalEntries(gid) > static_cast<int>(g_index.size()))
                {
                  g_index.resize(remote->NumGlobalEntries(gid));
                  g_value.resize(g_index.size());
                }
              remote->ExtractGlobalRowCopy(gid, g_index.size(), n, g_value.data(), g_index.data());
              for (int k = 0; k < n; ++k)
                {
                  p_column.push_back(local_of(g_index[k]));
                  p_value.push_back(g_value[k]);
                }
            }
          p_start[j + 1] = p_column.size();
        }
    }
    remote.reset();

    // Pᵀ of the owned rows: for each local coarse column, (row, P(row, ·)).
    const int           n_local = gid_of.size();
    std::vector<int>    t_start(n_local + 1, 0), t_row;
    std::vector<double> t_value;
    {
      for (int i = 0; i < n_rows; ++i)
        {
          int     n;
          double *v;
          int    *c;
          P.ExtractMyRowView(i, n, v, c);
          for (int k = 0; k < n; ++k)
            ++t_start[c[k] + 1];
        }
      for (int I = 0; I < n_local; ++I)
        t_start[I + 1] += t_start[I];
      t_row.resize(t_start[n_local]);
      t_value.resize(t_start[n_local]);
      std::vector<int> fill(t_start.begin(), t_start.end() - 1);
      for (int i = 0; i < n_rows; ++i)
        {
          int     n;
          double *v;
          int    *c;
          P.ExtractMyRowView(i, n, v, c);
          for (int k = 0; k < n; ++k)
            {
              t_row[fill[c[k]]]     = i;
              t_value[fill[c[k]]++] = v[k];
            }
        }
    }

    // Each coarse row complete in one pass (rows owned elsewhere go to
    // their owner in GlobalAssemble, summed with its own part).
    auto                Ac = std::make_unique<Epetra_FECrsMatrix>(Copy, coarse, A.MaxNumEntries());
    std::vector<double> sum(n_local, 0.);
    std::vector<int>    slot(n_local, -1), used, columns;
    std::vector<double> values;
    for (int I = 0; I < n_local; ++I)
      {
        if (t_start[I] == t_start[I + 1])
          continue;
        used.clear();
        for (int k = t_start[I]; k < t_start[I + 1]; ++k)
          {
            const double p = t_value[k];
            int          n;
            double      *a;
            int         *j;
            A.ExtractMyRowView(t_row[k], n, a, j);
            for (int e = 0; e < n; ++e)
              {
                const double pa = p * a[e];
                for (int q = p_start[j[e]]; q < p_start[j[e] + 1]; ++q)
                  {
                    const int J = p_column[q];
                    if (slot[J] < 0)
                      {
                        slot[J] = used.size();
                        used.push_back(J);
                        sum[J] = 0;
                      }
                    sum[J] += pa * p_value[q];
                  }
              }
          }
        std::sort(used.begin(), used.end(), [&](const int a, const int b) { return gid_of[a] < gid_of[b]; });
        columns.resize(used.size());
        values.resize(used.size());
        for (std::size_t k = 0; k < used.size(); ++k)
          {
            columns[k]    = gid_of[used[k]];
            values[k]     = sum[used[k]];
            slot[used[k]] = -1;
          }
        AssertThrow(Ac->InsertGlobalValues(gid_of[I], static_cast<int>(columns.size()), values.data(), columns.data()) >= 0,
                    ExcMessage("geometric coarse space: A_c's insertion failed"));
      }
    AssertThrow(Ac->GlobalAssemble(coarse, coarse) >= 0, ExcMessage("geometric coarse space: A_c's assembly failed"));
    // Benchmarks: the operators' entries (12 B each in memory).
    if (std::getenv("ANVIL_GMG_LOG") && A.Comm().MyPID() == 0)
      std::cout << "geometric coarse space (by rows): A " << A.NumGlobalRows() << " rows, " << A.NumGlobalNonzeros()
                << " entries; P " << P.NumGlobalNonzeros() << "; A_c " << Ac->NumGlobalRows() << " rows, "
                << Ac->NumGlobalNonzeros() << std::endl;
    return Ac;
  }
} // namespace anvil
