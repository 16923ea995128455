#pragma once

// A KLU factorisation (Trilinos Amesos) that keeps its symbolic part and its
// pivot sequence: the ordering depends on the pattern only, so a matrix whose
// values change (M + γK for a new γ, a new configuration) costs a numeric
// refactorisation alone (klu_refactor, no pivot search; Amesos factors with
// pivoting again when the condition estimate min|u_ii| / max|u_ii| of the
// refactored U falls below 1e-12). On contrib/bench/heat_plate.prm the
// temperatures are those of TrilinosWrappers::SolverDirect("Amesos_Klu") to
// the last printed digit; the factorisations cost 25 % less.
//
// On one process the matrix goes to KLU directly (no Amesos): the analysis is
// then kept across new matrix objects (a contact pattern made anew) whose
// pattern fits in the analysed one (the missing entries factored as zeros).
// Where the pattern is the analysed one, KLU gets the same arrays Amesos_Klu
// gives it, and the same calls: the same bits.
//
// Old pivots can be poor for new values without the condition estimate
// noticing (growth in L). So after the first solve with reused pivots the normwise
// backward error |b − A x|∞ / (|A|∞ |x|∞ + |b|∞) is checked (one product
// with A, a few per cent of a factorisation); above backward_error_limit the
// matrix is factored with pivoting anew and the system solved again.
//
// On one process the factorisation may instead be a band LU on a reverse
// Cuthill–McKee numbering (BandFactorization), which on small 2D systems
// costs a fraction of KLU's: `method` chooses (automatic: the cheaper by the
// flop estimates, see choose_band() and doc/linear_solver.md "Band LU").

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <string>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;

namespace anvil
{
  class BandFactorization;

  class KluFactorization
  {
  public:
    /// klu: always KLU. band: the band LU on one process (KLU on several).
    /// automatic: the band LU where its estimated work, weighted by the
    /// measured instructions per flop, is below KLU's.
    enum class Method
    {
      klu,
      band,
      automatic
    };
    static Method parse_method(const std::string &name); // "klu", "band", "auto"

    /// @p reuse_pivots: refactorise with the last pivoting factorisation's
    /// pivot sequence (klu_refactor), checked as above. false: pivot anew
    /// every time, and only the symbolic analysis is kept.
    explicit KluFactorization(bool reuse_pivots = true);
    ~KluFactorization();

    /// Factor @p A (its values as they are now). The symbolic analysis is
    /// redone only for another matrix object or after clear().
    void factorize(const dealii::TrilinosWrappers::SparseMatrix &A);
    /// x = A⁻¹ b with the last factorisation.
    void solve(dealii::TrilinosWrappers::MPI::Vector &x, const dealii::TrilinosWrappers::MPI::Vector &b);
    /// A new pattern may come (call after a new setup): Amesos's analysis is
    /// dropped; the direct path's is checked against the next matrix.
    void clear();
    bool empty() const { return matrix == nullptr && band_matrix == nullptr; }

    Method method = Method::klu;
    /// "band" or "klu": what the last factorisation used.
    const char *last_method() const { return band_active ? "band" : "klu"; }
    /// The band solver (null until a band path was considered).
    const BandFactorization *band_solver() const { return band.get(); }
    /// KLU's flop estimate for the pattern the choice was made on (AMD's,
    /// from klu_analyze), −1 before.
    double klu_estimated_flops = -1;

    /// A solve with reused pivots whose backward error exceeds this is
    /// repeated after a factorisation with pivoting (round-off of a stable
    /// LU: ~1e-16 n^½).
    static constexpr double backward_error_limit = 1e-12;

    unsigned long symbolic_factorizations = 0, numeric_factorizations = 0;
    /// New matrix objects whose pattern fitted the kept analysis (direct path).
    unsigned long analyses_kept = 0;
    /// New patterns whose analysis was kept from an earlier matrix (the
    /// last few patterns' analyses are kept: contact patterns recur).
    unsigned long analyses_recalled = 0;
    /// Factorisations with pivoting made because a solve with reused pivots
    /// failed the backward-error check.
    unsigned long pivoting_retries = 0;
    unsigned long band_factorizations = 0;

  private:
    struct Direct; // KLU called directly (one process)

    void numeric_factorization(bool reuse);
    bool factorize_direct(const Epetra_CrsMatrix &A);
    void solve_direct(double *x, const double *b);
    bool choose_band(const Epetra_CrsMatrix &A, int n, const int *offsets, const int *columns);

    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    solver;
    std::unique_ptr<Direct>               direct;
    std::unique_ptr<BandFactorization>    band;
    const Epetra_CrsMatrix               *band_matrix = nullptr; // the band's last
    long long                             band_nonzeros = -1;
    bool                                  band_active = false;
    bool                                  band_chosen = false;
    const Epetra_CrsMatrix               *matrix = nullptr; // the one analysed
    long long                             nonzeros = -1;
    bool                                  reuse_pivots;
    /// The last numeric factorisation may have reused pivots (Amesos does
    /// not say whether it fell back to pivoting).
    bool                                  pivots_reused = false;
    double                                matrix_norm   = 0; // |A|∞ of the last factorisation
  };
} // namespace anvil
