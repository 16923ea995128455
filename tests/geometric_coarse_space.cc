// The geometric coarse space (source/mechanics/geometric_coarse_space.cc):
// on an unstressed elastic block (standard Q1, constant coefficients, the
// tangent at u = 0 is linear elasticity, integrated exactly by 2-point Gauss
// on box cells) the Galerkin product Pᵀ K P equals the stiffness that anvil
// assembles on the coarse mesh itself (nested Q1 spaces: the coarse space is
// a subspace of the fine one, so the two bilinear forms agree on it), on the
// free coarse dofs, to round-off; a coarse dof on the supported face couples
// to nothing. Independent answer: rediscretisation. Also: P reproduces the
// linear fields (their coarse interpolant prolongs to their fine one) and a
// block with odd subdivisions is refused. One process (the comparison is
// dense).
#include <deal.II/base/mpi.h>

#include "../source/mechanics/geometric_coarse_space.h"
#include "check.h"
#include "galerkin_check.h"
#include "mechanics_fixture.h"

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

#include <cmath>
#include <iostream>
#include <sstream>

using namespace dealii;
using anvil_test::Overrides;

namespace
{
  constexpr int dim = 3;

  Overrides block(const unsigned int n)
  {
    const std::string s = std::to_string(n);
    return {{"Dimension", "3"},
            {"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 0.5, 1, " + s + ", " + s + ", " + s},
            {"Geometry/Random distortion", "0"},
            {"Bodies/body/Material/Model", "hypoelastic"},
            {"Mechanics/Element", "standard"}, // F-bar's dilatation is the fine cell's
            {"Boundary conditions/Displacement", "bottom: ux = 0, uy = 0, uz = 0"},
            {"Boundary conditions/Pressure", ""}};
  }

  /// My coarse numbering of the coarse fixture's dof at vertex @p x, component @p c.
  int coarse_index(const Point<dim> &x, const unsigned int c, const unsigned int n)
  {
    const double lower[3] = {0.1, 0, 0}, size[3] = {1, 0.5, 1};
    int          node = 0, stride = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        node += stride * static_cast<int>(std::lround((x[d] - lower[d]) / size[d] * n));
        stride *= n + 1;
      }
    return dim * node + c;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks           checks;
  const std::string                scene = std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm";
  const unsigned int               n     = 4; // coarse cells per direction

  anvil_test::MechanicsFixture<dim> fine(scene, block(2 * n));
  fine.problem->assemble_system(true);
  const auto &K     = fine.problem->get_system_matrix();
  auto        space = anvil::make_coarse_space(fine.problem->get_dof_handler(),
                                               fine.problem->update_constraints(), K);
  const auto  Ac    = anvil::galerkin_product(K.trilinos_matrix(), space);
  checks(space.n_coarse_dofs == dim * (n + 1) * (n + 1) * (n + 1), "coarse dofs: 3 (n + 1)³");

  anvil_test::MechanicsFixture<dim> coarse(scene, block(n));
  coarse.problem->assemble_system(true);
  const auto &Kc          = coarse.problem->get_system_matrix();
  const auto &constraints = coarse.problem->update_constraints();
  // The coarse fixture's dof → my numbering.
  std::vector<int> mine(Kc.m(), -1);
  for (const auto &cell : coarse.problem->get_dof_handler().active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      for (unsigned int c = 0; c < dim; ++c)
        mine[cell->vertex_dof_index(v, c)] = coarse_index(cell->vertex(v), c, n);
  checks(std::find(mine.begin(), mine.end(), -1) == mine.end(), "every coarse dof at a vertex");

  // Pᵀ K P in the coarse fixture's numbering against its own K.
  {
    std::vector<int> inverse(Kc.m());
    for (unsigned int i = 0; i < Kc.m(); ++i)
      inverse[mine[i]] = i;
    const auto         d = anvil_test::compare_to_rediscretisation(*Ac, inverse, Kc, constraints);
    std::ostringstream s, t;
    s << "Pᵀ K P = the coarse mesh's own K on the free dofs: max difference " << d.free << " of max |K_c| (<= 1e-12)";
    checks(d.free <= 1e-12, s.str());
    t << "constrained coarse dofs couple to nothing: " << d.constrained_coupling << " (<= 1e-14)";
    checks(d.constrained_coupling <= 1e-14, t.str());
  }

  // P reproduces u = (x, 2y − z, 3z + x) on the free fine dofs.
  {
    const Epetra_Map &rows = K.trilinos_matrix().RowMap();
    Epetra_Vector     uc(*space.coarse_map), uf(rows);
    const auto        field = [](const Point<dim> &x, const unsigned int c) {
      return c == 0 ? x[0] : c == 1 ? 2 * x[1] - x[2] : 3 * x[2] + x[0];
    };
    for (const auto &cell : coarse.problem->get_dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int c = 0; c < dim; ++c)
          uc[space.coarse_map->LID(coarse_index(cell->vertex(v), c, n))] = field(cell->vertex(v), c);
    space.P->Multiply(false, uc, uf);
    double error = 0;
    for (const auto &cell : fine.problem->get_dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int c = 0; c < dim; ++c)
          {
            const auto dof = cell->vertex_dof_index(v, c);
            // Fine dofs next to the support lose the constrained coarse nodes' share.
            if (cell->vertex(v)[1] > 0.5 / n + 1e-12 && !fine.problem->update_constraints().is_constrained(dof))
              error = std::max(error, std::abs(uf[rows.LID(static_cast<int>(dof))] - field(cell->vertex(v), c)));
          }
    std::ostringstream s;
    s << "P (coarse interpolant of a linear field) = its fine interpolant: " << error << " (<= 1e-13)";
    checks(error <= 1e-13, s.str());
  }

  // Odd subdivisions: no nested coarse mesh.
  {
    anvil_test::MechanicsFixture<dim> odd(scene, block(3));
    odd.problem->assemble_system(true);
    bool refused = false;
    try
      {
        anvil::make_coarse_space(odd.problem->get_dof_handler(), odd.problem->update_constraints(),
                                 odd.problem->get_system_matrix());
      }
    catch (const std::exception &e)
      {
        refused = std::string(e.what()).find("Geometry/Blocks") != std::string::npos;
      }
    checks(refused, "3 subdivisions: refused, naming Geometry/Blocks");
  }
  return checks.finish();
}
