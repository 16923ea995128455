// Benchmark (prints figures, asserts nothing): one full mechanical assembly
// (tangent + residual, as in every Newton iteration) on 1 and 2 threads, for
// a 2D plane-strain J2 F-bar block and a 3D one, in a plastic state (one
// Newton iteration into the first step of tests/plastic_block.prm). Best of
// several repetitions; the speed-up is t(1 thread) / t(2 threads).
//   bench_assembly_threads [--quick]
#include <deal.II/base/multithread_info.h>

#include "../../tests/mechanics_fixture.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

using namespace dealii;

namespace
{
  template <int dim>
  void run(const char *name, const anvil_test::Overrides &overrides, const unsigned int repetitions)
  {
    anvil_test::MechanicsFixture<dim> f(std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm",
                                        overrides);
    f.run_steps(1); // stops after one Newton iteration (Maximum iterations = 1): plastic
    const unsigned int cells = f.triangulation.n_global_active_cells();
    double             best[3] = {0, 0, 0};
    for (const unsigned int threads : {1u, 2u})
      {
        MultithreadInfo::set_thread_limit(threads);
        f.problem->assemble_system(true); // warm up (first touch, thread pool)
        double t_min = std::numeric_limits<double>::max();
        for (unsigned int r = 0; r < repetitions; ++r)
          {
            const auto start = std::chrono::steady_clock::now();
            f.problem->assemble_system(true);
            t_min = std::min(t_min, std::chrono::duration<double>(
                                      std::chrono::steady_clock::now() - start)
                                      .count());
          }
        best[threads] = t_min;
        std::printf("%-34s %8u cells %9u DoFs  %u thread(s): %8.4f s per assembly, %9.0f cells/s\n",
                    name, cells, static_cast<unsigned int>(f.problem->n_dofs()), threads, t_min,
                    cells / t_min);
      }
    std::printf("%-34s speed-up with 2 threads: %.2f (largest plastic increment %.3g)\n", name,
                best[1] / best[2], f.problem->largest_plastic_increment());
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  const bool         quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const unsigned int n2 = quick ? 64 : 256, n3 = quick ? 10 : 24, repetitions = quick ? 3 : 5;
  std::printf("mechanical assembly, tangent + residual, one process, %u cores\n",
              MultithreadInfo::n_cores());
  if (std::getenv("DEAL_II_NUM_THREADS"))
    std::printf("note: DEAL_II_NUM_THREADS=%s caps the threads\n", std::getenv("DEAL_II_NUM_THREADS"));
  const anvil_test::Overrides common = {{"Mechanics/Element", "F-bar"},
                                        {"Mechanics/Newton/Maximum iterations", "1"},
                                        {"Mechanics/Linear solver/Type", "iterative"},
                                        {"Mechanics/Linear solver/Tolerance", "1e-6"}};
  anvil_test::Overrides plane = common;
  plane.push_back({"Geometry/Blocks", "body: 0.1, 0, 1.1, 1, " + std::to_string(n2) + ", " +
                                        std::to_string(n2)});
  anvil_test::Overrides solid = common;
  solid.push_back({"Dimension", "3"});
  solid.push_back({"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 1, " + std::to_string(n3) + ", " +
                                        std::to_string(n3) + ", " + std::to_string(n3)});
  solid.push_back({"Boundary conditions/Displacement",
                   "bottom: ux = 0, uy = 0, uz = 0; top: ux = 0.05*t, uy = -0.1*t, uz = 0"});
  run<2>("2D plane strain J2 F-bar, pressure", plane, repetitions);
  run<3>("3D J2 F-bar, pressure", solid, repetitions);
  return 0;
}
