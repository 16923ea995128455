// The band LU's elimination and substitution (see the header): LAPACK's
// dgbtf2 with partial pivoting, done in panels of four columns as dgbtrf
// does, with each entry's arithmetic that of dgbtf2's column by column.
//
// Why panels: one column at a time, every entry of the columns it updates
// is loaded and stored once per multiplier column, and each column pays the
// scan of U's row for its zeros; at two_blocks' 60–80 wide bands that was
// 2.3 instructions per multiply-add. A panel of four columns is factored
// as dgbtf2 would (its own four columns updated at once), then each column
// of U to its right takes the panel's four row exchanges and the four
// updates in one pass:
//   c_i ← (((c_i − l0_i u0) − l1_i u1) − l2_i u2) − l3_i u3,
// the operations dgbtf2 makes on c_i in steps j0 … j0 + 3, in its order,
// so the factors carry the same bits. (A zero u_k, skipped by dgbtf2, is
// applied here as c_i − l·0 = c_i: at most the sign of a zero entry moves.)
// The multipliers are those of each column with the panel's later row
// exchanges applied (the value c_i of row i at step k is the one the later
// exchange moves, with its multiplier).
#include <anvil/core/band_elimination.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace anvil
{
  namespace band_kernel
  {
    namespace
    {
      // Vectorised (the build's -O2 vectorises only loops without a
      // remainder) and compiled for AVX2 and for base x86-64, chosen at load
      // time. No FMA: each entry rounded as in the scalar loop, the answers
      // independent of the processor.
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

      /// One column, the four multiplier columns l + k ld, m a multiple of 4.
      ANVIL_BAND_KERNEL void rank4_blocks(double *__restrict a, const double *const ua,
                                          const double *__restrict l, const int ld, const int m)
      {
        const double        u0 = ua[0], u1 = ua[1], u2 = ua[2], u3 = ua[3];
        const double *const l0 = l, *const l1 = l + ld, *const l2 = l + 2 * ld, *const l3 = l + 3 * ld;
        for (int i = 0; i < m; ++i)
          a[i] = (((a[i] - u0 * l0[i]) - u1 * l1[i]) - u2 * l2[i]) - u3 * l3[i];
      }

      /// Two columns, the multipliers read once for both.
      ANVIL_BAND_KERNEL void rank4_blocks2(double *__restrict a, const double *const ua,
                                           double *__restrict b, const double *const ub,
                                           const double *__restrict l, const int ld, const int m)
      {
        const double        a0 = ua[0], a1 = ua[1], a2 = ua[2], a3 = ua[3];
        const double        b0 = ub[0], b1 = ub[1], b2 = ub[2], b3 = ub[3];
        const double *const l0 = l, *const l1 = l + ld, *const l2 = l + 2 * ld, *const l3 = l + 3 * ld;
        for (int i = 0; i < m; ++i)
          {
            const double x0 = l0[i], x1 = l1[i], x2 = l2[i], x3 = l3[i];
            a[i]            = (((a[i] - a0 * x0) - a1 * x1) - a2 * x2) - a3 * x3;
            b[i]            = (((b[i] - b0 * x0) - b1 * x1) - b2 * x2) - b3 * x3;
          }
      }

      /// Column j's pivot: the first row reaching its largest magnitude
      /// among rows j … j + last (dgbtf2's idamax), after L's zero tail is
      /// cut from last. −1 for a zero column.
      ANVIL_BAND_KERNEL int find_pivot(const double *const lj, int &last)
      {
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
          return -1;
        int p = 0;
        while (std::abs(lj[p]) != largest)
          ++p;
        return p;
      }
    } // namespace

    ANVIL_BAND_KERNEL double eliminate(const Band &b, int *const pivot, int *const column_end, int *const row_end,
                     int *const column_top)
    {
      const int n = b.n;
      // &A(r, c)
      const auto at = [&](const int c, const int r) {
        return b.values + static_cast<std::size_t>(c) * b.stride + b.diagonal + r - c;
      };
      for (int j = 0; j < n; ++j)
        column_top[j] = j;
      // The panel's multipliers, rows j0 … j0 + 3 + lower (+ a block's padding).
      const int           ld = ((b.lower + 8) + 3) & ~3;
      std::vector<double> panel(4 * ld);
      double              multiply_adds = 0;
      for (int j0 = 0; j0 < n; j0 += 4)
        {
          const int nb = std::min(4, n - j0), panel_end = j0 + nb - 1;
          int       exchange[4] = {0, 0, 0, 0}, length[4] = {0, 0, 0, 0}, reach = panel_end;
          for (int k = 0; k < nb; ++k)
            {
              const int     j    = j0 + k;
              double *const lj   = at(j, j);
              int           last = std::min(b.lower, n - 1 - j);
              if (column_end[j] > 0) // the caller's bound: zeros below it (not scanned)
                last = std::min(last, column_end[j]);
              const int     p    = find_pivot(lj, last);
              if (p < 0)
                return -1. - j;
              pivot[j]      = j + p;
              column_end[j] = last;
              exchange[k]   = p;
              length[k]     = last;
              // The columns right of the panel the exchanges reach: both rows'.
              reach = std::max({reach, row_end[j], row_end[j + p]});
              if (p != 0)
                {
                  for (int c = j; c <= panel_end; ++c)
                    std::swap(at(c, j)[0], at(c, j)[p]);
                  std::swap(row_end[j], row_end[j + p]);
                }
              const double inverse_pivot = 1. / lj[0];
              for (int i = 1; i <= last; ++i)
                lj[i] *= inverse_pivot;
              // Fill follows U's row j down the multipliers.
              for (int i = 1; i <= last; ++i)
                row_end[j + i] = std::max(row_end[j + i], row_end[j]);
              // (U's row is recorded for the solve even where L's column is empty.)
              const int blocks = (last + 3) & ~3;
              for (int c = j + 1; c <= std::min(panel_end, row_end[j]); ++c)
                {
                  double *const a = at(c, j);
                  if (*a == 0.)
                    continue;
                  column_top[c] = std::min(column_top[c], j);
                  multiply_adds += last;
                  if (last > 0)
                    axpy_blocks(a + 1, a[0], lj + 1, blocks);
                }
            }
          if (reach <= panel_end)
            continue; // (a last panel of fewer than four columns ends here)

          // The multipliers in the rows' final order: column k with the
          // panel's later exchanges applied.
          int bottom = 3;
          for (int k = 0; k < 4; ++k)
            bottom = std::max(bottom, k + length[k]);
          const int rows = 4 + (((bottom - 3) + 3) & ~3); // rows j0 … j0 + rows − 1
          for (int k = 0; k < 4; ++k)
            {
              double *const l = panel.data() + k * ld;
              std::fill(l, l + rows, 0.);
              const double *const lk = at(j0 + k, j0 + k);
              for (int i = 1; i <= length[k]; ++i)
                l[k + i] = lk[i];
              for (int later = k + 1; later < 4; ++later)
                std::swap(l[later], l[later + exchange[later]]);
            }
          const double *const l0 = panel.data(), *const l1 = l0 + ld, *const l2 = l1 + ld;
          double              u[2][4];
          double             *held = nullptr;
          int                 exchanged[4], exchanges = 0;
          for (int k = 0; k < 4; ++k)
            if (exchange[k] != 0)
              exchanged[exchanges++] = k;
          for (int c = panel_end + 1; c <= reach; ++c)
            {
              double *const a = at(c, j0);
              // Most columns within the rows' reach hold none of the panel's
              // rows of U (the reach is a bound).
              if (exchanges == 0 && a[0] == 0. && a[1] == 0. && a[2] == 0. && a[3] == 0.)
                continue;
              for (int e = 0; e < exchanges; ++e)
                {
                  const int k = exchanged[e];
                  std::swap(a[k], a[k + exchange[k]]);
                }
              // The panel's rows of U: dgbtf2's steps on rows j0 … j0 + 3.
              a[1] -= l0[1] * a[0];
              a[2] -= l0[2] * a[0];
              a[2] -= l1[2] * a[1];
              a[3] -= l0[3] * a[0];
              a[3] -= l1[3] * a[1];
              a[3] -= l2[3] * a[2];
              const bool nonzero[4] = {a[0] != 0., a[1] != 0., a[2] != 0., a[3] != 0.};
              multiply_adds += nonzero[0] * length[0] + nonzero[1] * length[1] +
                               nonzero[2] * length[2] + nonzero[3] * length[3];
              const int first = nonzero[0] ? 0 : nonzero[1] ? 1 : nonzero[2] ? 2 : nonzero[3] ? 3 : -1;
              if (first < 0)
                continue;
              column_top[c] = std::min(column_top[c], j0 + first);
              if (rows == 4)
                continue;
              double *const ua = u[held ? 1 : 0];
              std::copy(a, a + 4, ua);
              if (!held)
                {
                  held = a;
                  continue;
                }
              rank4_blocks2(held + 4, u[0], a + 4, u[1], l0 + 4, ld, rows - 4);
              held = nullptr;
            }
          if (held)
            rank4_blocks(held + 4, u[0], l0 + 4, ld, rows - 4);
        }
      return multiply_adds;
    }

    ANVIL_BAND_KERNEL void substitute(const Band &b, const int *const pivot,
                                      const int *const column_end, const int *const column_top,
                                      double *const y)
    {
      // L: the exchanges and the multipliers in the order they were made.
      for (int j = 0; j < b.n; ++j)
        {
          if (pivot[j] != j)
            std::swap(y[j], y[pivot[j]]);
          const double *__restrict l =
            b.values + static_cast<std::size_t>(j) * b.stride + b.diagonal + 1;
          double *__restrict below = y + j + 1;
          const double yj          = y[j];
          if (yj != 0.)
            for (int i = 0; i < column_end[j]; ++i)
              below[i] -= yj * l[i];
        }
      // U, column by column from the last, from its first nonzero row.
      for (int j = b.n - 1; j >= 0; --j)
        {
          const double *uj    = b.values + static_cast<std::size_t>(j) * b.stride + b.diagonal;
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

    // No loop distribution: it would make the loop a memset, whose `rep
    // stosb` is as fast but counts an instruction per byte under callgrind
    // (it hid the kernel's counts behind the zeroing).
    __attribute__((target_clones("avx2", "default"),
                   optimize("tree-loop-vectorize", "no-tree-loop-distribute-patterns"))) void
    zero(double *__restrict a, const std::size_t m)
    {
      for (std::size_t i = 0; i < m; ++i)
        a[i] = 0.;
    }
#undef ANVIL_BAND_KERNEL
  } // namespace band_kernel
} // namespace anvil
