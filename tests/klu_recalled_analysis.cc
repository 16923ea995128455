// On one process KluFactorization keeps the analyses of the last few
// patterns, so a pattern that comes back (a contact node leaving a face and
// returning) is not analysed again (include/anvil/core/klu_factorization.h).
// A chain of 40 unknowns (a 1D Laplacian, diagonally dominant) with "contact"
// couplings that alternate, A B A B A, each in a new matrix object with new
// values: A = {(0, 39), (5, 20)}, B = {(3, 17)} (neither fits in the other,
// so each change needs an analysis of its own).
// Independent answers: every solution equal, bit for bit, to that of a fresh
// KluFactorization (a new analysis, pivoting) of the same matrix, and to the
// exact x chosen to make b = A x (1e-13 relative); the counts of analyses (2)
// and of recalled analyses (3).
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>

#include "check.h"

#include <cmath>
#include <memory>
#include <string>
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
  const Couplings A = {{0, 39}, {5, 20}}, B = {{3, 17}};
  const std::vector<Couplings> steps = {A, B, A, B, A};

  anvil::testing::Checks check;
  anvil::KluFactorization klu(true);
  std::unique_ptr<TrilinosWrappers::SparseMatrix> previous;
  for (unsigned int s = 0; s < steps.size(); ++s)
    {
      DynamicSparsityPattern dsp(N, N, owned);
      for (unsigned int i = 0; i < N; ++i)
        for (unsigned int j = (i > 0 ? i - 1 : 0); j < std::min(N, i + 2); ++j)
          dsp.add(i, j);
      for (const auto &[i, j] : steps[s])
        dsp.add(i, j), dsp.add(j, i);
      auto matrix = std::make_unique<TrilinosWrappers::SparseMatrix>();
      matrix->reinit(owned, owned, dsp, comm);
      const double diagonal = 4. + 0.37 * s; // new values at every step
      for (unsigned int i = 0; i < N; ++i)
        {
          matrix->set(i, i, diagonal + 0.01 * i);
          if (i > 0)
            matrix->set(i, i - 1, -1.);
          if (i + 1 < N)
            matrix->set(i, i + 1, -1. - 0.001 * s);
        }
      for (const auto &[i, j] : steps[s])
        matrix->set(i, j, -0.5), matrix->set(j, i, -0.7);
      matrix->compress(VectorOperation::insert);
      klu.clear(); // as MechanicalProblem::setup_matrix() does for every new pattern
      klu.factorize(*matrix);

      TrilinosWrappers::MPI::Vector exact(owned, comm), b(owned, comm), x(owned, comm),
        fresh_x(owned, comm);
      for (unsigned int i = 0; i < N; ++i)
        exact(i) = std::sin(0.3 * i + s) + 0.1 * i;
      exact.compress(VectorOperation::insert);
      matrix->vmult(b, exact);
      klu.solve(x, b);
      anvil::KluFactorization fresh(true);
      fresh.factorize(*matrix);
      fresh.solve(fresh_x, b);

      double differing = 0;
      for (unsigned int i = 0; i < N; ++i)
        differing += x(i) != fresh_x(i);
      TrilinosWrappers::MPI::Vector error(x);
      error -= exact;
      const double relative = error.linfty_norm() / exact.linfty_norm();
      const std::string step = "step " + std::to_string(s + 1) + " (" + (s % 2 ? "B" : "A") + "): ";
      check(differing == 0, step + std::to_string(int(differing)) +
                              " entries differ from a fresh analysis' solution (expected 0)");
      check(relative <= 1e-13, step + "error against the exact x " + std::to_string(relative) +
                                 " (<= 1e-13)");
      previous = std::move(matrix);
    }
  check(klu.symbolic_factorizations == 2,
        "analyses " + std::to_string(klu.symbolic_factorizations) + " (expected 2: A, B)");
  check(klu.analyses_recalled == 3,
        "recalled analyses " + std::to_string(klu.analyses_recalled) + " (expected 3)");
  return check.finish();
}
