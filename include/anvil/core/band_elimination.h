#pragma once

// The band LU's kernels (source/core/band_elimination.cc), for
// BandFactorization: dgbtf2's elimination with partial pivoting in panels
// of four columns, and dgbtrs' substitution.

#include <cstddef>

namespace anvil
{
  namespace band_kernel
  {
    /// The band, column-major: A(i, j) at band[j stride + diagonal + i − j]
    /// for j − diagonal ≤ i ≤ j + lower + 3. diagonal = lower + upper + 3:
    /// U's fill reaches lower + upper above the diagonal, three zero rows
    /// above that let a panel's four rows be read in every column it
    /// updates; three zero rows below each column let the updates run whole
    /// blocks of four rows.
    struct Band
    {
      double *values;
      int     n, lower, upper, stride, diagonal;
    };

    inline int diagonal_row(const int lower, const int upper) { return lower + upper + 3; }
    inline int column_stride(const int lower, const int upper)
    {
      return diagonal_row(lower, upper) + lower + 4;
    }

    /// The LU factors in place, with partial pivoting (the row dgbtf2's
    /// idamax picks), skipping exact zeros. @p pivot: the row exchanged
    /// with row j; @p column_end: L's column j's last nonzero row − j (on
    /// entry, where > 0, a bound on it: the rows below stay exact zeros);
    /// @p row_end: on entry each row's last column in the pattern (≥ the
    /// row), grown to the last column each row can reach; @p column_top:
    /// U's first nonzero row of each column. Returns the multiply-adds
    /// (Σ over columns j of L's length × U's nonzeros in row j), or −1 − j
    /// for a zero column j.
    double eliminate(const Band &band, int *pivot, int *column_end, int *row_end, int *column_top);

    /// y = U⁻¹ L⁻¹ P y with eliminate()'s factors.
    void substitute(const Band &band, const int *pivot, const int *column_end, const int *column_top,
                    double *y);

    /// a[0, m) = 0.
    void zero(double *a, std::size_t m);
  } // namespace band_kernel
} // namespace anvil
