// The single-precision nodal-block copy of a level's matrix
// (source/mechanics/float_block_matrix.cc) multiplies as Epetra's double
// matrix does, up to rounding its entries to float: row by row,
// |F x − K x|_i ≤ u Σ_j |K_ij x_j| (u = 2⁻²⁴, float's unit roundoff; the
// sums themselves are in double, ~1e-16), on the 3D elastic block's K
// (deal.II's Q1³ numbering) and on its Galerkin coarse operator (the coarse
// spaces' dim · node + component numbering), on 1 and 2 processes (ghost
// nodes imported whole, also where the top face's uz = 0 leaves only ux and
// uy in K's columns: checked to occur). The copy must be the float path
// (some row differs from K x) and hold ≤ 6 bytes per stored entry (half
// of Epetra's 12, on this small mesh with its many constrained dofs; ~4.5 at
// 1 M DoFs). The same for a 2D K in blocks of 2. A matrix whose rows do not come in nodes (an odd row
// count; on two processes one rank's share alone) is refused on every
// process, so that GMRES sees one operator.
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include "../source/mechanics/float_block_matrix.h"
#include "../source/mechanics/geometric_coarse_space.h"
#include "check.h"
#include "mechanics_fixture.h"

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

#include <cmath>
#include <map>
#include <cstdlib>
#include <sstream>

using namespace dealii;

namespace
{
  constexpr double unit_roundoff = 5.9604644775390625e-08; // 2^-24

  /// The largest |F x − K x|_i / (u Σ_j |K_ij x_j|) over all rows of all
  /// processes, and whether any row differs at all.
  std::pair<double, bool> worst_ratio(const Epetra_CrsMatrix &K, const anvil::FloatBlockMatrix &F)
  {
    Epetra_Vector x(K.OperatorDomainMap()), y(K.OperatorRangeMap()), z(K.OperatorRangeMap());
    Epetra_Vector bound(K.OperatorRangeMap());
    for (int i = 0; i < x.MyLength(); ++i)
      x[i] = std::sin(0.37 * K.RowMap().GID64(i) + 0.1) + 0.2;
    K.Multiply(false, x, y);
    F.Apply(x, z);
    // Σ_j |K_ij x_j| with x's ghosts: |K| |x| by Epetra on a copy of |K|.
    Epetra_CrsMatrix absK(K);
    for (int i = 0; i < absK.NumMyRows(); ++i)
      {
        int     n;
        double *v;
        absK.ExtractMyRowView(i, n, v);
        for (int e = 0; e < n; ++e)
          v[e] = std::abs(v[e]);
      }
    Epetra_Vector absx(x);
    absx.Abs(x);
    absK.Multiply(false, absx, bound);
    double worst = 0, differs = 0;
    for (int i = 0; i < y.MyLength(); ++i)
      {
        const double d = std::abs(z[i] - y[i]);
        worst          = std::max(worst, d / (unit_roundoff * bound[i] + 1e-300));
        differs        = std::max(differs, d > 0 ? 1. : 0.);
      }
    double all[2], mine[2] = {worst, differs};
    K.Comm().MaxAll(mine, all, 2);
    return {all[0], all[1] > 0};
  }

  /// The elastic block of @p cells, undistorted, standard Q1, the top's
  /// normal displacement given (its nodes partial in K's columns).
  anvil_test::Overrides elastic_block(const int dim, const std::string &cells, const std::string &displacement)
  {
    return {{"Dimension", std::to_string(dim)},
            {"Geometry/Blocks", "body: " + cells},
            {"Geometry/Random distortion", "0"},
            {"Mechanics/Element", "standard"},
            {"Boundary conditions/Displacement", displacement},
            {"Boundary conditions/Pressure", ""}};
  }

  /// 2 I on n rows, rows [begin, end) owned here.
  TrilinosWrappers::SparseMatrix diagonal(const unsigned int n, const unsigned int begin, const unsigned int end)
  {
    IndexSet owned(n);
    owned.add_range(begin, end);
    DynamicSparsityPattern dsp(n, n, owned);
    for (const auto i : owned)
      dsp.add(i, i);
    TrilinosWrappers::SparseMatrix S;
    S.reinit(owned, owned, dsp, MPI_COMM_WORLD);
    for (const auto i : owned)
      S.set(i, i, 2.);
    S.compress(VectorOperation::insert);
    return S;
  }

  void check_copy(anvil::testing::Checks &checks, const Epetra_CrsMatrix &K, const std::string &what,
                  const unsigned int block = 3)
  {
    const auto F = anvil::FloatBlockMatrix::make(K, block);
    checks(F != nullptr, what + ": nodal blocks of " + std::to_string(block) + " found");
    if (!F)
      return;
    // Both kernels: the processor's (AVX2 and FMA where it has them) and the portable loop.
    for (const char *kernel : {"", "portable"})
      {
        setenv("ANVIL_FLOAT_KERNEL", kernel, 1);
        const auto [worst, differs] = worst_ratio(K, *F);
        const std::string  name     = what + (*kernel ? " (portable kernel)" : "");
        std::ostringstream s;
        s << name << ": |F x - K x| <= " << worst << " u sum |K x| row by row (<= 1.01)";
        checks(worst <= 1.01, s.str());
        checks(differs, name + ": the product is float's (some row differs from K x)");
      }
    unsetenv("ANVIL_FLOAT_KERNEL");
    std::ostringstream t;
    double bytes = F->memory_consumption(), entries = K.NumMyNonzeros(), all[2], mine[2] = {bytes, entries};
    K.Comm().SumAll(mine, all, 2);
    t << what << ": " << all[0] / all[1] << " bytes per stored entry (<= 6, half of Epetra's 12)";
    checks(all[0] / all[1] <= 6, t.str());
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks           checks;
  checks.print_on_this_process(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);
  const std::string scene = std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm";

  anvil_test::MechanicsFixture<3> block(scene, elastic_block(3, "0, 0, 0, 1, 0.5, 1, 8, 6, 8",
                                                             "bottom: ux = 0, uy = 0, uz = 0; top: uz = 0"));
  block.problem->assemble_system(true);
  const auto &K = block.problem->get_system_matrix();
  check_copy(checks, K.trilinos_matrix(), "fine K");
  // On two processes the ghost columns include nodes of the top face whose
  // uz is constrained (eliminated from K's columns): partial nodes, which the
  // copy must import whole. Make sure the case is there.
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    {
      const Epetra_CrsMatrix &k = K.trilinos_matrix();
      std::map<long long, int> components;
      for (int j = 0; j < k.NumMyCols(); ++j)
        if (k.RowMap().LID(k.ColMap().GID64(j)) < 0)
          ++components[k.ColMap().GID64(j) / 3];
      int partial = 0;
      for (const auto &[node, n] : components)
        partial += n < 3 ? 1 : 0;
      checks(Utilities::MPI::sum(partial, MPI_COMM_WORLD) > 0, "np 2: some ghost nodes bring only part of their columns");
    }
  const auto space = anvil::make_coarse_space(block.problem->get_dof_handler(), block.problem->update_constraints(), K);
  const auto Ac    = anvil::galerkin_product(K.trilinos_matrix(), space);
  check_copy(checks, *Ac, "coarse A_1 = P^T K P");

  // 2D: blocks of 2 (the portable kernel alone).
  {
    anvil_test::MechanicsFixture<2> plane(scene, elastic_block(2, "0, 0, 1, 0.5, 12, 8", "bottom: ux = 0, uy = 0; top: uy = 0"));
    plane.problem->assemble_system(true);
    check_copy(checks, plane.problem->get_system_matrix().trilinos_matrix(), "2D K", 2);
  }

  // 7 rows: not nodes of 3 (on two processes: 4 and 3 rows, only one rank's share fails).
  const unsigned int p = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const bool         one = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1;
  checks(anvil::FloatBlockMatrix::make(diagonal(7, one ? 0 : (p == 0 ? 0 : 4), one ? 7 : (p == 0 ? 4 : 7)).trilinos_matrix(),
                                       3) == nullptr,
         "7 rows: refused on every process");
  checks(anvil::FloatBlockMatrix::make(diagonal(6, one ? 0 : 3 * p, one ? 6 : 3 * p + 3).trilinos_matrix(), 3) != nullptr,
         "6 rows in nodes of 3: taken");
  return checks.finish();
}
