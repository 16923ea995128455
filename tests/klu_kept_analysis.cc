// On one process KluFactorization keeps KLU's analysis across new matrix
// objects whose pattern fits in the analysed one (a contact pattern made anew
// each step, include/anvil/core/klu_factorization.h). A chain of 40 unknowns
// (a 1D Laplacian, diagonally dominant) with "contact" couplings between far
// unknowns that come and go, each pattern in a new matrix object:
//   1. couplings (0, 39), (5, 20): analysed;
//   2. only (5, 20), after clear() (as setup_matrix does): kept, the missing
//      entries factored as zeros;
//   3. (3, 17) appears: analysed again (its own pattern);
//   4. (3, 17) in a new object: kept.
// Independent answers: every solve against the exact x chosen to make b = A x
// (to 1e-13 relative), its backward error computed here (<= 1e-15), and the
// counts of analyses (2) and of kept analyses (2).
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

using namespace dealii;

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm     comm  = MPI_COMM_WORLD;
  const unsigned int N     = 40;
  const IndexSet     owned = complete_index_set(N);
  using Couplings          = std::vector<std::pair<unsigned int, unsigned int>>;
  const std::vector<Couplings> steps = {{{0, 39}, {5, 20}}, {{5, 20}}, {{3, 17}}, {{3, 17}}};
  const unsigned long expected_analyses[4] = {1, 1, 2, 2}, expected_kept[4] = {0, 1, 1, 2};

  anvil::KluFactorization klu(true);
  int                     failures = 0;
  // Each step's matrix lives while the next is made: a new object, never the
  // old one's address.
  std::unique_ptr<TrilinosWrappers::SparseMatrix> previous;
  for (unsigned int s = 0; s < steps.size(); ++s)
    {
      DynamicSparsityPattern dsp(N, N, owned);
      for (unsigned int i = 0; i < N; ++i)
        for (unsigned int j = (i > 0 ? i - 1 : 0); j < std::min(N, i + 2); ++j)
          dsp.add(i, j);
      for (const auto &[i, j] : steps[s])
        dsp.add(i, j), dsp.add(j, i);
      auto A = std::make_unique<TrilinosWrappers::SparseMatrix>();
      A->reinit(owned, owned, dsp, comm);
      const double diagonal = 4. + s; // new values at every step
      for (unsigned int i = 0; i < N; ++i)
        {
          A->set(i, i, diagonal);
          if (i > 0)
            A->set(i, i - 1, -1.);
          if (i + 1 < N)
            A->set(i, i + 1, -1.);
        }
      for (const auto &[i, j] : steps[s])
        A->set(i, j, -0.5), A->set(j, i, -0.5);
      A->compress(VectorOperation::insert);
      if (s == 1)
        klu.clear(); // as MechanicalProblem::setup_matrix() does
      klu.factorize(*A);

      TrilinosWrappers::MPI::Vector exact(owned, comm), b(owned, comm), x(owned, comm),
        r(owned, comm);
      for (unsigned int i = 0; i < N; ++i)
        exact(i) = std::sin(0.3 * i + s) + 0.1 * i;
      exact.compress(VectorOperation::insert);
      A->vmult(b, exact);
      klu.solve(x, b);
      A->vmult(r, x);
      r -= b;
      const double backward = r.linfty_norm() / (A->linfty_norm() * x.linfty_norm() + b.linfty_norm());
      x -= exact;
      const double error = x.linfty_norm() / exact.linfty_norm();
      const bool   ok    = error <= 1e-13 && backward <= 1e-15 &&
                      klu.symbolic_factorizations == expected_analyses[s] &&
                      klu.analyses_kept == expected_kept[s];
      failures += !ok;
      std::cout << "step " << s + 1 << ": error against the exact x " << error
                << " (<= 1e-13), backward error " << backward << " (<= 1e-15), analyses "
                << klu.symbolic_factorizations << " (expected " << expected_analyses[s]
                << "), kept " << klu.analyses_kept << " (expected " << expected_kept[s] << ") "
                << (ok ? "ok" : "FAILED") << std::endl;
      previous = std::move(A);
    }
  return failures == 0 ? 0 : 1;
}
