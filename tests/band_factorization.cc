// The band LU (include/anvil/core/band_factorization.h) through
// KluFactorization, against KLU on the same matrices:
// - random nonsymmetric matrices on the 9-point graph of a 2D grid with two
//   unknowns per point, numbered at random (so the band is RCM's doing), the
//   diagonal no larger than the rest of the row;
// - the same with every diagonal entry an explicit zero (no LU without row
//   exchanges exists: column 0 has a zero pivot);
// - couplings that come and go in new matrix objects: inside the band the
//   ordering is kept, a far one (a fold touching the other end) reorders.
// Independent answers: KLU's solution (relative difference <= 1e-12) and the
// backward error |b - A x|∞ / (|A|∞ |x|∞) of the band's (<= 1e-14, round-off
// of a stable LU); the band widths against the grid's (RCM on a w × h grid
// of 2 unknowns per point: at most 2 (w + 2) below and above); the automatic
// choice: band on the 2D strip, KLU on a 3D cube's graph.
// Under mpirun -np 2 the band is never used (KLU gathers the matrix).
#include "check.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/band_factorization.h>
#include <anvil/core/klu_factorization.h>

#include <trilinos_klu_decl.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <numeric>
#include <random>

using namespace dealii;
using Coupling = std::function<void(unsigned int, const std::function<void(unsigned int)> &)>;

namespace
{
  MPI_Comm   comm     = MPI_COMM_WORLD;
  anvil::testing::Checks check;
  bool                   root = true;

  /// The matrix of @p couplings (i's columns) with values from @p value.
  void build(TrilinosWrappers::SparseMatrix &A, const IndexSet &owned, const Coupling &couplings,
             const std::function<double(unsigned int, unsigned int)> &value)
  {
    DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
    for (const auto i : owned)
      couplings(i, [&](unsigned int j) { dsp.add(i, j); });
    A.reinit(owned, owned, dsp, comm);
    for (const auto i : owned)
      couplings(i, [&](unsigned int j) { A.set(i, j, value(i, j)); });
    A.compress(VectorOperation::insert);
  }

  double inf_norm(const TrilinosWrappers::MPI::Vector &v) { return v.linfty_norm(); }

  /// Solve with the band (method band) and with KLU; compare.
  void compare(const TrilinosWrappers::SparseMatrix &A, anvil::KluFactorization &band,
               const IndexSet &owned, const std::string &name)
  {
    anvil::KluFactorization klu;
    klu.method = anvil::KluFactorization::Method::klu;
    TrilinosWrappers::MPI::Vector b(owned, comm), x(owned, comm), y(owned, comm), r(owned, comm);
    for (const auto i : owned)
      b(i) = std::sin(0.37 * i) + 0.1 * (i % 3);
    b.compress(VectorOperation::insert);
    band.factorize(A);
    band.solve(x, b);
    klu.factorize(A);
    klu.solve(y, b);
    A.vmult(r, x);
    r -= b;
    const double backward = inf_norm(r) / (A.linfty_norm() * inf_norm(x));
    y -= x;
    const double difference = inf_norm(y) / inf_norm(x);
    const bool   one        = Utilities::MPI::n_mpi_processes(comm) == 1;
    if (root)
      std::cout << name << ": solved by " << band.last_method() << " (expected "
                << (one ? "band" : "klu") << "), |b - A x|/(|A| |x|) " << backward
                << " (<= 1e-14), against KLU " << difference << " (<= 1e-12)";
    // (KLU at np 2 reuses its pivots, checked by its own limit, 1e-12.)
    check(backward <= (one ? 1e-14 : 1e-12) && difference <= 1e-12 &&
            std::string(band.last_method()) == (one ? "band" : "klu"),
          "");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = Utilities::MPI::this_mpi_process(comm) == 0;
  check.print_on_this_process(root);
  const bool one = Utilities::MPI::n_mpi_processes(comm) == 1;

  // A w × h grid of points, 2 unknowns each, numbered at random.
  const unsigned int w = 7, h = 60, N = 2 * w * h;
  std::vector<unsigned int> number(N);
  std::iota(number.begin(), number.end(), 0u);
  std::mt19937 random(12);
  std::shuffle(number.begin(), number.end(), random);
  std::vector<unsigned int> unknown_of(N); // inverse
  for (unsigned int k = 0; k < N; ++k)
    unknown_of[number[k]] = k;
  // Row i's columns: the 9-point neighbours' two unknowns, plus @p extra.
  const auto grid = [&](std::vector<std::pair<unsigned int, unsigned int>> extra) -> Coupling {
    return [&, extra](unsigned int i, const std::function<void(unsigned int)> &f) {
      const unsigned int k = unknown_of[i], p = k / 2, x = p % w, y = p / w;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (int(x) + dx >= 0 && int(x) + dx < int(w) && int(y) + dy >= 0 && int(y) + dy < int(h))
            for (unsigned int c = 0; c < 2; ++c)
              f(number[2 * ((y + dy) * w + x + dx) + c]);
      for (const auto &[a, b] : extra)
        for (unsigned int c = 0; c < 2; ++c)
          {
            if (p == a)
              f(number[2 * b + c]);
            if (p == b)
              f(number[2 * a + c]);
          }
    };
  };
  const IndexSet owned = Utilities::create_evenly_distributed_partitioning(
    Utilities::MPI::this_mpi_process(comm), Utilities::MPI::n_mpi_processes(comm), N);
  // Values from (i, j) alone (the same on every process), in [-1, 1], the
  // diagonal's shifted by ±2.5 (random sign): a row's 18 entries sum to ~10
  // in magnitude, so the diagonal does not dominate, but the matrix is far
  // enough from singular (condition ~1e3) that two stable LUs agree to 1e-12.
  const auto random_value = [](unsigned int i, unsigned int j) {
    std::mt19937 g(1000003u * i + j);
    const double v = std::uniform_real_distribution<double>(-1, 1)(g);
    return i == j ? v + (i % 2 ? 2.5 : -2.5) : v;
  };

  anvil::KluFactorization band;
  band.method = anvil::KluFactorization::Method::band;
  TrilinosWrappers::SparseMatrix A;
  build(A, owned, grid({}), random_value);
  compare(A, band, owned, "random nonsymmetric");
  if (one)
    {
      const auto &b = *band.band_solver();
      // RCM's levels on the strip are its columns of w points (2w unknowns);
      // a coupling spans two levels at most.
      check(b.lower_bandwidth() < int(4 * w + 2) && b.upper_bandwidth() < int(4 * w + 2),
            "bandwidths " + std::to_string(b.lower_bandwidth()) + " + " +
              std::to_string(b.upper_bandwidth()) + " (< " + std::to_string(4 * w + 2) + " each)");
    }

  // A weak diagonal (0.3 against off-diagonal entries up to 1): partial
  // pivoting exchanges rows at most steps.
  build(A, owned, grid({}), [&](unsigned int i, unsigned int j) {
    return i == j ? (i % 2 ? 0.3 : -0.3) : random_value(i, j);
  });
  compare(A, band, owned, "weak diagonal");

  // The two unknowns of a point coupled by 3, each with a zero diagonal:
  // near a block diagonal of [[0, 3], [3, 0]], well conditioned, but no
  // pivot can be taken on the diagonal.
  build(A, owned, grid({}), [&](unsigned int i, unsigned int j) {
    return i == j ? 0. : unknown_of[i] / 2 == unknown_of[j] / 2 ? 3. : random_value(i, j);
  });
  compare(A, band, owned, "zero diagonal");

  // Couplings that come and go: within a few rows (inside the band), then a
  // fold touching points 40 rows apart (outside it).
  TrilinosWrappers::SparseMatrix B, C;
  build(B, owned, grid({{w * 10 + 1, w * 11 + 3}}), random_value);
  compare(B, band, owned, "near coupling");
  const auto orderings = one ? band.band_solver()->orderings : 0;
  check(!one || orderings == 1, "orderings after a coupling inside the band: " + std::to_string(orderings) +
                          " (expected 1)");
  build(C, owned, grid({{w * 5 + 2, w * 45 + 2}}), random_value);
  compare(C, band, owned, "far coupling");
  const auto reordered = one ? band.band_solver()->orderings : 1;
  check(!one || reordered == 2, "orderings after a far coupling: " + std::to_string(reordered) +
                                  " (expected 2)");

  // The automatic choice: band on this strip, KLU on a 3D cube's 27-point graph.
  anvil::KluFactorization automatic;
  automatic.method = anvil::KluFactorization::Method::automatic;
  build(A, owned, grid({}), random_value);
  compare(A, automatic, owned, "automatic, 2D strip");
  if (root && one)
    std::cout << "2D strip: band envelope " << automatic.band_solver()->estimated_flops()
              << " flops, actual " << 2 * automatic.band_solver()->last_multiply_adds
              << ", KLU estimate " << automatic.klu_estimated_flops << std::endl;
  // Folds (couplings 40 rows apart) widen the band: KLU's estimate is made
  // anew on the folded pattern (the choice would otherwise weigh the band's
  // folded work against KLU's unfolded one): equal to KLU's own analysis.
  if (one)
    {
      const double unfolded = automatic.klu_estimated_flops;
      build(C, owned, grid({{w * 5 + 2, w * 45 + 2}, {w * 8 + 4, w * 50 + 4}, {w * 12 + 1, w * 55 + 1}}),
            random_value);
      automatic.factorize(C);
      int    *offsets = nullptr, *columns = nullptr;
      double *values  = nullptr;
      C.trilinos_matrix().ExtractCrsDataPointers(offsets, columns, values);
      trilinos_klu_common common;
      trilinos_klu_defaults(&common);
      trilinos_klu_symbolic *symbolic = trilinos_klu_analyze(C.m(), offsets, columns, &common);
      const double           expected = symbolic->est_flops;
      trilinos_klu_free_symbolic(&symbolic, &common);
      check(automatic.klu_estimated_flops == expected && expected != unfolded,
            "KLU's estimate on the folded pattern " + std::to_string(automatic.klu_estimated_flops) +
              " (KLU's analysis " + std::to_string(expected) + ", unfolded " + std::to_string(unfolded) + ")");
    }
  const unsigned int m = 18, M = m * m * m;
  const IndexSet cube = Utilities::create_evenly_distributed_partitioning(
    Utilities::MPI::this_mpi_process(comm), Utilities::MPI::n_mpi_processes(comm), M);
  const Coupling cube_couplings = [&](unsigned int i, const std::function<void(unsigned int)> &f) {
    const int x = i % m, y = (i / m) % m, z = i / (m * m);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (x + dx >= 0 && x + dx < int(m) && y + dy >= 0 && y + dy < int(m) && z + dz >= 0 &&
              z + dz < int(m))
            f(((z + dz) * m + y + dy) * m + x + dx);
  };
  anvil::KluFactorization automatic_3d;
  automatic_3d.method = anvil::KluFactorization::Method::automatic;
  build(A, cube, cube_couplings, [&](unsigned int i, unsigned int j) { return (i == j ? 27. : 0) + random_value(i, j); });
  automatic_3d.factorize(A);
  if (root && one)
    std::cout << "3D cube: band envelope " << automatic_3d.band_solver()->estimated_flops()
              << " flops, bandwidths " << automatic_3d.band_solver()->lower_bandwidth() << ", KLU estimate "
              << automatic_3d.klu_estimated_flops << std::endl;
  check(std::string(automatic_3d.last_method()) == "klu",
        std::string("automatic, 3D cube 18^3: ") + automatic_3d.last_method() + " (expected klu)");
  return check.finish();
}
