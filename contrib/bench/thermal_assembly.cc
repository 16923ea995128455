// Heat assembly time with 1 and 2 threads (WorkStream): the mass matrix, the
// tangent A = ∂(K T − F)/∂T and the residual f(T, t) of ThermalProblem, on a
// ~20k-DoF 2D and a ~30k-DoF 3D Q1 mesh with k(T), convection, radiation, an
// expression source, a per-point source as the mechanics gives it, on a
// deformed configuration (MappingQEulerian, as in a coupled run). Prints the
// best of a few repeats and the speed-up; asserts nothing (ctest label "bench").
//
//   build/tests/bench_thermal_assembly             # 2D 141^2, 3D 30^3, 5 repeats
//   build/tests/bench_thermal_assembly --quick     # 2D 50^2, 3D 12^3, 2 repeats
//
// DEAL_II_NUM_THREADS caps the threads: unset it (contrib/bench.sh sets 1 for
// the other figures).
#include <deal.II/base/multithread_info.h>

#include "thermal_model.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <string>
#include <vector>

using namespace dealii;
using namespace anvil;
using anvil_test::ThermalModel;

namespace
{
  const char *sections[] = {"Heat: mass matrix", "Heat: tangent", "Heat: residual"};

  const std::string heat =
    "subsection Heat\n"
    " set Initial temperature = 300\n"
    " set Source = 0.5*x*(1 + t)\n"
    " subsection Boundary conditions\n"
    "  set Convection = top: 0.02, 280; bottom: 0.01, 290\n"
    "  set Radiation  = right: 0.8, 350\n"
    "  set Flux       = left: 0.3\n"
    " end\n"
    "end\n"
    "subsection Material\n subsection Thermal\n  set Conductivity = 50\n"
    "  set Conductivity temperature coefficient = 2e-3\n end\nend\n";

  /// CPU time of the process, all threads (s).
  double cpu_seconds()
  {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }

  /// Best (smallest) seconds per section and in all, over @p repeats.
  template <int dim>
  std::map<std::string, double> measure(ThermalModel<dim> &model, const unsigned int threads,
                                        const unsigned int repeats)
  {
    MultithreadInfo::set_thread_limit(threads);
    const auto T = model.temperature(dim == 2 ? "300 + 40*sin(x) + 15*y" : "300 + 40*sin(x) + 15*y - 5*z");
    std::map<std::string, double> best;
    for (unsigned int r = 0; r < repeats; ++r)
      {
        model.timer.reset();
        TrilinosWrappers::MPI::Vector f;
        const double cpu_start = cpu_seconds();
        const auto   start     = std::chrono::steady_clock::now();
        model.problem->assemble_system(0.3, T, 0, f);
        const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto data = model.timer.get_summary_data(TimerOutput::total_wall_time);
        data["all three"]     = total;
        data["all three, CPU"] = cpu_seconds() - cpu_start;
        for (const auto &[name, seconds] : data)
          best[name] = best.count(name) ? std::min(best[name], seconds) : seconds;
      }
    return best;
  }

  template <int dim>
  void run(const unsigned int n, const unsigned int repeats)
  {
    const std::string blocks =
      dim == 2 ? "body: 0, 0, 1, 1, " + std::to_string(n) + ", " + std::to_string(n) :
                 "body: 0, 0, 0, 1, 1, 1, " + std::to_string(n) + ", " + std::to_string(n) + ", " + std::to_string(n);
    ThermalModel<dim> model("subsection Geometry\n set Blocks = " + blocks + "\nend\n" + heat, false, -1,
                            dim == 2 ? "0.02*x*y; -0.01*x" : "0.02*x*y; -0.01*x; 0.01*z*x");
    // The mechanics' sources: a value per point in a flat array, as MechanicalProblem keeps them.
    const unsigned int  n_q = model.problem->get_quadrature().size();
    std::vector<double> sources(model.tria.n_active_cells() * n_q);
    for (std::size_t i = 0; i < sources.size(); ++i)
      sources[i] = 0.1 * (i % 17);
    model.problem->set_heat_source(
      [&sources, n_q](const typename DoFHandler<dim>::active_cell_iterator &cell, const unsigned int q) {
        return sources[cell->active_cell_index() * n_q + q];
      });
    const auto one = measure(model, 1, repeats), two = measure(model, 2, repeats);
    std::printf("%dD, %u DoFs, %u cells (best of %u):\n", dim, model.problem->n_dofs(),
                model.tria.n_global_active_cells(), repeats);
    std::printf("  %-20s %12s %12s %9s\n", "", "1 thread s", "2 threads s", "speed-up");
    std::vector<std::string> rows(std::begin(sections), std::end(sections));
    rows.push_back("all three");
    for (const auto &name : rows)
      if (one.count(name) && two.count(name))
        std::printf("  %-20s %12.4f %12.4f %9.2f\n", name.c_str(), one.at(name), two.at(name),
                    one.at(name) / two.at(name));
    // On a loaded machine the wall-clock speed-up says little: the CPU time
    // shows what the threads cost in extra work, and CPU/wall how much of the
    // time two threads actually ran.
    const double cpu1 = one.at("all three, CPU"), cpu2 = two.at("all three, CPU");
    std::printf("  all three, CPU s     %12.4f %12.4f   (2 threads: %.2f of the work of 1; ran %.2f cores)\n",
                cpu1, cpu2, cpu2 / cpu1, cpu2 / two.at("all three"));
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, numbers::invalid_unsigned_int);
  bool         quick   = false;
  unsigned int repeats = 5;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true, repeats = 2;
    else if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
      repeats = std::max(1, std::atoi(argv[++i]));
  MultithreadInfo::set_thread_limit(2);
  std::printf("Heat assembly with WorkStream, 1 and 2 threads (%u cores, up to %u threads allowed)\n",
              MultithreadInfo::n_cores(), MultithreadInfo::n_threads());
  if (MultithreadInfo::n_threads() < 2)
    std::printf("  NOTE: DEAL_II_NUM_THREADS limits the threads: the 2-thread figures are serial\n");
  run<2>(quick ? 50 : 141, repeats);
  run<3>(quick ? 12 : 30, repeats);
  std::printf("sections as ThermalProblem's timer names them; 'all three' is assemble_system "
              "(mass, tangent, residual) by the clock\n");
  return 0;
}
