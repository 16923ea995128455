// FrontalFactorization: AMD, the postordered elimination tree, fundamental
// supernodes and their fronts, then dense left-looking LU per front (see the
// header).
#include <anvil/core/frontal_factorization.h>

#include <trilinos_amd.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace anvil
{
  namespace
  {
    // As the band kernel (band_elimination.cc): vectorised, AVX2 and base
    // x86-64 chosen at load time, no FMA (each entry rounded as in the
    // scalar loop, the answers independent of the processor).
#define ANVIL_FRONT_KERNEL                                                                         \
  __attribute__((target_clones("avx2", "default"),                                                 \
                 optimize("tree-loop-vectorize", "vect-cost-model=dynamic")))

    /// Column a (ld rows, a multiple of 4) of a front takes the updates of
    /// its first @p pivots columns L (leading dimension ld): four pivots
    /// per pass, the rows among them first (the triangular part), then
    /// a ← (((a − u₀l₀) − u₁l₁) − u₂l₂) − u₃l₃ below them, which is the
    /// order of column-by-column elimination.
    ANVIL_FRONT_KERNEL void update_column(double *__restrict a, const double *__restrict L, const int ld,
                                          const int pivots)
    {
      int p = 0;
      for (; p + 4 <= pivots; p += 4)
        {
          const double *const l0 = L + static_cast<std::size_t>(p) * ld, *const l1 = l0 + ld,
                              *const l2 = l1 + ld, *const l3 = l2 + ld;
          a[p + 1] -= l0[p + 1] * a[p];
          a[p + 2] -= l0[p + 2] * a[p];
          a[p + 2] -= l1[p + 2] * a[p + 1];
          a[p + 3] -= l0[p + 3] * a[p];
          a[p + 3] -= l1[p + 3] * a[p + 1];
          a[p + 3] -= l2[p + 3] * a[p + 2];
          const double u0 = a[p], u1 = a[p + 1], u2 = a[p + 2], u3 = a[p + 3];
          if (u0 == 0. && u1 == 0. && u2 == 0. && u3 == 0.)
            continue;
          for (int i = p + 4; i < ld; ++i)
            a[i] = (((a[i] - u0 * l0[i]) - u1 * l1[i]) - u2 * l2[i]) - u3 * l3[i];
        }
      if (p + 2 <= pivots)
        {
          // Two pivots (a node's two displacements).
          const double *const l0 = L + static_cast<std::size_t>(p) * ld, *const l1 = l0 + ld;
          a[p + 1] -= l0[p + 1] * a[p];
          const double u0 = a[p], u1 = a[p + 1];
          if (u0 != 0. || u1 != 0.)
            for (int i = p + 2; i < ld; ++i)
              a[i] = (a[i] - u0 * l0[i]) - u1 * l1[i];
          p += 2;
        }
      for (; p < pivots; ++p)
        {
          const double u = a[p];
          if (u == 0.)
            continue;
          const double *const l = L + static_cast<std::size_t>(p) * ld;
          for (int i = p + 1; i < ld; ++i)
            a[i] -= u * l[i];
        }
    }

    /// update_column() on two columns a, b at once (the multipliers read
    /// once for both), each entry's operations those of update_column().
    ANVIL_FRONT_KERNEL void update_columns(double *__restrict a, double *__restrict b,
                                           const double *__restrict L, const int ld, const int pivots)
    {
      int p = 0;
      for (; p + 4 <= pivots; p += 4)
        {
          const double *const l0 = L + static_cast<std::size_t>(p) * ld, *const l1 = l0 + ld,
                              *const l2 = l1 + ld, *const l3 = l2 + ld;
          for (double *const x : {a, b})
            {
              x[p + 1] -= l0[p + 1] * x[p];
              x[p + 2] -= l0[p + 2] * x[p];
              x[p + 2] -= l1[p + 2] * x[p + 1];
              x[p + 3] -= l0[p + 3] * x[p];
              x[p + 3] -= l1[p + 3] * x[p + 1];
              x[p + 3] -= l2[p + 3] * x[p + 2];
            }
          const double a0 = a[p], a1 = a[p + 1], a2 = a[p + 2], a3 = a[p + 3];
          const double b0 = b[p], b1 = b[p + 1], b2 = b[p + 2], b3 = b[p + 3];
          for (int i = p + 4; i < ld; ++i)
            {
              const double x0 = l0[i], x1 = l1[i], x2 = l2[i], x3 = l3[i];
              a[i]            = (((a[i] - a0 * x0) - a1 * x1) - a2 * x2) - a3 * x3;
              b[i]            = (((b[i] - b0 * x0) - b1 * x1) - b2 * x2) - b3 * x3;
            }
        }
      if (p + 2 <= pivots)
        {
          const double *const l0 = L + static_cast<std::size_t>(p) * ld, *const l1 = l0 + ld;
          a[p + 1] -= l0[p + 1] * a[p];
          b[p + 1] -= l0[p + 1] * b[p];
          const double a0 = a[p], a1 = a[p + 1], b0 = b[p], b1 = b[p + 1];
          for (int i = p + 2; i < ld; ++i)
            {
              const double x0 = l0[i], x1 = l1[i];
              a[i]            = (a[i] - a0 * x0) - a1 * x1;
              b[i]            = (b[i] - b0 * x0) - b1 * x1;
            }
          p += 2;
        }
      for (; p < pivots; ++p)
        {
          const double *const l = L + static_cast<std::size_t>(p) * ld;
          const double        u = a[p], v = b[p];
          for (int i = p + 1; i < ld; ++i)
            {
              a[i] -= u * l[i];
              b[i] -= v * l[i];
            }
        }
    }

    // Not a memset (no loop distribution): `rep stosb` counts an
    // instruction per byte under callgrind (band_elimination.cc's zero()).
    __attribute__((target_clones("avx2", "default"),
                   optimize("tree-loop-vectorize", "no-tree-loop-distribute-patterns"))) void
    zero(double *__restrict a, const std::size_t m)
    {
      for (std::size_t i = 0; i < m; ++i)
        a[i] = 0.;
    }
    /// max |a[i]| for c < i < ld (ld a multiple of 4, rows past the front zero).
    ANVIL_FRONT_KERNEL double largest_below(const double *__restrict a, const int c, const int ld)
    {
      double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
      int    i = c + 1;
      for (; i & 3; ++i)
        m0 = std::max(m0, std::abs(a[i]));
      for (; i < ld; i += 4)
        {
          m0 = std::max(m0, std::abs(a[i]));
          m1 = std::max(m1, std::abs(a[i + 1]));
          m2 = std::max(m2, std::abs(a[i + 2]));
          m3 = std::max(m3, std::abs(a[i + 3]));
        }
      return std::max(std::max(m0, m1), std::max(m2, m3));
    }

    /// a[i] *= s for c < i < ld.
    ANVIL_FRONT_KERNEL void scale_below(double *__restrict a, const int c, const int ld, const double s)
    {
      int i = c + 1;
      for (; i & 3; ++i)
        a[i] *= s;
      for (; i < ld; ++i)
        a[i] *= s;
    }
#undef ANVIL_FRONT_KERNEL

    int padded(const int m) { return (m + 3) & ~3; }
  } // namespace

  void FrontalFactorization::analyze(const int size, const int *offsets, const int *columns)
  {
    n = size;
    // AMD orders A + Aᵀ; the CSR arrays are the columns of Aᵀ, the same sum.
    inverse.resize(n);
    double     info[TRILINOS_AMD_INFO];
    const int  status = trilinos_amd_order(n, offsets, columns, inverse.data(), nullptr, info);
    if (status != TRILINOS_AMD_OK && status != TRILINOS_AMD_OK_BUT_JUMBLED)
      throw std::runtime_error("FrontalFactorization: AMD failed");
    permutation.resize(n);
    for (int k = 0; k < n; ++k)
      permutation[inverse[k]] = k;
    symbolic(offsets, columns);
    multiply_adds_at_ordering = work;
    ++orderings;
  }

  void FrontalFactorization::reanalyze(const int *offsets, const int *columns)
  {
    symbolic(offsets, columns);
  }

  void FrontalFactorization::symbolic(const int *offsets, const int *columns)
  {
    ++analyses;
    // The graph of A + Aᵀ in the new numbering (duplicates left in: the
    // marks below skip them).
    std::vector<int> start(n + 1, 0), adjacent;
    const auto       graph = [&] {
      std::fill(start.begin(), start.end(), 0);
      for (int row = 0; row < n; ++row)
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          if (columns[k] != row)
            {
              ++start[permutation[row] + 1];
              ++start[permutation[columns[k]] + 1];
            }
      std::partial_sum(start.begin(), start.end(), start.begin());
      adjacent.resize(start[n]);
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (int row = 0; row < n; ++row)
        for (int k = offsets[row]; k < offsets[row + 1]; ++k)
          if (columns[k] != row)
            {
              const int i = permutation[row], j = permutation[columns[k]];
              adjacent[fill[i]++] = j;
              adjacent[fill[j]++] = i;
            }
    };
    graph();

    // The elimination tree (Liu's algorithm with path compression), then
    // its postorder as the numbering, so that each supernode's subtree
    // comes just before it (the update matrices form a stack).
    std::vector<int> parent(n, -1), ancestor(n, -1);
    for (int k = 0; k < n; ++k)
      for (int q = start[k]; q < start[k + 1]; ++q)
        {
          int r = adjacent[q];
          if (r >= k)
            continue;
          while (ancestor[r] != -1 && ancestor[r] != k)
            {
              const int next = ancestor[r];
              ancestor[r]    = k;
              r              = next;
            }
          if (ancestor[r] == -1)
            {
              ancestor[r] = k;
              parent[r]   = k;
            }
        }
    {
      std::vector<int> head(n, -1), next(n, -1), order, stack;
      order.reserve(n);
      for (int j = n - 1; j >= 0; --j) // children listed in increasing order
        if (parent[j] >= 0)
          {
            next[j]         = head[parent[j]];
            head[parent[j]] = j;
          }
      for (int root = 0; root < n; ++root)
        {
          if (parent[root] != -1)
            continue;
          stack.push_back(root);
          while (!stack.empty())
            {
              const int j = stack.back();
              if (head[j] >= 0)
                {
                  const int c = head[j];
                  head[j]     = next[c];
                  stack.push_back(c);
                }
              else
                {
                  order.push_back(j);
                  stack.pop_back();
                }
            }
        }
      bool identity = true;
      for (int k = 0; k < n; ++k)
        identity = identity && order[k] == k;
      if (!identity)
        {
          std::vector<int> old_inverse = inverse;
          for (int k = 0; k < n; ++k)
            inverse[k] = old_inverse[order[k]];
          for (int k = 0; k < n; ++k)
            permutation[inverse[k]] = k;
          graph();
          std::vector<int> new_of(n), old_parent = parent;
          for (int k = 0; k < n; ++k)
            new_of[order[k]] = k;
          for (int j = 0; j < n; ++j)
            parent[new_of[j]] = old_parent[j] < 0 ? -1 : new_of[old_parent[j]];
        }
    }

    // Each column's structure below the diagonal: its entries of A + Aᵀ and
    // its children's structures (flat, in column order).
    std::vector<int> column_start(n + 1, 0), structure, mark(n, -1), children(n, 0), child_head(n, -1),
      child_next(n, -1);
    structure.reserve(4 * start[n]);
    for (int j = n - 1; j >= 0; --j)
      if (parent[j] >= 0)
        {
          ++children[parent[j]];
          child_next[j]         = child_head[parent[j]];
          child_head[parent[j]] = j;
        }
    for (int j = 0; j < n; ++j)
      {
        const std::size_t begin = structure.size();
        mark[j]                 = j;
        for (int q = start[j]; q < start[j + 1]; ++q)
          if (adjacent[q] > j && mark[adjacent[q]] != j)
            {
              mark[adjacent[q]] = j;
              structure.push_back(adjacent[q]);
            }
        for (int c = child_head[j]; c >= 0; c = child_next[c])
          for (int q = column_start[c]; q < column_start[c + 1]; ++q)
            if (mark[structure[q]] != j)
              {
                mark[structure[q]] = j;
                structure.push_back(structure[q]);
              }
        std::sort(structure.begin() + begin, structure.end());
        column_start[j + 1] = structure.size();
      }
    const auto count = [&](const int j) { return column_start[j + 1] - column_start[j]; };

    // Supernodes: j joins j − 1's when it is j − 1's parent and only child
    // and their structures agree (fundamental), or, relaxed as CHOLMOD
    // does, when the merged supernode's explicit zeros stay a small share
    // of its entries (the dense kernels gain more on larger fronts than the
    // zeros cost: tiny fronts ran at ~3 instructions per multiply-add).
    first.clear();
    supernode_of.resize(n);
    for (int j = 0; j < n; ++j)
      {
        bool join = j > 0 && parent[j - 1] == j;
        if (join && !(children[j] == 1 && count(j - 1) == count(j) + 1))
          {
            const int f = first.back(), k = j - f + 1, r = count(j);
            double    entries = 0, zeros = 0;
            for (int i = f; i <= j; ++i)
              {
                entries += (j - i) + r;
                zeros += (j - i) + r - count(i);
              }
            join = k <= relax_columns[0] ||
                   (k <= relax_columns[1] && zeros <= relax_zeros[0] * entries) ||
                   (k <= relax_columns[2] && zeros <= relax_zeros[1] * entries);
          }
        if (!join)
          first.push_back(j);
        supernode_of[j] = first.size() - 1;
      }
    const int supernodes = first.size();
    first.push_back(n);
    row_start.assign(supernodes + 1, 0);
    rows.clear();
    for (int s = 0; s < supernodes; ++s)
      {
        const int last = first[s + 1] - 1;
        rows.insert(rows.end(), structure.begin() + column_start[last],
                    structure.begin() + column_start[last + 1]);
        row_start[s + 1] = rows.size();
      }

    // Children of each supernode (in order), their rows' places in its front.
    std::vector<int> parent_supernode(supernodes, -1), child_count(supernodes + 1, 0);
    for (int s = 0; s < supernodes; ++s)
      if (row_start[s + 1] > row_start[s])
        {
          parent_supernode[s] = supernode_of[rows[row_start[s]]];
          ++child_count[parent_supernode[s] + 1];
        }
    child_start.assign(child_count.begin(), child_count.end());
    std::partial_sum(child_start.begin(), child_start.end(), child_start.begin());
    child.resize(child_start[supernodes]);
    {
      std::vector<int> fill(child_start.begin(), child_start.end() - 1);
      for (int s = 0; s < supernodes; ++s)
        if (parent_supernode[s] >= 0)
          child[fill[parent_supernode[s]]++] = s;
    }
    relative_start.assign(supernodes + 1, 0);
    relative.clear();
    std::vector<int> place(n, -1);
    factor_start.assign(supernodes + 1, 0);
    leading.resize(supernodes);
    largest_front = 0;
    work = assembly = 0;
    std::size_t stack_size = 0;
    largest_stack          = 0;
    std::vector<std::size_t> stacked(supernodes, 0);
    for (int s = 0; s < supernodes; ++s)
      {
        const int k = first[s + 1] - first[s], r = row_start[s + 1] - row_start[s], m = k + r;
        for (int c = first[s]; c < first[s + 1]; ++c)
          place[c] = c - first[s];
        for (int t = 0; t < r; ++t)
          place[rows[row_start[s] + t]] = k + t;
        leading[s]        = padded(m);
        factor_start[s + 1] = factor_start[s] + static_cast<std::size_t>(m) * k + static_cast<std::size_t>(k) * r;
        largest_front     = std::max(largest_front, static_cast<std::size_t>(leading[s]) * m);
        for (int q = child_start[s]; q < child_start[s + 1]; ++q)
          {
            const int c = child[q];
            for (int t = row_start[c]; t < row_start[c + 1]; ++t)
              relative.push_back(place[rows[t]]);
            stack_size -= stacked[c];
            assembly += double(stacked[c]);
          }
        relative_start[s + 1] = relative.size();
        stacked[s]            = static_cast<std::size_t>(r) * r;
        stack_size += stacked[s];
        largest_stack = std::max(largest_stack, stack_size);
        assembly += double(leading[s]) * m;
        // Left-looking in the front: column c takes min(c, k) pivots.
        for (int c = 0; c < m; ++c)
          for (int p = 0; p < std::min(c, k); ++p)
            work += m - p - 1;
      }
    relative_start.resize(supernodes + 1);
    // Children's relative indices are stored by child: re-index.
    {
      std::vector<int> by_child(relative.size());
      std::vector<int> child_relative_start(supernodes + 1, 0);
      for (int s = 0; s < supernodes; ++s)
        child_relative_start[s + 1] = row_start[s + 1] - row_start[s];
      std::partial_sum(child_relative_start.begin(), child_relative_start.end(), child_relative_start.begin());
      std::size_t at = 0;
      for (int s = 0; s < supernodes; ++s)
        for (int q = child_start[s]; q < child_start[s + 1]; ++q)
          {
            const int c = child[q], r = row_start[c + 1] - row_start[c];
            std::copy(relative.begin() + at, relative.begin() + at + r, by_child.begin() + child_relative_start[c]);
            at += r;
          }
      relative.swap(by_child);
      relative_start.swap(child_relative_start);
    }
    if (!place_entries(offsets, columns))
      throw std::logic_error("FrontalFactorization: an entry outside its own analysis");
  }

  bool FrontalFactorization::fit(const int *offsets, const int *columns)
  {
    return place_entries(offsets, columns);
  }

  bool FrontalFactorization::place_entries(const int *offsets, const int *columns)
  {
    // Entry (i, j) belongs to the front of column min(i, j)'s supernode, at
    // the places of i and j there.
    const int supernodes = first.size() - 1;
    const int entries    = offsets[n];
    std::vector<int> owner(entries), count(supernodes + 1, 0);
    for (int row = 0; row < n; ++row)
      for (int k = offsets[row]; k < offsets[row + 1]; ++k)
        {
          owner[k] = supernode_of[std::min(permutation[row], permutation[columns[k]])];
          ++count[owner[k] + 1];
        }
    std::partial_sum(count.begin(), count.end(), count.begin());
    std::vector<int> row_of(entries);
    for (int row = 0; row < n; ++row)
      for (int k = offsets[row]; k < offsets[row + 1]; ++k)
        row_of[k] = row;
    entry.resize(entries);
    {
      std::vector<int> fill(count.begin(), count.end() - 1);
      for (int k = 0; k < entries; ++k)
        entry[fill[owner[k]]++] = k;
    }
    offset.resize(entries);
    std::vector<int> place(n, -1), stamp(n, -1);
    for (int s = 0; s < supernodes; ++s)
      {
        const int k = first[s + 1] - first[s];
        for (int c = first[s]; c < first[s + 1]; ++c)
          {
            place[c] = c - first[s];
            stamp[c] = s;
          }
        for (int t = row_start[s]; t < row_start[s + 1]; ++t)
          {
            place[rows[t]] = k + t - row_start[s];
            stamp[rows[t]] = s;
          }
        for (int q = count[s]; q < count[s + 1]; ++q)
          {
            const int e = entry[q], i = permutation[row_of[e]], j = permutation[columns[e]];
            if (stamp[i] != s || stamp[j] != s)
              return false;
            offset[q] = place[i] + static_cast<std::size_t>(place[j]) * leading[s];
          }
      }
    entry_start.swap(count);
    return true;
  }

  bool FrontalFactorization::factorize(const double *values)
  {
    const int supernodes = first.size() - 1;
    factors.resize(factor_start[supernodes]);
    front.resize(largest_front);
    stack.resize(largest_stack);
    std::size_t top = 0; // the stack's end
    smallest_pivot_ratio = 1;
    for (int s = 0; s < supernodes; ++s)
      {
        const int k = first[s + 1] - first[s], r = row_start[s + 1] - row_start[s], m = k + r,
                  ld = leading[s];
        double *const F = front.data();
        zero(F, static_cast<std::size_t>(ld) * m);
        for (int q = entry_start[s]; q < entry_start[s + 1]; ++q)
          F[offset[q]] += values[entry[q]];
        // The children's update matrices are the stack's top, in order.
        std::size_t below = top;
        for (int q = child_start[s]; q < child_start[s + 1]; ++q)
          {
            const int c = child[q], rc = row_start[c + 1] - row_start[c];
            below -= static_cast<std::size_t>(rc) * rc;
          }
        std::size_t at = below;
        for (int q = child_start[s]; q < child_start[s + 1]; ++q)
          {
            const int     c = child[q], rc = row_start[c + 1] - row_start[c];
            const int    *place = relative.data() + relative_start[c];
            const double *u     = stack.data() + at;
            for (int b = 0; b < rc; ++b, u += rc)
              {
                double *const column = F + static_cast<std::size_t>(place[b]) * ld;
                for (int a = 0; a < rc; ++a)
                  column[place[a]] += u[a];
              }
            at += static_cast<std::size_t>(rc) * rc;
          }
        top = below;

        for (int c = 0; c < m; ++c)
          {
            double *const a = F + static_cast<std::size_t>(c) * ld;
            if (c >= k)
              {
                // Right of the pivots: two columns per pass.
                if (c + 1 < m)
                  update_columns(a, a + ld, F, ld, k);
                else
                  update_column(a, F, ld, k);
                ++c;
                continue;
              }
            update_column(a, F, ld, c);
            const double largest = largest_below(a, c, ld);
            const double pivot   = a[c];
            if (!(std::abs(pivot) > 0) || std::abs(pivot) < threshold * largest)
              return false;
            if (largest > 0)
              smallest_pivot_ratio = std::min(smallest_pivot_ratio, std::abs(pivot) / largest);
            scale_below(a, c, ld, 1. / pivot);
          }
        // L's columns (m × k, U₁₁ above the diagonal), then U's rows right
        // of them (k × r), then the update matrix (r × r) onto the stack.
        double *f = factors.data() + factor_start[s];
        for (int c = 0; c < k; ++c, f += m)
          std::copy(F + static_cast<std::size_t>(c) * ld, F + static_cast<std::size_t>(c) * ld + m, f);
        for (int c = k; c < m; ++c, f += k)
          std::copy(F + static_cast<std::size_t>(c) * ld, F + static_cast<std::size_t>(c) * ld + k, f);
        double *u = stack.data() + top;
        for (int c = k; c < m; ++c, u += r)
          std::copy(F + static_cast<std::size_t>(c) * ld + k, F + static_cast<std::size_t>(c) * ld + m, u);
        top += static_cast<std::size_t>(r) * r;
      }
    ++factorizations;
    return true;
  }

  void FrontalFactorization::solve(double *x, const double *b) const
  {
    const int supernodes = first.size() - 1;
    work_vector.resize(2 * n);
    double *const y = work_vector.data();
    for (int i = 0; i < n; ++i)
      y[permutation[i]] = b[i];
    // Forward: L₁₁ in place, then the rows below take L₂₁ z (a dense
    // product into `t`, then scattered). Backward: z −= U₁₂ y(below)
    // (gathered), then U₁₁.
    double *const t = y + n;
    for (int s = 0; s < supernodes; ++s)
      {
        const int     k = first[s + 1] - first[s], r = row_start[s + 1] - row_start[s], m = k + r;
        const int    *below = rows.data() + row_start[s];
        const double *L     = factors.data() + factor_start[s];
        double *const z     = y + first[s];
        for (int p = 0; p < k; ++p)
          {
            const double        zp = z[p];
            const double *const l  = L + static_cast<std::size_t>(p) * m;
            for (int q = p + 1; q < k; ++q)
              z[q] -= zp * l[q];
          }
        if (r == 0)
          continue;
        std::fill(t, t + r, 0.);
        for (int p = 0; p < k; ++p)
          {
            const double        zp = z[p];
            const double *const l  = L + static_cast<std::size_t>(p) * m + k;
            if (zp != 0.)
              for (int i = 0; i < r; ++i)
                t[i] += zp * l[i];
          }
        for (int i = 0; i < r; ++i)
          y[below[i]] -= t[i];
      }
    for (int s = supernodes - 1; s >= 0; --s)
      {
        const int     k = first[s + 1] - first[s], r = row_start[s + 1] - row_start[s], m = k + r;
        const int    *below = rows.data() + row_start[s];
        const double *L     = factors.data() + factor_start[s];
        const double *U     = L + static_cast<std::size_t>(m) * k;
        double *const z     = y + first[s];
        for (int i = 0; i < r; ++i)
          t[i] = y[below[i]];
        for (int p = 0; p < k; ++p)
          {
            const double *const u   = U + p;
            double              sum = 0;
            for (int i = 0; i < r; ++i)
              sum += u[static_cast<std::size_t>(i) * k] * t[i];
            z[p] -= sum;
          }
        for (int q = k - 1; q >= 0; --q)
          {
            const double *const u = L + static_cast<std::size_t>(q) * m;
            z[q] /= u[q];
            const double zq = z[q];
            for (int p = 0; p < q; ++p)
              z[p] -= zq * u[p];
          }
      }
    for (int i = 0; i < n; ++i)
      x[i] = y[permutation[i]];
  }
} // namespace anvil
