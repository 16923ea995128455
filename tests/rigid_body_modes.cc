// The rigid-body modes handed to AMG (source/mechanics/rigid_body_modes.cc)
// are exact null vectors of the stiffness of the unsupported, unstressed
// body: |K r| <= 1e-12 |K|∞ |r| for the 3 modes of plane strain (F-bar Q1,
// standard Q2) and the 6 of 3D, on a randomly distorted mesh, on any number
// of processes. Independent answer: a rigid motion strains nothing, whatever
// the assembly does. Axisymmetric: the axial translation is null, the radial
// translation and the rotation are not (hoop strain u_r/r, |K r| > 1e-4
// |K|∞ |r|): so is a uniform stretch in every case, which shows the test can
// fail.
#include <deal.II/base/mpi.h>

#include <anvil/mechanics/linear_solver.h>

#include "mechanics_fixture.h"

#include <iostream>

using namespace dealii;
using anvil_test::Overrides;

namespace
{
  /// |K r| / (|K|∞ |r|).
  double null_residual(const TrilinosWrappers::SparseMatrix &K, const IndexSet &owned,
                       const std::vector<double> &mode)
  {
    TrilinosWrappers::MPI::Vector r(owned, MPI_COMM_WORLD), Kr(r);
    unsigned int                  row = 0;
    for (const auto i : owned)
      r(i) = mode[row++];
    r.compress(VectorOperation::insert);
    K.vmult(Kr, r);
    return Kr.l2_norm() / (K.linfty_norm() * r.l2_norm());
  }

  template <int dim>
  bool check(const std::string &name, const Overrides &extra, const std::vector<bool> &null)
  {
    Overrides overrides = {{"Boundary conditions/Displacement", ""},
                           {"Boundary conditions/Pressure", ""},
                           {"Dimension", std::to_string(dim)}};
    if (dim == 3)
      overrides.push_back({"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 1, 3, 3, 3"});
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    anvil_test::MechanicsFixture<dim> f(std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm",
                                        overrides);
    auto &problem = *f.problem;
    problem.assemble_system(true);
    const auto &K     = problem.get_system_matrix();
    const auto &owned = problem.get_dof_handler().locally_owned_dofs();
    auto modes = anvil::rigid_body_modes(problem.get_mapping(), problem.get_dof_handler(),
                                         &problem.displacement());
    bool ok = modes.modes.size() == null.size() && modes.node_blocks;
    // A uniform stretch u = (x − c_x, 0[, 0]): not a rigid motion. x − c_x
    // is the y component of the rotation about z (the last mode).
    std::vector<double> stretch(owned.n_elements(), 0.);
    for (unsigned int row = 0; row < stretch.size(); row += dim)
      stretch[row] = modes.modes.back()[row + 1];
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    for (unsigned int k = 0; k < modes.modes.size(); ++k)
      {
        const double e    = null_residual(K, owned, modes.modes[k]);
        const bool   pass = null[k] ? e <= 1e-12 : e > 1e-4;
        ok                = ok && pass;
        if (root)
          std::cout << name << ": mode " << k << " |K r| / (|K| |r|) = " << e
                    << (null[k] ? " (null: <= 1e-12)" : " (not null: > 1e-4)") << (pass ? "" : "  FAIL")
                    << std::endl;
      }
    const double e = null_residual(K, owned, stretch);
    ok             = ok && e > 1e-4;
    if (root)
      std::cout << name << ": uniform stretch |K r| / (|K| |r|) = " << e << " (> 1e-4)"
                << (e > 1e-4 ? "" : "  FAIL") << std::endl
                << name << ": node blocks " << (modes.node_blocks ? "yes" : "NO  FAIL") << std::endl;
    return ok;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  bool ok = true;
  ok = check<2>("plane strain, F-bar Q1", {}, {true, true, true}) && ok;
  ok = check<2>("plane strain, standard Q2",
                {{"Mechanics/Element", "standard"}, {"Mechanics/Polynomial degree", "2"}},
                {true, true, true}) && ok;
  ok = check<2>("axisymmetric, F-bar Q1", {{"Mechanics/Two-dimensional model", "axisymmetric"}},
                {false, true, false}) && ok;
  ok = check<3>("3D, F-bar Q1", {}, {true, true, true, true, true, true}) && ok;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << (ok ? "PASS" : "FAIL") << std::endl;
  return ok ? 0 : 1;
}
