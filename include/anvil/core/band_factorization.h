#pragma once

// A banded LU with partial pivoting (LAPACK's dgbtf2 layout and algorithm)
// of a sparse matrix renumbered by reverse Cuthill–McKee, for small 2D
// systems where KLU's sparse bookkeeping costs several times the arithmetic
// (doc/linear_solver.md, "Band LU"). One process only: the matrix comes as
// local CSR arrays (rows sorted or not), the vectors as plain arrays.
//
// The ordering and the band's width depend on the pattern only; a new
// pattern whose entries all fall inside the band keeps them (a contact
// coupling that comes and goes costs nothing), one that does not is ordered
// anew. Within the band the elimination skips exact zeros: a multiplier
// column is cut at its last nonzero and a row of U at its zero entries, so
// the work follows the envelope the numbering makes, not the band's
// rectangle, and a slack band costs little.

#include <anvil/core/band_elimination.h>

#include <vector>

namespace anvil
{
  class BandFactorization
  {
  public:
    /// Keep the ordering if every entry of the CSR pattern (n rows) lies in
    /// the band; else reorder (RCM on the symmetrized graph). true if the
    /// ordering was made anew.
    bool analyze(int n, const int *offsets, const int *columns);
    /// A pattern outside the band keeps the ordering if its band widths are
    /// within this factor of those the ordering was made with.
    double kept_growth = 1.25;
    /// Factor the values of the pattern given to the last analyze().
    void factorize(const int *offsets, const int *columns, const double *values);
    /// x = A⁻¹ b; x and b may be the same array.
    void solve(double *x, const double *b) const;

    int size() const { return n; }
    int lower_bandwidth() const { return lower; }
    int upper_bandwidth() const { return upper; }
    /// The flops of a factorisation without pivoting on the envelope of the
    /// pattern (Σ_j 2 l_j u_j with l_j, u_j the column's and the row's
    /// extent after fill): what the zero-skipping elimination costs when no
    /// row is exchanged; pivoting adds to it, bounded by the band.
    double estimated_flops() const { return envelope_flops; }
    /// Multiply-adds of the last factorisation (×2 for flops).
    double last_multiply_adds = 0;
    unsigned long orderings = 0, factorizations = 0;

  private:
    band_kernel::Band layout() const;
    bool choose_ordering(int size, const int *offsets, const int *columns);
    void place(const int *offsets, const int *columns); // positions, row ends
    void order(const int *offsets, const int *columns);
    void measure(const int *offsets, const int *columns); // widths, envelope
    bool fits(const int *offsets, const int *columns) const;

    int                 n = 0, lower = 0, upper = 0, stride = 0;
    int                 ordered_lower = 0, ordered_upper = 0; // when ordered
    std::vector<int>    permutation; // new index of old row i
    std::vector<int>    inverse;     // old index of new row k
    std::vector<double> band;        // column-major (band_kernel::Band)
    std::vector<int>    pivot;       // row exchanged with row j at step j
    std::vector<int>    column_end;  // last nonzero row of L's column j, minus j
    std::vector<int>    column_top;  // first nonzero row of U's column j
    std::vector<std::size_t> position;   // the pattern's k-th entry in band
    std::vector<int>    pattern_row_end; // each row's last column in the pattern
    /// L's column j cannot reach below the last row whose pattern starts at
    /// or left of column j: that row − j (fill and exchanges stay above it).
    std::vector<int>    column_reach;
    std::vector<int>    row_end;         // the same, grown by the elimination
    double              envelope_flops = 0;
  };
} // namespace anvil
