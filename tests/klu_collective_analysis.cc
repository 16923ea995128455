// KluFactorization decides whether to redo KLU's analysis by the matrix
// object's address (include/anvil/core/klu_factorization.h), a per-process
// fact: after a reinit one rank may get the freed block back and the other a
// new one. The analysis and the factorisation are collective (Amesos gathers
// the matrix on rank 0), so the ranks must agree, or they wait in different
// collectives (the coarsest level's KLU hung at np 2 in session 23).
//
// A reinit frees the old object before it makes the new one, so the new one
// usually gets the old address on every rank; whether it does on all of them
// is up to each rank's heap. The test makes the split happen: two identical
// matrices A and B (a 1D Laplacian chain with a far coupling; same pattern,
// same values), and the second factorisation is handed A on rank 0 (the
// object analysed first) and B on rank 1 (a new address there only). B goes
// first through everything A went through (its own analysis, solve and
// product), so that the two objects' communication state (Epetra's lazily
// built directories, its message tags) is alike, as that of one reinit'ed
// object is on every rank. The third factorisation: each
// rank's object again, new values: the kept analysis and pivots. Independent
// answers: each solve against the exact x chosen to make b = A x (1e-12
// relative) and the analyses counted on each rank (2: the first, and the one
// rank 1's new object forces on every rank). Without the agreement the ranks
// wait in different collectives (ctest's TIMEOUT).
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>

#include <cmath>
#include <iostream>

using namespace dealii;

namespace
{
  void fill(TrilinosWrappers::SparseMatrix &M, const IndexSet &owned, const unsigned int N, const double shift)
  {
    M = 0;
    for (const auto i : owned)
      {
        M.set(i, i, 2. + shift + 0.01 * i);
        if (i > 0)
          M.set(i, i - 1, -1.);
        if (i + 1 < N)
          M.set(i, i + 1, -1.);
        if (i == 3 || i == N - 4)
          M.set(i, i == 3 ? N - 4 : 3, -0.5); // a far coupling, both ways
      }
    M.compress(VectorOperation::insert);
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm     comm = MPI_COMM_WORLD;
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned int N    = 40;
  const IndexSet     owned =
    Utilities::create_evenly_distributed_partitioning(rank, Utilities::MPI::n_mpi_processes(comm), N);
  DynamicSparsityPattern dsp(N, N, owned);
  for (const auto i : owned)
    {
      dsp.add(i, i);
      if (i > 0)
        dsp.add(i, i - 1);
      if (i + 1 < N)
        dsp.add(i, i + 1);
    }
  for (const unsigned int i : {3u, N - 4})
    if (owned.is_element(i))
      dsp.add(i, i == 3 ? N - 4 : 3);
  TrilinosWrappers::SparseMatrix A, B;
  A.reinit(owned, owned, dsp, comm);
  B.reinit(owned, owned, dsp, comm);

  anvil::KluFactorization klu(true), klu_b(true);
  int                     failures = 0;
  auto                    solve_and_check = [&](anvil::KluFactorization &solver,
                             const TrilinosWrappers::SparseMatrix &M, const unsigned int k) {
    TrilinosWrappers::MPI::Vector exact(owned, comm), b(owned, comm), x(owned, comm);
    for (const auto i : owned)
      exact(i) = std::cos(0.3 * i) + 0.1 * i;
    exact.compress(VectorOperation::insert);
    M.vmult(b, exact);
    solver.solve(x, b);
    x -= exact;
    const double error = x.l2_norm() / exact.l2_norm();
    const bool   ok    = error <= 1e-12;
    failures += !ok;
    if (rank == 0)
      std::cout << "factorisation " << k << ": |x - x_exact| / |x_exact| " << error << " (<= 1e-12) "
                << (ok ? "ok" : "FAILED") << std::endl;
  };
  fill(A, owned, N, 0.);
  fill(B, owned, N, 0.);
  klu_b.factorize(B);
  solve_and_check(klu_b, B, 0);
  klu.factorize(A);
  solve_and_check(klu, A, 1);

  const TrilinosWrappers::SparseMatrix &given = rank == 0 ? A : B;
  for (const double shift : {0.5, 1.})
    {
      fill(A, owned, N, shift);
      fill(B, owned, N, shift);
      klu.factorize(given);
      solve_and_check(klu, given, shift == 0.5 ? 2 : 3);
    }

  // Every rank counts the same analyses: the first, and the one rank 1's new
  // object at the second factorisation makes collective.
  const bool counts = klu.symbolic_factorizations == 2;
  failures += !counts;
  std::cout << "rank " << rank << ": symbolic analyses " << klu.symbolic_factorizations << " (expected 2) "
            << (counts ? "ok" : "FAILED") << std::endl;
  return Utilities::MPI::max(failures, comm) == 0 ? 0 : 1;
}
