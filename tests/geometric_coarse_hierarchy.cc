// The geometric coarse space from the mesh hierarchy (source/mechanics/
// coarse_space_prolongation.cc), on meshes session 20's arithmetic refused.
// (1) Two elastic bodies (tests/geometric_two_bodies.prm, a gap between
// them, different moduli) meshed as blocks refined once, 2D and 3D: Pᵀ K P
// equals the stiffness anvil assembles on the unrefined blocks, on the free
// coarse dofs, to round-off (nested Q1 spaces and a constant-coefficient
// form integrated exactly on box cells: Galerkin = rediscretisation); a
// constrained coarse dof couples to nothing. The coarse dofs are matched by
// position (the gap keeps the bodies' nodes apart). (2) On a randomly
// distorted (non-affine) block refined once, P prolongs the coarse
// interpolant of a linear field to its fine interpolant (isoparametric Q1
// holds linear fields, and the refinement puts the children's vertices at
// the parent's reference midpoints). One process (dense comparison).
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
#include <map>
#include <sstream>

using namespace dealii;
using anvil_test::Overrides;

namespace
{
  template <int dim>
  Overrides two_bodies(const unsigned int refinements)
  {
    Overrides o = {{"Dimension", std::to_string(dim)},
                   {"Geometry/Global refinements", std::to_string(refinements)},
                   {"Bodies/a/Material/Model", "hypoelastic"},
                   {"Bodies/b/Material/Model", "hypoelastic"},
                   {"Mechanics/Element", "standard"},
                   {"Mechanics/Linear solver/Preconditioner", "AMG"}};
    if (dim == 3)
      {
        o.push_back({"Geometry/Blocks", "a: 0, 0, 0, 1, 1, 1, 4, 4, 4; b: 1.5, 0, 0, 2.5, 0.5, 1, 4, 2, 4"});
        o.push_back({"Boundary conditions/Displacement", "a.bottom: ux = 0, uy = 0, uz = 0; b.left: ux = 0, uy = 0, uz = 0"});
      }
    else
      o.push_back({"Boundary conditions/Displacement", "a.bottom: ux = 0, uy = 0; b.left: ux = 0, uy = 0"});
    return o;
  }

  template <int dim>
  void galerkin_is_rediscretisation(anvil::testing::Checks &checks, const std::string &scene)
  {
    anvil_test::MechanicsFixture<dim> fine(scene, two_bodies<dim>(1));
    fine.problem->assemble_system(true);
    const auto &K     = fine.problem->get_system_matrix();
    auto        space = anvil::make_coarse_space(fine.problem->get_dof_handler(),
                                                 fine.problem->update_constraints(), K);
    const auto  Ac    = anvil::galerkin_product(K.trilinos_matrix(), space);
    const auto  fine_at = anvil_test::dof_positions(fine.problem->get_dof_handler());
    std::map<std::pair<std::array<long, dim>, unsigned int>, int> coarse_dof_at;
    for (const auto &[row, k] : space.injection)
      {
        const auto &[x, c]                = fine_at[K.trilinos_matrix().RowMap().GID(row)];
        coarse_dof_at[anvil_test::position_key<dim>(x, c)] = k;
      }

    anvil_test::MechanicsFixture<dim> coarse(scene, two_bodies<dim>(0));
    coarse.problem->assemble_system(true);
    const auto        &Kc          = coarse.problem->get_system_matrix();
    const auto        &constraints = coarse.problem->update_constraints();
    const unsigned int N           = Kc.m();
    const std::string  d           = std::to_string(dim) + "D: ";
    checks(space.n_coarse_dofs == N && coarse_dof_at.size() == N,
           d + "coarse dofs = the unrefined mesh's (" + std::to_string(space.n_coarse_dofs) + ", " +
             std::to_string(N) + ")");
    const auto         coarse_at = anvil_test::dof_positions(coarse.problem->get_dof_handler());
    std::vector<int>   inverse(N, -1);
    for (unsigned int i = 0; i < N; ++i)
      {
        const auto it = coarse_dof_at.find(anvil_test::position_key<dim>(coarse_at[i].first, coarse_at[i].second));
        if (it != coarse_dof_at.end())
          inverse[it->second] = i;
      }
    checks(std::find(inverse.begin(), inverse.end(), -1) == inverse.end(), d + "every coarse dof at a coarse node");
    const auto difference = anvil_test::compare_to_rediscretisation(*Ac, inverse, Kc, constraints);
    std::ostringstream s, t;
    s << d << "Pᵀ K P = the unrefined mesh's own K on the free dofs: max difference " << difference.free
      << " of max |K_c| (<= 1e-12)";
    checks(difference.free <= 1e-12, s.str());
    t << d << "constrained coarse dofs couple to nothing: " << difference.constrained_coupling << " (<= 1e-14)";
    checks(difference.constrained_coupling <= 1e-14, t.str());
  }

  template <int dim>
  void linear_fields_on_distorted_cells(anvil::testing::Checks &checks, const std::string &scene)
  {
    Overrides o = {{"Dimension", std::to_string(dim)},
                   {"Geometry/Random distortion", "0.25"},
                   {"Geometry/Global refinements", "1"},
                   {"Bodies/body/Material/Model", "hypoelastic"}};
    if (dim == 3)
      o.insert(o.end(), {{"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 0.7, 4, 4, 3"},
                         {"Boundary conditions/Displacement", "bottom: ux = 0, uy = 0, uz = 0"},
                         {"Boundary conditions/Pressure", ""}});
    anvil_test::MechanicsFixture<dim> fine(scene, o);
    fine.problem->assemble_system(true);
    const auto &K     = fine.problem->get_system_matrix();
    auto        space = anvil::make_coarse_space(fine.problem->get_dof_handler(),
                                                 fine.problem->update_constraints(), K);
    const Epetra_Map &rows = K.trilinos_matrix().RowMap();
    const auto        at   = anvil_test::dof_positions(fine.problem->get_dof_handler());
    const auto field = [](const Point<dim> &x, const unsigned int c) {
      return c == 0 ? 1 + x[0] - 3 * x[1] : c == 1 ? 2 * x[1] - x[dim - 1] + 0.5 : 3 * x[dim - 1] + x[0];
    };
    Epetra_Vector uc(*space.coarse_map), uf(rows), one_c(*space.coarse_map), sum(rows);
    for (const auto &[row, k] : space.injection)
      uc[space.coarse_map->LID(k)] = field(at[rows.GID(row)].first, at[rows.GID(row)].second);
    one_c.PutScalar(1.);
    space.P->Multiply(false, uc, uf);
    space.P->Multiply(false, one_c, sum);
    // Rows next to the support lose the constrained coarse nodes' share (row sum < 1).
    double       error   = 0;
    unsigned int checked = 0;
    for (int row = 0; row < rows.NumMyElements(); ++row)
      if (std::abs(sum[row] - 1) < 1e-14 && !fine.problem->update_constraints().is_constrained(rows.GID(row)))
        {
          error = std::max(error, std::abs(uf[row] - field(at[rows.GID(row)].first, at[rows.GID(row)].second)));
          ++checked;
        }
    std::ostringstream s;
    s << dim << "D distorted cells: P (coarse interpolant of a linear field) = its fine interpolant on " << checked
      << " of " << rows.NumMyElements() << " rows: " << error << " (<= 1e-13)";
    checks(error <= 1e-13 && checked > static_cast<unsigned int>(rows.NumMyElements()) / 2, s.str());
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks           checks;
  const std::string                two = std::string(ANVIL_SOURCE_DIR) + "/tests/geometric_two_bodies.prm";
  const std::string                block = std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm";
  galerkin_is_rediscretisation<2>(checks, two);
  galerkin_is_rediscretisation<3>(checks, two);
  linear_fields_on_distorted_cells<2>(checks, block);
  linear_fields_on_distorted_cells<3>(checks, block);
  return checks.finish();
}
