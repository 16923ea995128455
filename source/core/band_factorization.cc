// BandFactorization: reverse Cuthill–McKee, then LAPACK's unblocked banded
// LU with partial pivoting (dgbtf2) and its solve (dgbtrs), written out so
// that the elimination can skip the band's zeros (see the header).
#include <deal.II/base/exceptions.h>

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
    // Three zero rows below each column: the elimination's blocks of 4.
    stride = 2 * lower + upper + 4;
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
    const int kv = lower + upper;
    position.resize(offsets[n]);
    pattern_row_end.resize(n);
    for (int row = 0; row < n; ++row)
      {
        const int i = permutation[row];
        int      &e = pattern_row_end[i];
        e           = i;
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          {
            const int j = permutation[columns[k]];
            position[k] = static_cast<std::size_t>(j) * stride + kv + i - j;
            e           = std::max(e, j);
          }
      }
  }

  namespace
  {
    // The loops below are vectorised (the build's -O2 vectorises only loops
    // without a remainder) and compiled twice, for AVX2 (4 doubles an
    // instruction) and for the base x86-64 (2), the processor choosing at
    // load time. No FMA: each entry is rounded as in the scalar loop, so
    // the answers do not depend on the processor.
#define ANVIL_BAND_KERNEL                                                                          \
  __attribute__((target_clones("avx2", "default"),                                                 \
                 optimize("tree-loop-vectorize", "vect-cost-model=dynamic")))

    /// cc[0, m) −= u l[0, m), m a multiple of 4.
    ANVIL_BAND_KERNEL void axpy_blocks(double *__restrict cc, const double u,
                                       const double *__restrict l, const int m)
    {
      for (int i = 0; i < m; i += 4)
        {
          cc[i] -= u * l[i];
          cc[i + 1] -= u * l[i + 1];
          cc[i + 2] -= u * l[i + 2];
          cc[i + 3] -= u * l[i + 3];
        }
    }

    /// Two columns at once, l read once for both (the same bits as two
    /// calls: the columns do not depend on each other). A call of its own:
    /// written inline in eliminate() it vectorised worse (+7 % on the
    /// folded tube).
    ANVIL_BAND_KERNEL void axpy_blocks2(double *__restrict a, const double ua,
                                        double *__restrict b, const double ub,
                                        const double *__restrict l, const int m)
    {
      for (int i = 0; i < m; i += 4)
        {
          const double l0 = l[i], l1 = l[i + 1], l2 = l[i + 2], l3 = l[i + 3];
          a[i] -= ua * l0;
          a[i + 1] -= ua * l1;
          a[i + 2] -= ua * l2;
          a[i + 3] -= ua * l3;
          b[i] -= ub * l0;
          b[i + 1] -= ub * l1;
          b[i + 2] -= ub * l2;
          b[i + 3] -= ub * l3;
        }
    }

    /// Four columns at once, l read once for all (the same bits as four
    /// calls: the columns do not depend on each other).
    ANVIL_BAND_KERNEL void axpy_blocks4(double *const *const cc, const double *const u,
                                        const double *__restrict l, const int m)
    {
      double *__restrict a = cc[0], *__restrict b = cc[1], *__restrict c = cc[2],
                         *__restrict d = cc[3];
      const double ua = u[0], ub = u[1], uc = u[2], ud = u[3];
      for (int i = 0; i < m; i += 4)
        {
          const double l0 = l[i], l1 = l[i + 1], l2 = l[i + 2], l3 = l[i + 3];
          a[i] -= ua * l0;
          a[i + 1] -= ua * l1;
          a[i + 2] -= ua * l2;
          a[i + 3] -= ua * l3;
          b[i] -= ub * l0;
          b[i + 1] -= ub * l1;
          b[i + 2] -= ub * l2;
          b[i + 3] -= ub * l3;
          c[i] -= uc * l0;
          c[i + 1] -= uc * l1;
          c[i + 2] -= uc * l2;
          c[i + 3] -= uc * l3;
          d[i] -= ud * l0;
          d[i + 1] -= ud * l1;
          d[i + 2] -= ud * l2;
          d[i + 3] -= ud * l3;
        }
    }

    /// dgbtf2 on the band (column-major, @p stride ≥ 2 lower + upper + 4,
    /// A(i, j) at band[j stride + kv + i − j], the rows past kv + lower
    /// zero padding): column j's pivot among its lower rows, the exchange
    /// over the columns the two rows reach, the multipliers, the rank-1
    /// update, skipping zero multipliers' tails and zero entries of U's row.
    /// Returns the multiply-adds, or −1 − j for a zero column j.
    /// Per-column overhead is what this kernel is about (the tube's columns
    /// hold 10–30 multipliers): the update runs whole blocks of 4 rows (the
    /// padding rows make them safe: l is zero past its last nonzero, so an
    /// entry past it gets x − u·0 = x) over four columns of U at a time, and
    /// the pivot search is a max reduction, then the first row that reaches
    /// it (the row partial pivoting picks, as dgbtf2's idamax does).
    /// @p row_end: on entry each row's last column in the pattern (≥ the
    /// row); kept as the last column row i can reach (its own, and those of
    /// the rows eliminated into it: fill follows U's rows down the
    /// multipliers), so a row of U is scanned to its reach, not to
    /// dgbtf2's bound j + ku + p over all earlier exchanges (2× as far on
    /// two_blocks). @p column_top: U's first nonzero row in each column,
    /// for the solve.
    ANVIL_BAND_KERNEL double eliminate(double *const band, const int n, const int lower,
                                       const int upper, const int stride, int *const pivot,
                                       int *const column_end, int *const row_end,
                                       int *const column_top)
    {
      const int kv            = lower + upper;
      double    multiply_adds = 0;
      const auto column = [&](const int c, const int j) {
        return band + static_cast<std::size_t>(c) * stride + kv + j - c; // A(j, c)
      };
      for (int j = 0; j < n; ++j)
        column_top[j] = j;
      double *targets[4];
      double  factors[4];
      for (int j = 0; j < n; ++j)
        {
          double *const lj = band + static_cast<std::size_t>(j) * stride + kv; // lj[i] = A(j+i, j)
          int           last = std::min(lower, n - 1 - j);
          while (last > 0 && lj[last] == 0.)
            --last;
          double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
          int    i = 0;
          for (; i + 3 <= last; i += 4)
            {
              m0 = std::max(m0, std::abs(lj[i]));
              m1 = std::max(m1, std::abs(lj[i + 1]));
              m2 = std::max(m2, std::abs(lj[i + 2]));
              m3 = std::max(m3, std::abs(lj[i + 3]));
            }
          for (; i <= last; ++i)
            m0 = std::max(m0, std::abs(lj[i]));
          const double largest = std::max(std::max(m0, m1), std::max(m2, m3));
          if (!(largest > 0.))
            return -1. - j;
          int p = 0;
          while (std::abs(lj[p]) != largest)
            ++p;
          pivot[j]      = j + p;
          column_end[j] = last;
          if (p != 0)
            {
              const int reach = std::max(row_end[j], row_end[j + p]);
              for (int c = j; c <= reach; ++c)
                {
                  double *const cc = column(c, j);
                  std::swap(cc[0], cc[p]);
                }
              std::swap(row_end[j], row_end[j + p]);
            }
          const int ju = row_end[j];
          const double inverse_pivot = 1. / lj[0];
          for (int i = 1; i <= last; ++i)
            lj[i] *= inverse_pivot;
          if (last == 0)
            continue;
          for (int i = 1; i <= last; ++i)
            row_end[j + i] = std::max(row_end[j + i], ju);
          const double *const l      = lj + 1;
          const int           blocks = (last + 3) & ~3;
          int                 held = 0, updated = 0;
          for (int c = j + 1; c <= ju; ++c)
            {
              double *const a = column(c, j);
              if (*a == 0.)
                continue;
              column_top[c] = std::min(column_top[c], j);
              ++updated;
              targets[held]   = a + 1;
              factors[held++] = a[0];
              if (held == 4)
                {
                  axpy_blocks4(targets, factors, l, blocks);
                  held = 0;
                }
            }
          multiply_adds += double(last) * updated;
          if (held >= 2)
            axpy_blocks2(targets[0], factors[0], targets[1], factors[1], l, blocks);
          if (held == 3)
            axpy_blocks(targets[2], factors[2], l, blocks);
          else if (held == 1)
            axpy_blocks(targets[0], factors[0], l, blocks);
        }
      return multiply_adds;
    }

    /// a[0, m) = 0 by vector stores: memset's `rep stosb` is as fast but
    /// counts as one instruction per byte under callgrind, which would hide
    /// the kernel's counts behind the zeroing.
    __attribute__((target_clones("avx2", "default"),
                   optimize("tree-loop-vectorize", "no-tree-loop-distribute-patterns"))) void
    zero(double *__restrict a, const std::size_t m)
    {
      for (std::size_t i = 0; i < m; ++i)
        a[i] = 0.;
    }

    /// y = U⁻¹ L⁻¹ P y with eliminate()'s factors (dgbtrs).
    ANVIL_BAND_KERNEL void substitute(const double *const band, const int n, const int kv,
                                      const int stride, const int *const pivot,
                                      const int *const column_end, const int *const column_top,
                                      double *const y)
    {
      // L: the exchanges and the multipliers in the order they were made.
      for (int j = 0; j < n; ++j)
        {
          if (pivot[j] != j)
            std::swap(y[j], y[pivot[j]]);
          const double *__restrict l = band + static_cast<std::size_t>(j) * stride + kv + 1;
          double *__restrict below   = y + j + 1;
          const double yj            = y[j];
          if (yj != 0.)
            for (int i = 0; i < column_end[j]; ++i)
              below[i] -= yj * l[i];
        }
      // U, column by column from the last, from its first nonzero row.
      for (int j = n - 1; j >= 0; --j)
        {
          const double *uj    = band + static_cast<std::size_t>(j) * stride + kv;
          const int     above = j - column_top[j];
          y[j] /= uj[0];
          const double yj = y[j];
          if (yj == 0.)
            continue;
          const double *__restrict u = uj - above;
          double *__restrict top     = y + j - above;
          for (int i = 0; i < above; ++i)
            top[i] -= yj * u[i];
        }
    }
#undef ANVIL_BAND_KERNEL
  } // namespace

  void BandFactorization::factorize(const int *offsets, const int *columns, const double *values)
  {
    (void)offsets;
    (void)columns;
    // Vector stores, not assign(): the zeroing streams the whole band
    // (1.5 MB on two_blocks) and assign's element loop cost a tenth of the
    // elimination.
    band.resize(static_cast<std::size_t>(n) * stride);
    zero(band.data(), band.size());
    for (std::size_t k = 0; k < position.size(); ++k)
      band[position[k]] = values[k];
    pivot.resize(n);
    column_end.resize(n);
    column_top.resize(n);
    row_end = pattern_row_end;
    const double multiply_adds = eliminate(band.data(), n, lower, upper, stride, pivot.data(),
                                           column_end.data(), row_end.data(), column_top.data());
    AssertThrow(multiply_adds >= 0,
                ExcMessage("Band LU: the matrix is singular (column " +
                           std::to_string(inverse[static_cast<int>(-1. - multiply_adds)]) + ")"));
    last_multiply_adds = multiply_adds;
    ++factorizations;
  }

  void BandFactorization::solve(double *x, const double *b) const
  {
    std::vector<double> y(n);
    for (int i = 0; i < n; ++i)
      y[permutation[i]] = b[i];
    substitute(band.data(), n, lower + upper, stride, pivot.data(), column_end.data(),
               column_top.data(), y.data());
    for (int i = 0; i < n; ++i)
      x[i] = y[permutation[i]];
  }
} // namespace anvil
