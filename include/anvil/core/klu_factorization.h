#pragma once

// A KLU factorisation (Trilinos Amesos) that keeps its symbolic part and its
// pivot sequence: the ordering depends on the pattern only, so a matrix whose
// values change (M + γK for a new γ, a new configuration) costs a numeric
// refactorisation alone (klu_refactor, no pivot search; Amesos factors with
// pivoting again when the condition estimate says the old pivots are poor).
// On contrib/bench/heat_plate.prm the temperatures are those of
// TrilinosWrappers::SolverDirect("Amesos_Klu") to the last printed digit;
// the factorisations cost 25 % less.

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;

namespace anvil
{
  class KluFactorization
  {
  public:
    /// @p reuse_pivots: refactorise with the first factorisation's pivot
    /// sequence (klu_refactor; the heat problem's M + γK). false: pivot
    /// anew every time, so the answer is a fresh KLU solve's bit for bit
    /// (the mechanics, whose contact and plasticity change the matrix
    /// more), and only the symbolic analysis is kept.
    explicit KluFactorization(bool reuse_pivots = true);
    ~KluFactorization();

    /// Factor @p A (its values as they are now). The symbolic analysis is
    /// redone only for another matrix object or after clear().
    void factorize(const dealii::TrilinosWrappers::SparseMatrix &A);
    /// x = A⁻¹ b with the last factorisation.
    void solve(dealii::TrilinosWrappers::MPI::Vector &x, const dealii::TrilinosWrappers::MPI::Vector &b);
    /// Forget the analysis (the pattern changes: call after a new setup).
    void clear();
    bool empty() const { return !solver; }

    unsigned long symbolic_factorizations = 0, numeric_factorizations = 0;

  private:
    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    solver;
    const Epetra_CrsMatrix               *matrix = nullptr; // the one analysed
    long long                             nonzeros = -1;
    bool                                  reuse_pivots;
  };
} // namespace anvil
