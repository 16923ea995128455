// The mechanics' KLU reuses its pivots across factorisations (klu_refactor)
// and checks each solve's backward error (include/anvil/core/klu_factorization.h).
// A matrix whose first factorisation pivots on the diagonal, then values for
// which the diagonal is a poor pivot (|a_11| = 3e-6 against |a_21| = 1: the
// old pivot order grows U by 3e5, but min|u_ii| / max|u_ii| = 1e-11 passes
// Amesos's own 1e-12 condition check). Independent answers: the backward
// error |b − A x|∞ / (|A|∞ |x|∞ + |b|∞) of every solve, computed here (<= 1e-15
// for a stable LU), the exact solution of the 2 x 2 block by Cramer's rule
// (to 1e-14), and the counts: one symbolic analysis, one retry with pivoting
// for the poor values and none for the good ones.
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>

#include <cmath>
#include <iostream>

using namespace dealii;

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm     comm  = MPI_COMM_WORLD;
  const unsigned int N     = 4; // a 2 x 2 block and two decoupled rows
  const IndexSet     owned = complete_index_set(N);
  DynamicSparsityPattern dsp(N, N, owned);
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j)
      dsp.add(i, j);
  for (unsigned int i = 2; i < N; ++i)
    dsp.add(i, i);
  TrilinosWrappers::SparseMatrix A;
  A.reinit(owned, owned, dsp, comm);

  anvil::KluFactorization klu(true);
  int failures = 0;
  // {a11, a12 = a21, a22}: diagonally dominant, the poor one, good again.
  const double cases[3][3] = {{2., 0.5, 3.}, {3e-6, 1., 1.}, {4., 1., 2.}};
  const unsigned long expected_retries[3] = {0, 1, 1};
  for (unsigned int k = 0; k < 3; ++k)
    {
      const double a11 = cases[k][0], a12 = cases[k][1], a22 = cases[k][2];
      A = 0;
      A.set(0, 0, a11);
      A.set(0, 1, a12);
      A.set(1, 0, a12);
      A.set(1, 1, a22);
      A.set(2, 2, 5.);
      A.set(3, 3, 7.);
      A.compress(VectorOperation::insert);
      klu.factorize(A);

      TrilinosWrappers::MPI::Vector b(owned, comm), x(owned, comm), r(owned, comm);
      const double b0 = 1. / 3., b1 = 2. / 7.;
      b(0) = b0, b(1) = b1, b(2) = 1., b(3) = 1.;
      b.compress(VectorOperation::insert);
      klu.solve(x, b);
      A.vmult(r, x);
      r -= b;
      const double norm_A   = std::max({std::abs(a11) + std::abs(a12), std::abs(a12) + std::abs(a22), 7.});
      const double backward = r.linfty_norm() / (norm_A * x.linfty_norm() + b.linfty_norm());
      // Cramer's rule for the 2 x 2 block.
      const double det  = a11 * a22 - a12 * a12;
      const double x0   = (b0 * a22 - a12 * b1) / det, x1 = (a11 * b1 - a12 * b0) / det;
      const double exact_error = std::max(std::abs(x(0) - x0), std::abs(x(1) - x1)) /
                                 std::max(std::abs(x0), std::abs(x1));
      const bool ok = backward <= 1e-15 && exact_error <= 1e-14 &&
                      klu.pivoting_retries == expected_retries[k];
      failures += !ok;
      std::cout << "a11 " << a11 << ": backward error " << backward << " (<= 1e-15), against Cramer "
                << exact_error << " (<= 1e-14), retries with pivoting " << klu.pivoting_retries
                << " (expected " << expected_retries[k] << ") " << (ok ? "ok" : "FAILED") << std::endl;
    }
  const bool counts = klu.symbolic_factorizations == 1 && klu.numeric_factorizations == 4;
  failures += !counts;
  std::cout << "symbolic analyses " << klu.symbolic_factorizations << " (expected 1), numeric factorisations "
            << klu.numeric_factorizations << " (expected 4: three and the retry) " << (counts ? "ok" : "FAILED")
            << std::endl;
  return failures == 0 ? 0 : 1;
}
