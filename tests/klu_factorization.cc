// The heat solver's KLU that keeps its analysis and pivot sequence
// (include/anvil/core/klu_factorization.h) solves every matrix it is given, not
// the first one: the Newton matrix M + γK of a 2D Q1-like 9-point operator
// (nonsymmetric, as anvil's with its kept Dirichlet columns) is factorised
// for γ = 1e-3, 1, 1e3 (the mass-dominated and the conduction-dominated
// extremes ARKode reaches) and solved. Independent answers: the backward
// error |b − A x| / (|A|_F |x|) of each solve (round-off of a stable LU:
// <= 1e-14, whatever the condition number) and a fresh
// TrilinosWrappers::SolverDirect (no reuse) to 1e-12 relative. Also: one
// symbolic analysis for the three matrices, three numeric factorisations.
// Runs the same under mpirun -np 2 (KLU gathers the matrix on rank 0).
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>

#include <cmath>
#include <iostream>

using namespace dealii;

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool     root = Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int n = 40, N = n * n; // grid points
  const IndexSet     owned = Utilities::create_evenly_distributed_partitioning(
    Utilities::MPI::this_mpi_process(comm), Utilities::MPI::n_mpi_processes(comm), N);

  // 9-point couplings of a grid; every neighbour of a point on the left edge
  // keeps its column to that point, whose own row is a diagonal (a Dirichlet row).
  auto neighbours = [&](const unsigned int i, auto &&f) {
    const int x = i % n, y = i / n;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (x + dx >= 0 && x + dx < int(n) && y + dy >= 0 && y + dy < int(n))
          f((y + dy) * n + x + dx, dx == 0 && dy == 0, std::abs(dx) + std::abs(dy));
  };
  DynamicSparsityPattern dsp(N, N, owned);
  for (const auto i : owned)
    neighbours(i, [&](unsigned int j, bool, int) { dsp.add(i, j); });
  TrilinosWrappers::SparseMatrix A;
  A.reinit(owned, owned, dsp, comm);

  anvil::KluFactorization klu;
  int failures = 0;
  for (const double gamma : {1e-3, 1., 1e3})
    {
      A = 0;
      for (const auto i : owned)
        {
          const bool dirichlet = i % n == 0;
          neighbours(i, [&](unsigned int j, bool diagonal, int distance) {
            if (dirichlet)
              {
                if (diagonal)
                  A.set(i, j, 4. / 9.);
                return;
              }
            const double mass = diagonal ? 4. / 9. : distance == 1 ? 1. / 9. : 1. / 36.;
            const double stiffness = diagonal ? 8. / 3. : -1. / 3.;
            A.set(i, j, mass + gamma * stiffness * (1 + 0.1 * (j % 7)));
          });
        }
      A.compress(VectorOperation::insert);
      klu.factorize(A);

      TrilinosWrappers::MPI::Vector b(owned, comm), x(owned, comm), fresh(owned, comm), r(owned, comm);
      for (const auto i : owned)
        b(i) = std::sin(0.37 * i) + (i % n == 0 ? 100. : 0.);
      b.compress(VectorOperation::insert);
      klu.solve(x, b);
      A.vmult(r, x);
      r -= b;
      const double residual = r.l2_norm() / (A.frobenius_norm() * x.l2_norm());

      SolverControl                  control(1, 0);
      TrilinosWrappers::SolverDirect direct(control, TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
      direct.solve(A, fresh, b);
      fresh -= x;
      const double difference = fresh.l2_norm() / x.l2_norm();
      const bool   ok         = residual <= 1e-14 && difference <= 1e-12;
      failures += !ok;
      if (root)
        std::cout << "gamma " << gamma << ": |b - A x|/(|A| |x|) " << residual << " (<= 1e-14), against a fresh KLU "
                  << difference << " (<= 1e-12) " << (ok ? "ok" : "FAILED") << std::endl;
    }
  const bool counts = klu.symbolic_factorizations == 1 && klu.numeric_factorizations == 3;
  failures += !counts;
  if (root)
    std::cout << "symbolic analyses " << klu.symbolic_factorizations << " (expected 1), numeric factorisations "
              << klu.numeric_factorizations << " (expected 3) " << (counts ? "ok" : "FAILED") << std::endl;
  return failures == 0 ? 0 : 1;
}
