// Contact search + evaluation benchmark (prints figures, asserts nothing):
// times the pieces of ContactProblem on a long contact surface, outside the
// Newton loop, for the scene given (contrib/bench/contact_strip.prm: 10001
// slave nodes on 9999 master segments).
//
//   contact_search SCENE.prm [--set 'Section/Entry=value']... [--press BODY]
//                  [--delta MM] [--repeat N]
//
// The body BODY (default: upper) is moved by uy = -delta (default 1e-4 mm)
// so that every slave node penetrates its master; then, as the mechanics
// does per step and per Newton iteration:
//   setup        gather the surfaces (once per run)
//   begin_step   tributary areas at t_n and the candidate couplings (per step)
//   couplings    the dof groups for the sparsity (per step if they grew)
//   assemble     search (R-tree of the master faces) + elements with their
//                tangents (per Newton iteration), and residual only
// Each is timed (wall, max over the processes) and also given per 10^4 slave
// nodes. The number of elements and the sum of |r_slave| (about sum t_N) of
// an evaluation are printed: they should not depend on the processes.
// Built with the tests (build/tests/bench_contact_search), so that it
// compiles whenever the library changes; contrib/bench.sh runs it.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/simulator/simulator.h>
#include <anvil/geometry/geometry.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <set>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  struct Options
  {
    std::string                                        scene;
    std::vector<std::pair<std::string, std::string>> overrides;
    std::string                                        press  = "upper";
    double                                             delta  = 1e-4;
    unsigned int                                       repeat = 5;
  };

  // Wall time of f(), the maximum over the processes.
  double timed(const std::function<void()> &f)
  {
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = MPI_Wtime();
    f();
    return Utilities::MPI::max(MPI_Wtime() - start, MPI_COMM_WORLD);
  }

  template <int dim>
  void run(anvil::Scene &scene, const Options &options)
  {
    const MPI_Comm comm = MPI_COMM_WORLD;
    const bool     root = Utilities::MPI::this_mpi_process(comm) == 0;
    auto          &prm  = scene.parameters();

    anvil::Geometry<dim> geometry;
    geometry.parse_parameters(prm, scene);
    anvil::ContactProblem<dim> contact;
    contact.parse_parameters(prm, scene, geometry);
    if (contact.empty())
      throw anvil::InputError(options.scene + ": the scene has no contact pairs (Contact/Pairs)");
    const auto pressed = geometry.body_id(options.press, "--press");

    parallel::distributed::Triangulation<dim> triangulation(comm);
    geometry.create(triangulation);
    const FESystem<dim> fe(FE_Q<dim>(1), dim);
    DoFHandler<dim>     dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    const IndexSet owned = dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

    // u_old = 0; u: the pressed body moved by -delta in y.
    TrilinosWrappers::MPI::Vector u_owned(owned, comm), u_old(owned, relevant, comm),
      u(owned, relevant, comm);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->material_id() == pressed)
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (fe.system_to_component_index(i).first == 1 && owned.is_element(dofs[i]))
              u_owned(dofs[i]) = -options.delta;
        }
    u_owned.compress(VectorOperation::insert);
    u = u_owned;
    u_old = 0;

    // Slave nodes: the vertices on the slave boundaries (both surfaces when two-pass).
    std::set<types::boundary_id> slave_ids;
    for (const auto &p : contact.get_pairs())
      {
        slave_ids.insert(p.slaves.begin(), p.slaves.end());
        if (p.two_pass)
          slave_ids.insert(p.masters.begin(), p.masters.end());
      }
    std::set<unsigned int> slave_vertices;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() && slave_ids.count(cell->face(f)->boundary_id()))
            for (const unsigned int v : cell->face(f)->vertex_indices())
              slave_vertices.insert(cell->face(f)->vertex_index(v));
    // (vertices on a partition boundary may count twice with several processes)
    const double n_slaves = Utilities::MPI::sum(double(slave_vertices.size()), comm);
    const double per      = 1e4 / n_slaves;

    // What the elements add: their count and sum |r_slave| (= sum t_N when
    // frictionless and flat; a check that np = 1 and np = 2 agree).
    double     elements = 0, slave_force = 0;
    const auto adder    = [&](const std::vector<types::global_dof_index> &,
                           const dealii::Vector<double>                &r,
                           const FullMatrix<double>                    *) {
      elements += 1;
      double r2 = 0;
      for (unsigned int d = 0; d < dim; ++d)
        r2 += r[d] * r[d];
      slave_force += std::sqrt(r2);
    };

    const double t_setup = timed([&] { contact.setup(dof_handler, false); });
    const double t_begin = timed([&] { contact.begin_step(0, 1, u_old); });
    std::size_t  groups  = 0;
    const double t_couplings = timed([&] { groups = contact.couplings().size(); });
    groups = Utilities::MPI::sum(groups, comm);
    // First evaluation: may ask for couplings outside the candidates (then again).
    bool complete = true;
    const double t_first = timed([&] { complete = contact.assemble(u, true, adder); });
    if (!complete)
      {
        contact.couplings();
        contact.assemble(u, true, adder);
      }
    elements = slave_force = 0;
    const double t_tangent = timed([&] {
      for (unsigned int k = 0; k < options.repeat; ++k)
        contact.assemble(u, true, adder);
    }) / options.repeat;
    const double active = Utilities::MPI::sum(elements, comm) / options.repeat;
    const double force  = Utilities::MPI::sum(slave_force, comm) / options.repeat;
    const double busiest = Utilities::MPI::max(elements, comm) / options.repeat;
    const double t_residual = timed([&] {
      for (unsigned int k = 0; k < options.repeat; ++k)
        contact.assemble(u, false, adder);
    }) / options.repeat;
    const double t_commit = timed([&] { contact.commit(); });

    if (root)
      {
        const auto &pair = contact.get_pairs().front();
        std::printf("contact search: %s, %s, %s%s, %u process(es)\n", options.scene.c_str(),
                    pair.name.c_str(), pair.tool >= 0 ? "node-to-tool" : "node-to-segment",
                    pair.two_pass ? " two-pass" : "", Utilities::MPI::n_mpi_processes(comm));
        std::printf("  %.0f slave nodes, %.0f in contact (elements per evaluation; the busiest process "
                    "evaluates %.0f), %zu coupling groups\n", n_slaves, active, busiest, groups);
        std::printf("  %-34s %12s %16s\n", "phase", "s", "s per 1e4 slaves");
        const auto line = [&](const char *what, const double s) {
          std::printf("  %-34s %12.6f %16.6f\n", what, s, s * per);
        };
        line("setup (once)", t_setup);
        line("begin_step (per step)", t_begin);
        line("couplings (when they grow)", t_couplings);
        line("first assemble with tangent", t_first);
        line("assemble with tangent (per Newton)", t_tangent);
        line("assemble residual only", t_residual);
        line("commit (per step)", t_commit);
        std::printf("  sum |r_slave| of an evaluation %.6e N (about sum t_N)\n", force);
      }
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Options                          options;
  try
    {
      for (int i = 1; i < argc; ++i)
        {
          const std::string a = argv[i];
          if (a == "--set" && i + 1 < argc)
            options.overrides.push_back(anvil::Scene::parse_override(argv[++i]));
          else if (a == "--press" && i + 1 < argc)
            options.press = argv[++i];
          else if (a == "--delta" && i + 1 < argc)
            options.delta = std::atof(argv[++i]);
          else if (a == "--repeat" && i + 1 < argc)
            options.repeat = std::max(1, std::atoi(argv[++i]));
          else if (options.scene.empty() && a.rfind("-", 0) != 0)
            options.scene = a;
          else
            throw anvil::InputError("unknown or incomplete option '" + a + "'");
        }
      if (options.scene.empty())
        throw anvil::InputError("usage: contact_search SCENE.prm [--set P=V]... [--press BODY] "
                                "[--delta MM] [--repeat N]");
      anvil::Scene scene(options.scene, options.overrides);
      scene.read_shape();
      if (scene.dimension() == 2)
        {
          scene.read([](ParameterHandler &prm, const anvil::Scene &s) {
            anvil::Simulator<2>::declare_parameters(prm, s.body_names(), s.contact_pair_names(),
                                                    s.contact_tool_names());
          });
          run<2>(scene, options);
        }
      else
        {
          scene.read([](ParameterHandler &prm, const anvil::Scene &s) {
            anvil::Simulator<3>::declare_parameters(prm, s.body_names(), s.contact_pair_names(),
                                                    s.contact_tool_names());
          });
          run<3>(scene, options);
        }
    }
  catch (const anvil::InputError &e)
    {
      std::cerr << "contact_search: error: " << e.what() << std::endl;
      return 2;
    }
  return 0;
}
