#pragma once

// A single-precision copy of a smoothed level's matrix, stored by nodal
// blocks, for the multilevel cycle's smoothers and residuals
// (geometric_coarse_space.h). Why: at 1 M DoFs the cycle streams K nine
// times per GMRES iteration from memory, and Epetra's rows cost 12 bytes an
// entry (value and column index); two ranks share one memory bus, so the
// solve, not the assembly, held np 2's speed-up below 1.7 (issue 15). A
// dim × dim block of floats with one column index is 4.4 bytes an entry.
// The smoother is a preconditioner inside double-precision GMRES, whose own
// products stay on K: the answer is GMRES's to its tolerance, and the
// cycle's rounding (float's 6e-8) is far below what the smoother removes
// (doc/linear_solver.md, session 26).

#include <memory>
#include <vector>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_Operator.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

class Epetra_CrsMatrix;
class Epetra_Import;
class Epetra_Map;
class Epetra_Comm;
class Epetra_MultiVector;
class Epetra_Vector;

namespace anvil
{
  /**
   * y = A x with A's entries rounded to float, x and y in double. Made by
   * make() only when A's owned rows come in nodes: runs of @p block
   * consecutive global indices block·n … block·n + block − 1 (deal.II's
   * Q1^dim numbering, one vertex's dofs together; the coarse spaces' dim ·
   * node + component). Otherwise make() returns nullptr on every process
   * and the caller keeps A. A may be destroyed after make().
   */
  class FloatBlockMatrix : public Epetra_Operator
  {
  public:
    static std::unique_ptr<FloatBlockMatrix> make(const Epetra_CrsMatrix &A, unsigned int block);
    ~FloatBlockMatrix() override;

    int Apply(const Epetra_MultiVector &X, Epetra_MultiVector &Y) const override;
    int ApplyInverse(const Epetra_MultiVector &, Epetra_MultiVector &) const override { return -1; }
    int SetUseTranspose(bool) override { return -1; }
    double NormInf() const override { return 0; }
    const char *Label() const override { return "anvil::FloatBlockMatrix"; }
    bool UseTranspose() const override { return false; }
    bool HasNormInf() const override { return false; }
    const Epetra_Comm &Comm() const override;
    const Epetra_Map  &OperatorDomainMap() const override;
    const Epetra_Map  &OperatorRangeMap() const override;

    /// Bytes held (the blocks, their columns and the import vector).
    std::size_t memory_consumption() const;

  private:
    explicit FloatBlockMatrix(const Epetra_CrsMatrix &A, unsigned int block);

    unsigned int block;
    /// A's domain, copied: a middle level's A is freed once this copy is
    /// made (only the coarser level's Galerkin product needed it).
    std::unique_ptr<Epetra_Map>    domain;
    /// np > 1: the ghost nodes, whole (the .cc says why).
    std::unique_ptr<Epetra_Map>    column_map;
    /// Block columns below this are owned (x's own entries), the rest ghosts.
    int                            n_owned_blocks = 0;
    /// Block row i's first block in a ghost column.
    std::vector<int>               ghosts_from;
    std::unique_ptr<Epetra_Import> importer;
    /// Block row i's blocks: [row_start[i], row_start[i + 1]).
    std::vector<int>   row_start;
    /// A block's column: its node in x's layout (owned nodes, then ghost nodes).
    std::vector<int>   columns;
    /// block × block floats per block, column-major (and `block` spare at the end).
    std::vector<float> values;
    /// x's ghost entries (np > 1).
    mutable std::unique_ptr<Epetra_Vector> x_columns;
  };
} // namespace anvil
