// KluFactorization: Amesos_Klu with the symbolic analysis and the pivots kept
// (see the header).
#include <deal.II/lac/trilinos_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_Comm.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <trilinos_klu_decl.h>

#include <anvil/core/band_factorization.h>
#include <anvil/core/klu_factorization.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <cmath>
#include <vector>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// |A|∞, the largest row sum of |a_ij| over all processes.
    double infinity_norm(const Epetra_CrsMatrix &A)
    {
      double largest = 0;
      for (int row = 0; row < A.NumMyRows(); ++row)
        {
          int     n      = 0;
          double *values = nullptr;
          int    *columns = nullptr;
          A.ExtractMyRowView(row, n, values, columns);
          double sum = 0;
          for (int k = 0; k < n; ++k)
            sum += std::abs(values[k]);
          largest = std::max(largest, sum);
        }
      double global = largest;
      A.Comm().MaxAll(&largest, &global, 1);
      return global;
    }

    /// n, the number of entries, then the CSR arrays (int offsets, int
    /// columns, double values) in the machine's byte order, to
    /// folder/matrix_<k>.bin, k counting the calls.
    void dump_matrix(const std::string &folder, const int n, const int *offsets, const int *columns,
                     const double *values)
    {
      static int  count = 0;
      FILE *const f     = std::fopen((folder + "/matrix_" + std::to_string(count++) + ".bin").c_str(), "wb");
      AssertThrow(f, ExcMessage("ANVIL_MATRIX_DUMP: cannot write to " + folder));
      const int entries = offsets[n];
      std::fwrite(&n, sizeof(int), 1, f);
      std::fwrite(&entries, sizeof(int), 1, f);
      std::fwrite(offsets, sizeof(int), n + 1, f);
      std::fwrite(columns, sizeof(int), entries, f);
      std::fwrite(values, sizeof(double), entries, f);
      std::fclose(f);
    }
  } // namespace

  /// KLU's objects and the analysed pattern: KLU reads the rows of A as the
  /// columns of Aᵀ (Amesos_Klu does the same and solves with tsolve).
  struct KluFactorization::Direct
  {
    Direct() { trilinos_klu_defaults(&common); }
    ~Direct() { free(); }
    void free()
    {
      if (numeric)
        trilinos_klu_free_numeric(&numeric, &common);
      if (symbolic)
        trilinos_klu_free_symbolic(&symbolic, &common);
    }

    trilinos_klu_common    common;
    trilinos_klu_symbolic *symbolic = nullptr;
    trilinos_klu_numeric  *numeric  = nullptr;
    int                    n        = 0;
    std::vector<int>       Ap, Ai; // the analysed pattern, rows sorted
    /// The matrix's k-th entry sits at Ai[position[k]]; empty: the matrix's
    /// pattern is the analysed one (its arrays are given to KLU as they are).
    std::vector<int>    position;
    std::vector<double> values; // the matrix on the analysed pattern
    /// L's and U's entries estimated by the analysis made for the choice
    /// of the band (choose_band), −1 before.
    double estimated_entries = -1;
    /// The band's estimated multiply-adds when KLU's estimate was made.
    double band_work_at_estimate = -1;
  };

  namespace
  {
    /// Where each entry of the pattern (offsets, columns) sits in (Ap, Ai),
    /// false if one is missing. Rows sorted in both.
    bool find_positions(const int n, const int *offsets, const int *columns,
                        const std::vector<int> &Ap, const std::vector<int> &Ai,
                        std::vector<int> &position)
    {
      position.resize(offsets[n]);
      for (int row = 0; row < n; ++row)
        {
          int at = Ap[row];
          for (int k = offsets[row]; k < offsets[row + 1]; ++k)
            {
              while (at < Ap[row + 1] && Ai[at] < columns[k])
                ++at;
              if (at == Ap[row + 1] || Ai[at] != columns[k])
                return false;
              position[k] = at++;
            }
        }
      return true;
    }
  } // namespace

  KluFactorization::KluFactorization(const bool reuse_pivots)
    : reuse_pivots(reuse_pivots)
  {}
  KluFactorization::~KluFactorization() = default;

  KluFactorization::Method KluFactorization::parse_method(const std::string &name)
  {
    if (name == "klu")
      return Method::klu;
    if (name == "band")
      return Method::band;
    AssertThrow(name == "auto", ExcMessage("Direct solver: '" + name + "' is none of auto, klu, band"));
    return Method::automatic;
  }

  bool KluFactorization::choose_band(const Epetra_CrsMatrix &A, const int n, const int *offsets,
                                     const int *columns)
  {
    if (method == Method::klu)
      return false;
    if (&A == band_matrix && A.NumMyNonzeros() == band_nonzeros)
      return band_chosen;
    // Local column indices are rows only if the column map is the row map.
    if (!A.ColMap().SameAs(A.RowMap()) || !A.DomainMap().SameAs(A.RowMap()) ||
        !A.RangeMap().SameAs(A.RowMap()))
      return band_chosen = false;
    if (!band)
      band = std::make_unique<BandFactorization>();
    if (!direct)
      direct = std::make_unique<Direct>();
    const bool reordered = band->analyze(n, offsets, columns);
    band_matrix          = &A;
    band_nonzeros        = A.NumMyNonzeros();
    if (method == Method::band)
      return band_chosen = true;
    if (!reordered)
      return band_chosen;
    const double band_entries = double(n) * (2 * band->lower_bandwidth() + band->upper_bandwidth() + 4);
    // KLU's estimate from an analysis alone (AMD's flop count), made anew
    // when the band's work has moved by half since: contact couplings (the
    // tube's folds) raise both, KLU's by less (2.3 → 6.2 M flops on the
    // tube, the band's 0.74 → 8 M multiply-adds).
    // The envelope's flops / 2: the multiply-adds without exchanges if no
    // entry in it stayed zero (1.0–1.7 × the kernel's count: the tube, two_blocks).
    const double band_work = band->estimated_flops() / 2;
    if (klu_estimated_flops < 0 || band_work > 1.5 * direct->band_work_at_estimate ||
        band_work < direct->band_work_at_estimate / 1.5)
      {
        trilinos_klu_common common;
        trilinos_klu_defaults(&common);
        trilinos_klu_symbolic *symbolic =
          trilinos_klu_analyze(n, const_cast<int *>(offsets), const_cast<int *>(columns), &common);
        if (!symbolic)
          return band_chosen = false;
        klu_estimated_flops       = symbolic->est_flops;
        direct->estimated_entries = symbolic->lnz + symbolic->unz;
        direct->band_work_at_estimate = band_work;
        trilinos_klu_free_symbolic(&symbolic, &common);
      }
    // The band if its instructions are fewer, and its storage is within a
    // few times KLU's factors (or small anyway: 2 M entries, 16 MB; at 8 MB
    // the folded tube's widest bands, 127–135, went to KLU at ~2 × the
    // band's instructions: doc/linear_solver.md, session 14). Instructions
    // per factorisation and solve (callgrind on the tube unfolded and
    // folded and on two_blocks, doc/linear_solver.md): KLU's refactorisation
    // 5.5 per estimated flop (with pivoting ~10); the band ~2.5 per
    // multiply-add and ~6 per band entry (pivot search, scatter, solve),
    // more on narrow bands (per-column overhead), where it wins anyway.
    constexpr double klu_instructions_per_flop = 5.5, band_instructions_per_multiply_add = 2.5,
                     band_instructions_per_entry = 6;
    const double band_instructions =
      band_work * band_instructions_per_multiply_add +
      double(n) * (band->lower_bandwidth() + band->upper_bandwidth()) * band_instructions_per_entry;
    // Instructions are not time on wide bands: the band LU streams its
    // n (2l + u + 4) doubles (up to 16 MB) through the caches at every
    // factorisation, KLU's factors stay in them. Measured CPU time per
    // factorisation and solve (session 15, the folded tube's and
    // two_blocks' matrices): KLU's refactorisation 0.54 ms per M estimated
    // flops; the band 2.96 ms per M entries n (l + u), 0.09 per M envelope
    // multiply-adds and 0.75 per M entries per 100 of width (the caches):
    // at width 85–203 the band took 1.4–2.3 × KLU's time for 0.7 × its
    // instructions; at 27–77 (two_blocks, the unfolded tube) 0.56–0.92 ×.
    // The band also only where its modelled time is within 1.3 × KLU's, or
    // where it fits the core's 2 MB L2 cache anyway (256 k entries:
    // two_blocks' bands, the heat's, the unfolded tube's at width 27).
    const double width = band->lower_bandwidth() + band->upper_bandwidth();
    const double band_entries_width = double(n) * width / 1e6;
    const double band_ms = 2.96 * band_entries_width + 0.09 * band_work / 1e6 +
                           0.75 * band_entries_width * width / 100;
    const double klu_ms = 0.54 * klu_estimated_flops / 1e6;
    band_chosen = band_instructions < klu_estimated_flops * klu_instructions_per_flop &&
                  (band_ms <= 1.3 * klu_ms || band_entries <= (1 << 18)) &&
                  (band_entries <= 4 * direct->estimated_entries || band_entries <= (1 << 21));
    return band_chosen;
  }

  void KluFactorization::clear()
  {
    band_matrix   = nullptr;
    band_active   = false;
    solver.reset();
    problem.reset();
    matrix        = nullptr;
    nonzeros      = -1;
    pivots_reused = false;
  }

  bool KluFactorization::factorize_direct(const Epetra_CrsMatrix &A)
  {
    int    *offsets = nullptr, *columns = nullptr;
    double *entries = nullptr;
    if (A.Comm().NumProc() != 1 || A.ExtractCrsDataPointers(offsets, columns, entries) != 0)
      return false;
    const int n = A.NumMyRows();
    // Diagnostics: ANVIL_MATRIX_DUMP=folder writes each new pattern's matrix
    // (doc/linear_solver.md, "Band LU", session 13).
    if (const char *folder = std::getenv("ANVIL_MATRIX_DUMP"))
      if ((&A != matrix || A.NumMyNonzeros() != nonzeros) &&
          (&A != band_matrix || A.NumMyNonzeros() != band_nonzeros))
        dump_matrix(folder, n, offsets, columns, entries);
    if (choose_band(A, n, offsets, columns))
      {
        band->factorize(offsets, columns, entries);
        band_active   = true;
        pivots_reused = false;
        ++band_factorizations;
        return true;
      }
    band_active = false;
    if (&A != matrix || A.NumMyNonzeros() != nonzeros)
      {
        // Local columns are rows only if the column map is the row map; the
        // union and the positions need sorted rows (FillComplete sorts them).
        if (!A.ColMap().SameAs(A.RowMap()) || !A.DomainMap().SameAs(A.RowMap()) ||
            !A.RangeMap().SameAs(A.RowMap()))
          return false;
        for (int row = 0; row < n; ++row)
          for (int k = offsets[row] + 1; k < offsets[row + 1]; ++k)
            if (columns[k - 1] >= columns[k])
              return false;
        if (!direct)
          direct = std::make_unique<Direct>();
        Direct    &d    = *direct;
        const bool kept = d.symbolic && d.n == n &&
                          find_positions(n, offsets, columns, d.Ap, d.Ai, d.position);
        if (kept)
          ++analyses_kept;
        else
          {
            // The matrix's own pattern. (The union with the analysed one was
            // tried: on two_blocks the sliding contact brings new entries at
            // nearly every step, so it was analysed as often, with more fill:
            // +14 % factorisation instructions.)
            d.free();
            d.n = n;
            d.Ap.assign(offsets, offsets + n + 1);
            d.Ai.assign(columns, columns + offsets[n]);
            trilinos_klu_defaults(&d.common);
            d.symbolic = trilinos_klu_analyze(n, d.Ap.data(), d.Ai.data(), &d.common);
            AssertThrow(d.symbolic && d.common.status == TRILINOS_KLU_OK,
                        ExcMessage("KLU: the matrix is structurally singular"));
            ++symbolic_factorizations;
            AssertThrow(find_positions(n, offsets, columns, d.Ap, d.Ai, d.position),
                        ExcInternalError());
          }
        if (d.position.size() == d.Ai.size())
          d.position.clear(); // the same pattern: the matrix's arrays as they are
        matrix   = &A;
        nonzeros = A.NumMyNonzeros();
      }

    Direct       &d = *direct;
    const double *Ax = entries;
    if (!d.position.empty())
      {
        d.values.assign(d.Ai.size(), 0.);
        for (std::size_t k = 0; k < d.position.size(); ++k)
          d.values[d.position[k]] = entries[k];
        Ax = d.values.data();
      }
    // Amesos_Klu's numeric factorisation: refactor with the last pivots,
    // accepted if min|u_ii| / max|u_ii| > 1e-12, else factor with pivoting
    // (no scaling: Amesos's default, scale 0; −1 is the same factorisation
    // without klu_scale's pass that checks the input for invalid entries,
    // which a matrix from FillComplete cannot have).
    d.common.scale   = -1;
    bool pivoting    = true;
    int *Ap          = d.Ap.data();
    int *Ai          = d.position.empty() ? columns : d.Ai.data();
    auto *values     = const_cast<double *>(Ax);
    if (reuse_pivots && d.numeric &&
        trilinos_klu_refactor(Ap, Ai, values, d.symbolic, d.numeric, &d.common) == 1 &&
        d.common.status == TRILINOS_KLU_OK)
      {
        trilinos_klu_rcond(d.symbolic, d.numeric, &d.common);
        pivoting = !(d.common.rcond > 1e-12);
      }
    if (pivoting)
      {
        if (d.numeric)
          trilinos_klu_free_numeric(&d.numeric, &d.common);
        d.numeric = trilinos_klu_factor(Ap, Ai, values, d.symbolic, &d.common);
        AssertThrow(d.numeric && d.common.status == TRILINOS_KLU_OK,
                    ExcMessage("KLU: the matrix is numerically singular"));
      }
    ++numeric_factorizations;
    pivots_reused = !pivoting;
    matrix_norm   = pivots_reused ? infinity_norm(A) : 0;
    return true;
  }

  void KluFactorization::solve_direct(double *x, const double *b)
  {
    Direct &d = *direct;
    std::copy(b, b + d.n, x);
    const int ok = trilinos_klu_tsolve(d.symbolic, d.numeric, d.n, 1, x, &d.common);
    AssertThrow(ok == 1, ExcMessage("KLU: solve failed"));
  }

  void KluFactorization::numeric_factorization(const bool reuse)
  {
    // Refactorize: klu_refactor with the pivots of the last factorisation
    // with pivoting (Amesos pivots anew when there is none, or when the
    // refactored U's condition estimate is below 1e-12).
    Teuchos::ParameterList parameters;
    parameters.set("Refactorize", reuse);
    solver->SetParameters(parameters);
    const int ierr = solver->NumericFactorization();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
    ++numeric_factorizations;
  }

  void KluFactorization::factorize(const TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &epetra = A.trilinos_matrix();
    if (!solver && factorize_direct(epetra))
      return;
    direct.reset();
    // Another object (a reinit, a deep copy_from) or another number of
    // entries: the analysis no longer describes the matrix. The object's
    // address is a per-process fact (a reinit may hand one rank the freed
    // block back and the other a new one), while the analysis below and
    // the factorisation are collective: every rank must take the same branch
    // or the ranks wait in different collectives (seen with the coarsest
    // level's KLU at np 2, session 23). So a new analysis anywhere is one
    // everywhere.
    if (solver)
      {
        int here = &epetra != matrix || epetra.NumGlobalNonzeros64() != nonzeros, anywhere = here;
        epetra.Comm().MaxAll(&here, &anywhere, 1);
        if (anywhere)
          clear();
      }
    const bool first = !solver;
    if (first)
      {
        problem = std::make_unique<Epetra_LinearProblem>();
        problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&epetra));
        Amesos factory;
        solver.reset(factory.Create("Amesos_Klu", *problem));
        AssertThrow(solver, ExcMessage("Trilinos has no Amesos_Klu"));
        const int ierr = solver->SymbolicFactorization();
        AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
        matrix   = &epetra;
        nonzeros = epetra.NumGlobalNonzeros64();
        ++symbolic_factorizations;
      }
    pivots_reused = reuse_pivots && !first;
    numeric_factorization(pivots_reused);
    matrix_norm = pivots_reused ? infinity_norm(epetra) : 0;
  }

  void KluFactorization::solve(TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &b)
  {
    Assert(solver || direct || band_active, ExcMessage("KluFactorization::solve before factorize"));
    int ierr = 0;
    if (band_active)
      band->solve(x.trilinos_vector()[0], b.trilinos_vector()[0]);
    else if (direct)
      solve_direct(x.trilinos_vector()[0], b.trilinos_vector()[0]);
    else
      {
        problem->SetLHS(&x.trilinos_vector());
        problem->SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
        ierr = solver->Solve();
        AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
      }
    if (!pivots_reused)
      return;

    // The backward error of the solve with reused pivots (see the header):
    // once per factorisation. What it guards against is growth in the
    // factors, which a first solve shows; later solves with the same factors
    // (the heat's mass and Newton solves: 249 checks for 82 factorisations
    // on two_blocks) would repeat it. A passed check clears pivots_reused
    // until the next factorisation.
    Epetra_MultiVector r(b.trilinos_vector());
    matrix->Multiply(false, x.trilinos_vector(), r);
    r.Update(-1., b.trilinos_vector(), 1.);
    double r_norm = 0, x_norm = 0, b_norm = 0;
    r.NormInf(&r_norm);
    x.trilinos_vector().NormInf(&x_norm);
    b.trilinos_vector().NormInf(&b_norm);
    const double scale = matrix_norm * x_norm + b_norm;
    if (r_norm <= backward_error_limit * scale || !(scale > 0))
      {
        // The kept pivots were fit for this matrix: the factors are, for
        // every later right-hand side too.
        pivots_reused = false;
        return;
      }
    ++pivoting_retries;
    pivots_reused = false;
    if (direct)
      {
        // Without a numeric object factorize_direct pivots.
        trilinos_klu_free_numeric(&direct->numeric, &direct->common);
        factorize_direct(*matrix);
        solve_direct(x.trilinos_vector()[0], b.trilinos_vector()[0]);
        return;
      }
    numeric_factorization(false);
    ierr = solver->Solve();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
  }
} // namespace anvil
