// KluFactorization: Amesos_Klu with the symbolic analysis kept (see the header).
#include <deal.II/lac/trilinos_solver.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include <anvil/core/klu_factorization.h>

namespace anvil
{
  using namespace dealii;

  KluFactorization::KluFactorization(const bool reuse_pivots)
    : reuse_pivots(reuse_pivots)
  {}
  KluFactorization::~KluFactorization() = default;

  void KluFactorization::clear()
  {
    solver.reset();
    problem.reset();
    matrix   = nullptr;
    nonzeros = -1;
  }

  void KluFactorization::factorize(const TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &epetra = A.trilinos_matrix();
    // Another object (a reinit, a deep copy_from) or another number of
    // entries: the analysis no longer describes the matrix.
    if (solver && (&epetra != matrix || epetra.NumGlobalNonzeros64() != nonzeros))
      clear();
    if (!solver)
      {
        problem = std::make_unique<Epetra_LinearProblem>();
        problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&epetra));
        Amesos factory;
        solver.reset(factory.Create("Amesos_Klu", *problem));
        AssertThrow(solver, ExcMessage("Trilinos has no Amesos_Klu"));
        // Later factorisations reuse the first one's pivot sequence
        // (klu_refactor, no pivot search) while its condition estimate
        // stays acceptable; Amesos factors with pivoting again otherwise.
        Teuchos::ParameterList parameters;
        parameters.set("Refactorize", reuse_pivots);
        solver->SetParameters(parameters);
        const int ierr = solver->SymbolicFactorization();
        AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
        matrix   = &epetra;
        nonzeros = epetra.NumGlobalNonzeros64();
        ++symbolic_factorizations;
      }
    const int ierr = solver->NumericFactorization();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
    ++numeric_factorizations;
  }

  void KluFactorization::solve(TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &b)
  {
    Assert(solver, ExcMessage("KluFactorization::solve before factorize"));
    problem->SetLHS(&x.trilinos_vector());
    problem->SetRHS(const_cast<Epetra_MultiVector *>(&b.trilinos_vector()));
    const int ierr = solver->Solve();
    AssertThrow(ierr == 0, TrilinosWrappers::SolverDirect::ExcTrilinosError(ierr));
  }
} // namespace anvil
