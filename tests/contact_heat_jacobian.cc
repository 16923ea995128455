// The heat problem's Newton matrix with contact heat (seed eq. 30-34) against
// central differences of its own right-hand side f(T): on prm/two_blocks.prm
// (coarser blocks), after pressing and a few sliding steps of the isothermal
// split, the columns of a slave node's temperature and of a master node's
// must satisfy
//     (M + gamma A_total) e_j = M e_j - gamma df/dT_j,
// A_total holding the conduction and the exchange Q = hA (T_s - sum w_a T_a)
// between nodes of the two bodies that share no cell. f is linear in T (k
// constant, the exchange frozen over the step): the differences are exact but
// for round-off, so the columns agree to ~1e-10 of their largest entry. Also
// checked: each column has entries in the other body's rows (the exchange is
// really there) and they are more than round-off. Run on 1 and 2 processes
// (the second: the couplings cross the partition as ghost columns).
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>

#include <anvil/core/scene.h>
#include <anvil/coupling/coupled_problem.h>
#include <anvil/coupling/interface.h>
#include <anvil/geometry/geometry.h>
#include <anvil/simulator/simulator.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>

using namespace dealii;
using TVector = TrilinosWrappers::MPI::Vector;

namespace
{
  /// The temperature dof at reference point @p X of the body with @p material (every process).
  types::global_dof_index dof_at(const DoFHandler<2> &dofs, const Point<2> &X,
                                 const types::material_id material)
  {
    types::global_dof_index found = 0;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == material)
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(X) < 1e-9)
            found = cell->vertex_dof_index(v, 0) + 1;
    found = Utilities::MPI::max(found, dofs.get_communicator());
    AssertThrow(found > 0, ExcMessage("no node at the point"));
    return found - 1;
  }

  /// Entry (i, j) of @p A on the owner of row i, 0 elsewhere and where the pattern has none.
  double entry(const TrilinosWrappers::SparseMatrix &A, const types::global_dof_index i,
               const types::global_dof_index j)
  {
    if (!A.locally_owned_range_indices().is_element(i))
      return 0;
    for (auto e = A.begin(i); e != A.end(i); ++e)
      if (e->column() == j)
        return e->value();
    return 0;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool     root = Utilities::MPI::this_mpi_process(comm) == 0;
  std::ofstream  null_stream("/dev/null");
  int            failures = 0;
  try
    {
      // 2 x 4 and 8 x 4 cells of 0.3125 mm; pressing (2 steps), then 4 sliding steps.
      anvil::Scene scene(ANVIL_SOURCE_DIR "/prm/two_blocks.prm",
                         {{"Geometry/Blocks", "lower: 0, 0, 5, 1.25, 16, 4; upper: 0, 1.25, 1.25, 2.5, 4, 4"}});
      scene.read_shape();
      scene.read([](ParameterHandler &prm, const anvil::Scene &s) {
        anvil::Simulator<2>::declare_parameters(prm, s.body_names(), s.contact_pair_names(),
                                                s.contact_tool_names());
      });
      auto                &prm = scene.parameters();
      anvil::Geometry<2>   geometry;
      geometry.parse_parameters(prm, scene);
      const std::string    coupling = prm.get({"Physics"}, "Coupling");
      auto scheme = anvil::CouplingSchemeRegistry<2>::instance().create(coupling);
      scheme->parse_parameters(prm, scene);
      anvil::CoupledProblem<2> physics;
      physics.parse_parameters(prm, scene, geometry, true, true, coupling);
      parallel::distributed::Triangulation<2> tria(comm);
      geometry.create(tria);
      TimerOutput timer(comm, null_stream, TimerOutput::never, TimerOutput::wall_times);
      physics.setup(tria, timer, true);
      scheme->initialize(physics);
      const double dt = 5e-5;
      for (unsigned int k = 0; k < 6; ++k)
        {
          const auto r = scheme->advance(k * dt, (k + 1) * dt);
          AssertThrow(r.converged, ExcMessage("step " + std::to_string(k) + " failed"));
          scheme->commit(k * dt, (k + 1) * dt);
        }
      // The next step's exchange, as its thermal phase would see it.
      const double t = 7 * dt;
      auto        &heat = *physics.heat();
      physics.mechanics()->solve_step(6 * dt, t, false);
      heat.set_configuration(physics.mechanics()->get_dof_handler(), physics.mechanics()->displacement());
      physics.contact_problem().prepare_heat(dt);

      const auto &dofs = heat.get_dof_handler();
      const auto  lower = geometry.body_id("lower", ""), upper = geometry.body_id("upper", "");
      // A slave node (upper block's bottom, inside the contact) and a master
      // node (lower block's top) under the slid upper block.
      const auto slave  = dof_at(dofs, Point<2>(0.625, 1.25), upper);
      const auto master = dof_at(dofs, Point<2>(0.9375, 1.25), lower);

      TVector T(dofs.locally_owned_dofs(), comm), f0, fp, fm;
      T = heat.temperature();
      // A temperature field with differences across the interface (the
      // answer does not depend on it: f is linear).
      for (const auto i : dofs.locally_owned_dofs())
        T(i) += 0.01 * double(i % 7);
      T.compress(VectorOperation::insert);
      const double gamma  = 2.5e-5;
      const auto   system = heat.assemble_system(t, T, gamma, f0);
      TrilinosWrappers::SparseMatrix newton, mass;
      newton.copy_from(system.newton);
      mass.copy_from(system.mass);

      std::map<types::material_id, std::string> name{{lower, "lower"}, {upper, "upper"}};
      std::vector<types::material_id>            body_of(dofs.n_dofs(), 0);
      {
        std::vector<types::global_dof_index> cell_dofs(dofs.get_fe().n_dofs_per_cell());
        for (const auto &cell : dofs.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(cell_dofs);
              for (const auto i : cell_dofs)
                body_of[i] = cell->material_id() + 1;
            }
        Utilities::MPI::max(body_of, comm, body_of);
      }
      for (const auto &[label, j] : {std::pair<std::string, types::global_dof_index>{"slave", slave},
                                     {"master", master}})
        {
          const double h = 1.;
          TVector      Tp(T), Tm(T);
          if (Tp.locally_owned_elements().is_element(j))
            Tp(j) += h, Tm(j) -= h;
          Tp.compress(VectorOperation::insert);
          Tm.compress(VectorOperation::insert);
          heat.assemble_system(t, Tp, 0, fp);
          heat.assemble_system(t, Tm, 0, fm);
          double scale = 0, error = 0, cross = 0;
          for (const auto i : dofs.locally_owned_dofs())
            {
              const double fd = (fp(i) - fm(i)) / (2 * h);
              const double jac = -(entry(newton, i, j) - entry(mass, i, j)) / gamma;
              scale = std::max(scale, std::abs(fd));
              error = std::max(error, std::abs(jac - fd));
              if (body_of[i] != body_of[j])
                cross = std::max(cross, std::abs(jac));
            }
          scale = Utilities::MPI::max(scale, comm);
          error = Utilities::MPI::max(error, comm) / scale;
          cross = Utilities::MPI::max(cross, comm) / scale;
          const bool ok = error < 1e-9 && cross > 1e-3;
          if (root)
            std::cout << (ok ? "PASS " : "FAIL ") << label << " column (dof " << j << ", "
                      << name[body_of[j] - 1] << " block): |J e_j - FD| / max|FD| = " << error
                      << ", largest entry in the other block's rows / max|FD| = " << cross
                      << " (expected < 1e-9 and > 1e-3)" << std::endl;
          failures += !ok;
        }
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cout << "FAIL: " << e.what() << std::endl;
      return 1;
    }
  return failures > 0 ? 1 : 0;
}
