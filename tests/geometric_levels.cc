// Three levels of geometric coarse spaces (source/mechanics/
// coarse_space_levels.cc, galerkin_product.cc), one process:
// (1) box path: an unstressed elastic 3D block of 8³ equal cells (standard
// Q1, constant coefficients, 2-point Gauss exact on box cells): the level-2
// operator A_2 = P₂ᵀ (P₁ᵀ K P₁) P₂ equals the stiffness anvil assembles on
// the 2³ block itself on the free coarse dofs, to round-off (nested Q1
// spaces: Galerkin = rediscretisation), constrained coarse dofs couple to
// nothing, the row-by-row product equals EpetraExt's, and P₁P₂ maps a linear
// field's level-2 interpolant to its fine interpolant;
// (2) hierarchy path: two elastic bodies with a gap and different moduli
// (tests/geometric_two_bodies.prm) refined twice, 2D and 3D: A_2 equals the
// unrefined blocks' own K (coarse dofs matched by position);
// (3) a randomly distorted block refined twice, 2D and 3D: P₁P₂ maps linear
// fields exactly (the isoparametric Q1 space of every ancestor holds them,
// and each refinement puts the children's vertices at the parent's
// reference midpoints).
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
  std::string dims()
  {
    return std::to_string(dim) + "D: ";
  }

  /// P₁ P₂ (level-2 interpolant of a linear field) against the fine
  /// interpolant, on the free fine rows whose P₁P₂ row sums to 1 (rows near
  /// the support lose the constrained coarse nodes' share).
  template <int dim>
  void linear_field_through_two_levels(anvil::testing::Checks &checks, const std::string &what,
                                       const anvil_test::MechanicsFixture<dim> &fine, const anvil::CoarseSpace &space)
  {
    const auto        &K    = fine.problem->get_system_matrix();
    const Epetra_Map  &rows = K.trilinos_matrix().RowMap();
    const auto         at   = anvil_test::dof_positions(fine.problem->get_dof_handler());
    const auto        &two  = *space.coarser;
    const auto field = [](const Point<dim> &x, const unsigned int c) {
      return c == 0 ? 1 + x[0] - 3 * x[1] : c == 1 ? 2 * x[1] - x[dim - 1] + 0.5 : 3 * x[dim - 1] + x[0];
    };
    Epetra_Vector u2(*two.coarse_map), one2(*two.coarse_map), u1(*space.coarse_map), one1(*space.coarse_map),
      uf(rows), sum(rows);
    // Level-2 dof k sits at the fine dof of fine_nodes (hierarchy) or at the
    // fine dof injected twice (box).
    std::map<int, int> fine_of;
    if (!two.fine_nodes.empty())
      for (const auto &[row, k] : two.fine_nodes)
        fine_of[k] = row;
    else
      {
        std::map<int, int> fine_of_level1;
        for (const auto &[row, k] : space.injection)
          fine_of_level1[k] = row;
        for (const auto &[row1, k] : two.injection)
          fine_of[k] = fine_of_level1.at(space.coarse_map->GID(row1));
      }
    for (const auto &[k, row] : fine_of)
      u2[two.coarse_map->LID(k)] = field(at[rows.GID(row)].first, at[rows.GID(row)].second);
    one2.PutScalar(1.);
    two.P->Multiply(false, u2, u1);
    space.P->Multiply(false, u1, uf);
    two.P->Multiply(false, one2, one1);
    space.P->Multiply(false, one1, sum);
    double       error   = 0;
    unsigned int checked = 0;
    for (int row = 0; row < rows.NumMyElements(); ++row)
      if (std::abs(sum[row] - 1) < 1e-14 && !fine.problem->update_constraints().is_constrained(rows.GID(row)))
        {
          error = std::max(error, std::abs(uf[row] - field(at[rows.GID(row)].first, at[rows.GID(row)].second)));
          ++checked;
        }
    std::ostringstream s;
    s << dims<dim>() << what << ": P₁P₂ (level-2 interpolant of a linear field) = its fine interpolant on " << checked
      << " of " << rows.NumMyElements() << " rows: " << error << " (<= 1e-13)";
    checks(error <= 1e-13 && checked > static_cast<unsigned int>(rows.NumMyElements()) / 4, s.str());
  }

  /// Three levels asked for, three made.
  template <int dim>
  anvil::CoarseSpace three_levels(anvil::testing::Checks &checks, const anvil_test::MechanicsFixture<dim> &fine)
  {
    const auto &K     = fine.problem->get_system_matrix();
    auto        space = anvil::make_coarse_space(fine.problem->get_dof_handler(), fine.problem->update_constraints(), K);
    const unsigned int levels =
      anvil::add_coarse_levels(fine.problem->get_dof_handler(), fine.problem->update_constraints(), K, space, 3, 0);
    checks(levels == 3 && space.coarser && !space.coarser->coarser,
           dims<dim>() + "three levels made (" + std::to_string(levels) + ")");
    return space;
  }

  void report(anvil::testing::Checks &checks, const std::string &what, const anvil_test::GalerkinDifference &d)
  {
    std::ostringstream s, t;
    s << what << ": A_2 = the twice coarser mesh's own K on the free dofs: max difference " << d.free
      << " of max |K_c| (<= 1e-12)";
    checks(d.free <= 1e-12, s.str());
    t << what << ": constrained level-2 dofs couple to nothing: " << d.constrained_coupling << " (<= 1e-14)";
    checks(d.constrained_coupling <= 1e-14, t.str());
  }

  Overrides block(const unsigned int n)
  {
    const std::string s = std::to_string(n);
    return {{"Dimension", "3"},
            {"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 0.5, 1, " + s + ", " + s + ", " + s},
            {"Geometry/Random distortion", "0"},
            {"Bodies/body/Material/Model", "hypoelastic"},
            {"Mechanics/Element", "standard"},
            {"Boundary conditions/Displacement", "bottom: ux = 0, uy = 0, uz = 0"},
            {"Boundary conditions/Pressure", ""}};
  }

  void box_path(anvil::testing::Checks &checks, const std::string &scene)
  {
    constexpr int                     dim = 3;
    anvil_test::MechanicsFixture<dim> fine(scene, block(8));
    fine.problem->assemble_system(true);
    const auto &K     = fine.problem->get_system_matrix();
    const auto  space = three_levels(checks, fine);
    const auto  A1    = anvil::galerkin_product_by_rows(K.trilinos_matrix(), *space.P);
    {
      const auto         reference = anvil::galerkin_product(K.trilinos_matrix(), space);
      const double       d         = anvil_test::relative_difference(*reference, *A1);
      std::ostringstream s;
      s << "3D box: A_1 row by row = EpetraExt's Pᵀ (K P): " << d << " of its largest entry (<= 1e-14)";
      checks(d <= 1e-14, s.str());
    }
    const auto A2 = anvil::galerkin_product_by_rows(*A1, *space.coarser->P);
    checks(space.coarser->n_coarse_dofs == dim * 27, "3D box: level 2 = the 2³ block's 81 dofs");

    anvil_test::MechanicsFixture<dim> coarse(scene, block(2));
    coarse.problem->assemble_system(true);
    const auto        &Kc = coarse.problem->get_system_matrix();
    std::vector<int>   inverse(Kc.m(), -1);
    const double       lower[3] = {0.1, 0, 0}, size[3] = {1, 0.5, 1};
    for (const auto &cell : coarse.problem->get_dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int c = 0; c < dim; ++c)
          {
            int node = 0, stride = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                node += stride * static_cast<int>(std::lround((cell->vertex(v)[d] - lower[d]) / size[d] * 2));
                stride *= 3;
              }
            inverse[dim * node + c] = cell->vertex_dof_index(v, c);
          }
    checks(std::find(inverse.begin(), inverse.end(), -1) == inverse.end(), "3D box: every level-2 dof at a vertex");
    report(checks, "3D box", anvil_test::compare_to_rediscretisation(*A2, inverse, Kc, coarse.problem->update_constraints()));
    linear_field_through_two_levels(checks, "box", fine, space);
  }

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
        o.push_back({"Geometry/Blocks", "a: 0, 0, 0, 1, 1, 1, 2, 2, 2; b: 1.5, 0, 0, 2.5, 0.5, 1, 2, 1, 2"});
        o.push_back({"Boundary conditions/Displacement", "a.bottom: ux = 0, uy = 0, uz = 0; b.left: ux = 0, uy = 0, uz = 0"});
      }
    else
      o.push_back({"Boundary conditions/Displacement", "a.bottom: ux = 0, uy = 0; b.left: ux = 0, uy = 0"});
    return o;
  }

  template <int dim>
  void hierarchy_path(anvil::testing::Checks &checks, const std::string &scene)
  {
    anvil_test::MechanicsFixture<dim> fine(scene, two_bodies<dim>(2));
    fine.problem->assemble_system(true);
    const auto &K     = fine.problem->get_system_matrix();
    const auto  space = three_levels(checks, fine);
    const auto  A1    = anvil::galerkin_product_by_rows(K.trilinos_matrix(), *space.P);
    {
      const auto         reference = anvil::galerkin_product(K.trilinos_matrix(), space);
      const double       d         = anvil_test::relative_difference(*reference, *A1);
      std::ostringstream s;
      s << dims<dim>() << "two bodies: A_1 row by row = EpetraExt's: " << d << " (<= 1e-14)";
      checks(d <= 1e-14, s.str());
    }
    const auto A2      = anvil::galerkin_product_by_rows(*A1, *space.coarser->P);
    const auto fine_at = anvil_test::dof_positions(fine.problem->get_dof_handler());
    std::map<std::pair<std::array<long, dim>, unsigned int>, int> level2_at;
    for (const auto &[row, k] : space.coarser->fine_nodes)
      {
        const auto &[x, c]                          = fine_at[K.trilinos_matrix().RowMap().GID(row)];
        level2_at[anvil_test::position_key<dim>(x, c)] = k;
      }

    anvil_test::MechanicsFixture<dim> coarse(scene, two_bodies<dim>(0));
    coarse.problem->assemble_system(true);
    const auto        &Kc = coarse.problem->get_system_matrix();
    const unsigned int N  = Kc.m();
    checks(space.coarser->n_coarse_dofs == N && level2_at.size() == N,
           dims<dim>() + "level-2 dofs = the unrefined mesh's (" + std::to_string(space.coarser->n_coarse_dofs) +
             ", " + std::to_string(N) + ")");
    const auto       coarse_at = anvil_test::dof_positions(coarse.problem->get_dof_handler());
    std::vector<int> inverse(N, -1);
    for (unsigned int i = 0; i < N; ++i)
      {
        const auto it = level2_at.find(anvil_test::position_key<dim>(coarse_at[i].first, coarse_at[i].second));
        if (it != level2_at.end())
          inverse[it->second] = i;
      }
    checks(std::find(inverse.begin(), inverse.end(), -1) == inverse.end(),
           dims<dim>() + "every level-2 dof at an unrefined node");
    report(checks, dims<dim>() + "two bodies",
           anvil_test::compare_to_rediscretisation(*A2, inverse, Kc, coarse.problem->update_constraints()));
  }

  template <int dim>
  void distorted(anvil::testing::Checks &checks, const std::string &scene)
  {
    Overrides o = {{"Dimension", std::to_string(dim)},
                   {"Geometry/Random distortion", "0.25"},
                   {"Geometry/Global refinements", "2"},
                   {"Bodies/body/Material/Model", "hypoelastic"}};
    if (dim == 3)
      o.insert(o.end(), {{"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 0.7, 2, 2, 2"},
                         {"Boundary conditions/Displacement", "bottom: ux = 0, uy = 0, uz = 0"},
                         {"Boundary conditions/Pressure", ""}});
    anvil_test::MechanicsFixture<dim> fine(scene, o);
    fine.problem->assemble_system(true);
    const auto space = three_levels(checks, fine);
    linear_field_through_two_levels(checks, "distorted cells refined twice", fine, space);
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks           checks;
  const std::string                two   = std::string(ANVIL_SOURCE_DIR) + "/tests/geometric_two_bodies.prm";
  const std::string                block = std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm";
  box_path(checks, block);
  hierarchy_path<2>(checks, two);
  hierarchy_path<3>(checks, two);
  distorted<2>(checks, block);
  distorted<3>(checks, block);
  return checks.finish();
}
