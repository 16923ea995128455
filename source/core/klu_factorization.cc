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

#include <anvil/core/klu_factorization.h>

#include <algorithm>
#include <cmath>

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
  } // namespace

  KluFactorization::KluFactorization(const bool reuse_pivots)
    : reuse_pivots(reuse_pivots)
  {}
  KluFactorization::~KluFactorization() = default;

  void KluFactorization::clear()
  {
    solver.reset();
    problem.reset();
    matrix        = nullptr;
    nonzeros      = -1;
    pivots_reused = false;
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
    // Another object (a reinit, a deep copy_from) or another number of
    // entries: the analysis no longer describes the matrix.
    if (solver && (&epetra != matrix || epetra.NumGlobalNonzeros64() != nonzeros))
      clear();
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
    Assert(solver, ExcMessage("KluFactorization::solve before factorize"));
    problem->SetLHS(&x.trilinos_vector());
    problem->SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    int ierr = solver->Solve();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
    if (!pivots_reused)
      return;

    // The backward error of the solve with reused pivots (see the header).
    Epetra_MultiVector r(b.trilinos_vector());
    matrix->Multiply(false, x.trilinos_vector(), r);
    r.Update(-1., b.trilinos_vector(), 1.);
    double r_norm = 0, x_norm = 0, b_norm = 0;
    r.NormInf(&r_norm);
    x.trilinos_vector().NormInf(&x_norm);
    b.trilinos_vector().NormInf(&b_norm);
    const double scale = matrix_norm * x_norm + b_norm;
    if (r_norm <= backward_error_limit * scale || !(scale > 0))
      return;
    numeric_factorization(false);
    pivots_reused = false;
    ++pivoting_retries;
    ierr = solver->Solve();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
  }
} // namespace anvil
