#pragma once

// A multifrontal LU on a minimum-degree ordering, for the small 2D systems
// where BandFactorization's reverse Cuthill–McKee band is wide: on
// two_blocks the upper block sits on the lower one, so RCM's levels hold both
// blocks' columns and the band is 60–90 wide, while approximate minimum
// degree (AMD, on the graph of A + Aᵀ) needs about half the multiply-adds
// (doc/linear_solver.md, "Session 17").
//
// The elimination tree is postordered and cut into fundamental supernodes;
// each supernode's front (its columns and the rows its factor reaches) is a
// dense matrix: the entries of A and the children's update matrices are
// added into it, its pivot columns factored, the rest of it (the Schur
// complement) handed to the parent, so every multiply-add runs in a dense
// vectorised loop. The pivots are the diagonal ones (the mechanics' tangent
// is close to symmetric positive definite): a pivot smaller than
// `threshold` × its column's largest entry makes factorize() return false,
// and the caller factors with partial pivoting instead (the band).
//
// One process only: the matrix comes as local CSR arrays (rows sorted or
// not, no duplicates), the vectors as plain arrays.

#include <cstddef>
#include <vector>

namespace anvil
{
  class FrontalFactorization
  {
  public:
    /// Order the CSR pattern (n rows) by AMD and analyse it.
    void analyze(int n, const int *offsets, const int *columns);
    /// Analyse a new pattern with the kept ordering (no AMD): its entries
    /// then fit by construction.
    void reanalyze(const int *offsets, const int *columns);
    /// Whether every entry of the pattern lies in the analysed fronts; if so,
    /// the pattern's entries are placed and factorize() takes its values.
    bool fit(const int *offsets, const int *columns);
    /// Factor the values of the pattern last analysed or fitted. false if a
    /// diagonal pivot failed the threshold (the factors are then unusable).
    bool factorize(const double *values);
    /// x = A⁻¹ b; x and b may be the same array.
    void solve(double *x, const double *b) const;

    int size() const { return n; }
    int supernodes() const { return static_cast<int>(first.size()) - 1; }
    /// Multiply-adds of a factorisation (every front entry, zeros included).
    double multiply_adds() const { return work; }
    /// Doubles the fronts zero and add into per factorisation (front sizes²
    /// and update matrices), the traffic beside the multiply-adds.
    double assembly_entries() const { return assembly; }
    /// Multiply-adds at the last AMD ordering.
    double multiply_adds_at_ordering = 0;
    /// A pivot below this fraction of its column's largest magnitude fails.
    double threshold = 1e-3;
    /// Relaxed supernodes: a column joins its child's supernode if the
    /// merged one has at most relax_columns[0] columns, or at most
    /// relax_columns[1] (relax_columns[2]) and at most relax_zeros[0]
    /// (relax_zeros[1]) of its entries explicit zeros.
    int    relax_columns[3] = {4, 16, 48};
    double relax_zeros[2]   = {0.8, 0.1};
    /// The smallest |pivot| / column maximum of the last factorisation.
    double smallest_pivot_ratio = 1;
    unsigned long orderings = 0, analyses = 0, factorizations = 0;

  private:
    void symbolic(const int *offsets, const int *columns);
    bool place_entries(const int *offsets, const int *columns);

    int              n = 0;
    std::vector<int> permutation; // new index of old row i
    std::vector<int> inverse;     // old index of new row k

    // Supernodes, in postorder: columns [first[s], first[s + 1]), the rows
    // below them rows[row_start[s] … row_start[s + 1]), children
    // child[child_start[s] …], each supernode's rows' places in its
    // parent's front (relative[relative_start[c] …]).
    std::vector<int>         first, row_start, rows, child_start, child, relative_start, relative;
    std::vector<int>         supernode_of; // of each column
    std::vector<std::size_t> factor_start; // L's columns (ld × k), then U's rows (k × r)
    std::vector<int>         leading;      // the front's leading dimension (m rounded up to 4)
    std::size_t              largest_front = 0, largest_stack = 0;

    // The pattern's entries grouped by supernode: entry[entry_start[s] …]
    // is the CSR index, offset[…] its place in the front.
    std::vector<int>         entry_start, entry;
    std::vector<std::size_t> offset;

    std::vector<double> factors;
    mutable std::vector<double> work_vector;
    std::vector<double> front, stack;
    double              work = 0, assembly = 0;
  };
} // namespace anvil
