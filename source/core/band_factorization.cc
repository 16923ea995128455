// BandFactorization: reverse Cuthill–McKee, then LAPACK's unblocked banded
// LU with partial pivoting (dgbtf2) and its solve (dgbtrs), written out so
// that the elimination can skip the band's zeros (see the header).
#include <deal.II/base/exceptions.h>

#include <anvil/core/band_elimination.h>
#include <anvil/core/band_factorization.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// The graph of A + Aᵀ without the diagonal, as adjacency lists.
    void symmetric_graph(const int n, const int *offsets, const int *columns,
                         std::vector<int> &start, std::vector<int> &adjacent)
    {
      start.assign(n + 1, 0);
      for (int row = 0; row < n; ++row)
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          if (columns[k] != row)
            {
              ++start[row + 1];
              ++start[columns[k] + 1];
            }
      for (int i = 0; i < n; ++i)
        start[i + 1] += start[i];
      adjacent.resize(start[n]);
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (int row = 0; row < n; ++row)
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          if (columns[k] != row)
            {
              adjacent[fill[row]++]         = columns[k];
              adjacent[fill[columns[k]]++] = row;
            }
      // Duplicates (an entry and its transpose) are left: they cost a
      // visited test in the search, less than sorting the lists.
    }

    /// Breadth-first levels from @p root over unvisited nodes (visited
    /// marks them with @p mark): the nodes in order, the last level's start.
    int levels(const int root, const std::vector<int> &start, const std::vector<int> &adjacent,
               std::vector<int> &visited, const int mark, std::vector<int> &queue,
               int &last_level_start)
    {
      queue.clear();
      queue.push_back(root);
      visited[root] = mark;
      int depth = 0, level_begin = 0;
      while (level_begin < static_cast<int>(queue.size()))
        {
          const int level_end = queue.size();
          last_level_start    = level_begin;
          for (int q = level_begin; q < level_end; ++q)
            for (int k = start[queue[q]]; k < start[queue[q] + 1]; ++k)
              if (visited[adjacent[k]] != mark)
                {
                  visited[adjacent[k]] = mark;
                  queue.push_back(adjacent[k]);
                }
          level_begin = level_end;
          ++depth;
        }
      return depth;
    }
  } // namespace

  void BandFactorization::order(const int *offsets, const int *columns)
  {
    std::vector<int> start, adjacent;
    symmetric_graph(n, offsets, columns, start, adjacent);
    const auto degree = [&](const int i) { return start[i + 1] - start[i]; };

    // Cuthill–McKee per connected component, from a pseudo-peripheral node
    // (George & Liu: restart from the last level's node of least degree
    // while the depth grows), neighbours taken by increasing degree.
    std::vector<int> visited(n, -1), queue, cm, neighbours;
    std::vector<char> placed(n, 0);
    cm.reserve(n);
    int mark = 0;
    for (int seed = 0; seed < n; ++seed)
      {
        if (placed[seed])
          continue;
        int root = seed, last_start = 0;
        int depth = levels(root, start, adjacent, visited, mark++, queue, last_start);
        for (int tries = 0; tries < 3; ++tries)
          {
            int candidate = queue[last_start];
            for (int q = last_start; q < static_cast<int>(queue.size()); ++q)
              if (degree(queue[q]) < degree(candidate))
                candidate = queue[q];
            const int d = levels(candidate, start, adjacent, visited, mark++, queue, last_start);
            if (d <= depth)
              break;
            depth = d;
            root  = candidate;
          }
        const std::size_t first = cm.size();
        cm.push_back(root);
        placed[root] = 1;
        for (std::size_t q = first; q < cm.size(); ++q)
          {
            neighbours.clear();
            for (int k = start[cm[q]]; k < start[cm[q] + 1]; ++k)
              if (!placed[adjacent[k]])
                {
                  placed[adjacent[k]] = 1;
                  neighbours.push_back(adjacent[k]);
                }
            std::stable_sort(neighbours.begin(), neighbours.end(),
                             [&](int a, int b) { return degree(a) < degree(b); });
            cm.insert(cm.end(), neighbours.begin(), neighbours.end());
          }
      }
    inverse.assign(cm.rbegin(), cm.rend());
    permutation.resize(n);
    for (int k = 0; k < n; ++k)
      permutation[inverse[k]] = k;
    measure(offsets, columns);
    ordered_lower = lower;
    ordered_upper = upper;
    ++orderings;
  }

  void BandFactorization::measure(const int *offsets, const int *columns)
  {
    // Band widths, and the envelope's flops: row i's first column f_i (L's
    // fill stays right of it), column c's first row g_c (U's stays below).
    lower = upper = 0;
    std::vector<int> first_column(n), first_row(n);
    for (int k = 0; k < n; ++k)
      first_column[k] = first_row[k] = k;
    for (int row = 0; row < n; ++row)
      for (int k = offsets[row]; k < offsets[row + 1]; ++k)
        {
          const int i = permutation[row], j = permutation[columns[k]];
          lower              = std::max(lower, i - j);
          upper              = std::max(upper, j - i);
          first_column[i]    = std::min(first_column[i], j);
          first_row[j]       = std::min(first_row[j], i);
        }
    // L's column j reaches the last row i with f_i <= j; U's row j holds
    // the columns c > j with g_c <= j.
    std::vector<int> reach(n, 0), starting(n + 1, 0);
    for (int i = 0; i < n; ++i)
      {
        reach[first_column[i]] = std::max(reach[first_column[i]], i);
        ++starting[first_row[i] + 1];
      }
    envelope_flops = 0;
    int furthest = 0, counted = 0;
    for (int j = 0; j < n; ++j)
      {
        furthest = std::max(furthest, reach[j]);
        counted += starting[j + 1];
        envelope_flops += 2. * (furthest - j) * (counted - (j + 1));
      }
    stride = band_kernel::column_stride(lower, upper);
  }

  bool BandFactorization::fits(const int *offsets, const int *columns) const
  {
    for (int row = 0; row < n; ++row)
      for (int k = offsets[row]; k < offsets[row + 1]; ++k)
        {
          const int d = permutation[row] - permutation[columns[k]];
          if (d > lower || -d > upper)
            return false;
        }
    return true;
  }

  bool BandFactorization::analyze(const int size, const int *offsets, const int *columns)
  {
    const bool reordered = choose_ordering(size, offsets, columns);
    place(offsets, columns);
    return reordered;
  }

  bool BandFactorization::choose_ordering(const int size, const int *offsets, const int *columns)
  {
    if (size == n && !permutation.empty())
      {
        if (fits(offsets, columns))
          return false;
        // The new couplings widen the band by little: keep the ordering
        // (the elimination skips the band's zeros, so a wider band costs
        // mostly its storage); else order anew.
        measure(offsets, columns);
        if (lower <= kept_growth * ordered_lower && upper <= kept_growth * ordered_upper)
          return false;
      }
    n = size;
    order(offsets, columns);
    return true;
  }

  void BandFactorization::place(const int *offsets, const int *columns)
  {
    // Each entry's place in the band and each row's last column, for every
    // factorisation of this pattern.
    const int diagonal = band_kernel::diagonal_row(lower, upper);
    position.resize(offsets[n]);
    pattern_row_end.resize(n);
    column_reach.assign(n, 0);
    for (int row = 0; row < n; ++row)
      {
        const int i     = permutation[row];
        int      &e     = pattern_row_end[i];
        int       first = i;
        e               = i;
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          {
            const int j = permutation[columns[k]];
            position[k] = static_cast<std::size_t>(j) * stride + diagonal + i - j;
            e           = std::max(e, j);
            first       = std::min(first, j);
          }
        column_reach[first] = std::max(column_reach[first], i);
      }
    // A row's entries left of its first column stay zero until a step
    // reaches it: steps k < j touch rows up to the reach of column k only.
    for (int j = 0, furthest = 0; j < n; ++j)
      {
        furthest        = std::max({furthest, column_reach[j], j});
        column_reach[j] = furthest - j;
      }
  }

  void BandFactorization::factorize(const int *offsets, const int *columns, const double *values)
  {
    (void)offsets;
    (void)columns;
    // Vector stores, not assign(): the zeroing streams the whole band
    // (1.5 MB on two_blocks) and assign's element loop cost a tenth of the
    // elimination.
    band.resize(static_cast<std::size_t>(n) * stride);
    band_kernel::zero(band.data(), band.size());
    for (std::size_t k = 0; k < position.size(); ++k)
      band[position[k]] = values[k];
    pivot.resize(n);
    column_end = column_reach; // bounds on entry
    column_top.resize(n);
    row_end = pattern_row_end;
    const double multiply_adds = band_kernel::eliminate(layout(), pivot.data(), column_end.data(),
                                                        row_end.data(), column_top.data());
    AssertThrow(multiply_adds >= 0,
                ExcMessage("Band LU: the matrix is singular (column " +
                           std::to_string(inverse[static_cast<int>(-1. - multiply_adds)]) + ")"));
    last_multiply_adds = multiply_adds;
    ++factorizations;
  }

  band_kernel::Band BandFactorization::layout() const
  {
    return {const_cast<double *>(band.data()), n, lower, upper, stride,
            band_kernel::diagonal_row(lower, upper)};
  }

  void BandFactorization::solve(double *x, const double *b) const
  {
    std::vector<double> y(n);
    for (int i = 0; i < n; ++i)
      y[permutation[i]] = b[i];
    band_kernel::substitute(layout(), pivot.data(), column_end.data(), column_top.data(), y.data());
    for (int i = 0; i < n; ++i)
      x[i] = y[permutation[i]];
  }
} // namespace anvil
