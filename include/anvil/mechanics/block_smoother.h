#pragma once

// Aggregate-block Gauss–Seidel: the fine-level smoother of the mechanics'
// AMG for nearly incompressible (plastic F-bar) tangents (doc/linear_solver.md,
// "Session 10").

#include <cstddef>
#include <vector>

class Epetra_CrsMatrix;
struct ML_Smoother_Struct;

namespace anvil
{
  /**
   * Multiplicative block Gauss–Seidel on aggregates of nodes: each block is
   * a node and its (up to 3^dim − 1) neighbours in K's graph, as ML's
   * uncoupled aggregation would make them, its diagonal block of K inverted
   * once (dense LU with partial pivoting, then the explicit inverse) when
   * the smoother is built.
   *
   * Why blocks of this size: in plastic flow the tangent is nearly
   * incompressible (bulk / shear ≈ 500), and every field with small
   * cell-centre divergence is low-energy at any wavelength. A point smoother
   * cannot reduce those; a block of 3 × 3 × 3 nodes (81 dofs) touches 64
   * cells, so it holds 81 − 64 = 17 local divergence-free fields which it
   * solves exactly (a node block, 3 dofs against 8 cells, holds none).
   *
   * Only the locally owned rows and columns are used: across processes the
   * smoother is block Jacobi (the off-process couplings are left to the
   * coarse levels). The rows of a node must be consecutive (components
   * rows per node, as rigid_body_modes() checks).
   */
  class AggregateBlockSmoother
  {
  public:
    AggregateBlockSmoother(const Epetra_CrsMatrix &K, unsigned int components);

    /// One forward (backward) sweep over the blocks: x += A_BB⁻¹ (b − K x)_B
    /// block after block, with the x already updated.
    void forward_sweep(double *x, const double *b) const;
    void backward_sweep(double *x, const double *b) const;

    /// Sweeps per smoothing (ML gives its user smoothers no sweep count),
    /// alternating in direction, the pre-smoother starting forward.
    unsigned int sweeps = 1;

    unsigned int n_blocks() const { return block_start.size() - 1; }
    /// Bytes held (factors, blocks, the column map).
    std::size_t memory_consumption() const;

    /**
     * ML's user-defined smoother ("smoother: user-defined function"): the
     * pre-smoother sweeps forward, the post-smoother backward (a symmetric
     * V-cycle). ML gives the function no data of ours, so it applies the
     * smoother made active by an ActiveScope (one at a time per process).
     */
    static int ml_smoother(ML_Smoother_Struct *sm, int x_length, double *x, int rhs_length, double *rhs);

    /// Makes @p s the smoother ml_smoother() applies, for the scope's life.
    class ActiveScope
    {
    public:
      explicit ActiveScope(const AggregateBlockSmoother *s);
      ~ActiveScope();

    private:
      const AggregateBlockSmoother *previous;
    };

  private:
    void solve_block(unsigned int block, double *x, const double *b) const;

    const Epetra_CrsMatrix &matrix;
    int                     n_rows;
    /// Local column → local row (−1: a ghost column, skipped).
    std::vector<int> column_to_row;
    /// Rows of block k: rows[block_start[k] .. block_start[k+1]).
    std::vector<unsigned int> block_start, rows;
    /// The inverse of each diagonal block (row-major, n_k × n_k).
    std::vector<std::size_t> factor_start;
    std::vector<double>      factors;
    mutable std::vector<double> work;
  };
} // namespace anvil
