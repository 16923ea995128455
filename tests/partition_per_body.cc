// Geometry/Partition = per body (issue 15): on any number of processes every
// process owns cells of every body, an equal share of each (cell counts differ
// by at most one), and each process's share of a body is one slab across the
// body's longest axis (the slabs' ranges along it do not overlap). Independent
// answer: the body's cell count from its Blocks entry, divided by the number of
// processes. Also: the partition of the serial mesh (np = 3) and the default
// partition still p4est's.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>

#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/geometry/partition.h>
#include <anvil/simulator/simulator.h>

#include "check.h"

#include <algorithm>
#include <limits>
#include <map>

using namespace dealii;

namespace
{
  template <int dim>
  anvil::Geometry<dim> geometry_of(anvil::Scene &scene)
  {
    scene.read_shape();
    scene.read([](ParameterHandler &prm, const anvil::Scene &s) {
      anvil::Simulator<dim>::declare_parameters(prm, s.body_names(), s.contact_pair_names(),
                                                s.contact_tool_names());
    });
    anvil::Geometry<dim> geometry;
    geometry.parse_parameters(scene.parameters(), scene);
    return geometry;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int               np = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int               rank = Utilities::MPI::this_mpi_process(comm);
  anvil::testing::Checks           check;
  check.print_on_this_process(rank == 0);

  // two_blocks' bodies refined once: lower 30 x 10 -> 1200 cells, upper 10 x 10 -> 400.
  anvil::Scene scene(ANVIL_SOURCE_DIR "/prm/two_blocks.prm",
                     {{"Geometry/Partition", "per body"}, {"Geometry/Global refinements", "1"}});
  const auto geometry = geometry_of<2>(scene);
  auto       tria     = geometry.make_triangulation(comm);
  check(dynamic_cast<parallel::fullydistributed::Triangulation<2> *>(tria.get()) != nullptr,
        "Partition = per body makes a fully distributed triangulation");
  geometry.create(*tria);
  check(tria->n_global_active_cells() == 1600,
        "1600 cells in all (" + std::to_string(tria->n_global_active_cells()) + ")");
  for (const auto &[name, expected] : std::map<std::string, unsigned int>{{"lower", 1200}, {"upper", 400}})
    {
      const auto   id    = geometry.body_id(name, "");
      unsigned int owned = 0;
      double       lo = std::numeric_limits<double>::max(), hi = -lo;
      for (const auto &cell : tria->active_cell_iterators())
        if (cell->is_locally_owned() && cell->material_id() == id)
          {
            ++owned;
            lo = std::min(lo, cell->center()[0]);
            hi = std::max(hi, cell->center()[0]);
          }
      const auto counts = Utilities::MPI::all_gather(comm, owned);
      const auto los = Utilities::MPI::all_gather(comm, lo), his = Utilities::MPI::all_gather(comm, hi);
      unsigned int total = 0, fewest = expected, most = 0;
      for (const auto n : counts)
        total += n, fewest = std::min(fewest, n), most = std::max(most, n);
      check(total == expected, name + ": " + std::to_string(total) + " cells owned in all, expected " +
                                 std::to_string(expected));
      check(fewest > 0, name + ": every one of the " + std::to_string(np) +
                          " processes owns some of its cells (fewest " + std::to_string(fewest) + ")");
      check(most - fewest <= 1 && most <= (expected + np - 1) / np,
            name + ": equal shares, " + std::to_string(fewest) + " to " + std::to_string(most) +
              " cells (expected " + std::to_string(expected) + "/" + std::to_string(np) + ")");
      bool slabs = true; // the longest axis of both blocks is x
      for (unsigned int r = 1; r < np; ++r)
        slabs = slabs && his[r - 1] <= los[r];
      check(slabs, name + ": the processes' shares are slabs in x, in process order");
    }

  // The serial partition into 3: each body in thirds, the ids 0, 1, 2 in x order.
  {
    Triangulation<2> serial;
    GridGenerator::subdivided_hyper_rectangle(serial, {12, 2}, Point<2>(0, 0), Point<2>(6, 1));
    const auto component = anvil::partition_per_body(serial, 3);
    std::map<types::subdomain_id, unsigned int> count;
    bool ordered = true;
    for (const auto &cell : serial.active_cell_iterators())
      {
        ++count[cell->subdomain_id()];
        ordered = ordered && cell->subdomain_id() == static_cast<unsigned int>(cell->center()[0] / 2);
      }
    check(std::count(component.begin(), component.end(), 0u) == 24, "one body (one component)");
    check(count.size() == 3 && count[0] == 8 && count[1] == 8 && count[2] == 8,
          "12 x 2 cells in 3: 8 each");
    check(ordered, "the thirds are x in [0, 2), [2, 4), [4, 6)");
  }

  // The default is p4est's.
  {
    anvil::Scene plain(ANVIL_SOURCE_DIR "/prm/two_blocks.prm", {});
    const auto   g = geometry_of<2>(plain);
    check(g.partition_kind() == "space-filling curve" &&
            dynamic_cast<parallel::distributed::Triangulation<2> *>(g.make_triangulation(comm).get()),
          "default Partition: space-filling curve (p4est)");
  }
  return check.finish();
}
