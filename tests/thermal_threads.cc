// The heat problem's assembly on threads (WorkStream) gives the serial
// result: M, the tangent A = ∂(K T − F)/∂T, the Newton matrix M + γA and
// f(T, t) assembled with 1, 2 and 3 threads, compared entry by entry.
// Independent answer: the serial assembly itself. The copier adds the cells
// in their serial order, so the sums are those of the serial loop. One
// round-off source remains, deal.II's own: FEValues reuses the Jacobians of
// the previous cell when a cell is a translation of it (CellSimilarity), and
// deal.II switches this off whenever more than one thread is allowed (the
// previous cell of a thread's FEValues depends on the scheduling). Integrals
// on the reference configuration (M, the Dirichlet lift in f) may so differ
// by an ulp between 1 and 2 threads (accepted: 1e-14 relative); with 2 and 3
// threads everything must be bit-identical, and so must the tangent, which
// lives on the deformed configuration (MappingQEulerian: never similar).
//
// Cases: 2D plane, 2D axisymmetric and 3D, each with hanging nodes, a
// deformed configuration, k(T) = k0 (1 + a (T − T_ref)), convection,
// radiation, a prescribed flux, a time-dependent Temperature boundary (the
// ġ lift), an expression source and a per-point source as the mechanics
// gives it; the 3D case with the lumped mass, and a linear 2D case that takes
// the fast path (K once, F from the mechanics' sources, fluxes per face).
// Runs the same under mpirun -np 2. Exits 1 on a failed check.
#include <deal.II/base/multithread_info.h>

#include "thermal_model.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

using namespace dealii;
using namespace anvil;
using anvil_test::ThermalModel;

namespace
{
  int  failures = 0;
  bool root     = true;

  /// The locally owned entries of a matrix, row by row, in storage order.
  std::vector<double> entries(const TrilinosWrappers::SparseMatrix &m)
  {
    std::vector<double> v;
    for (auto it = m.begin(); it != m.end(); ++it)
      v.push_back(it->value());
    return v;
  }

  std::vector<double> entries(const TrilinosWrappers::MPI::Vector &f)
  {
    std::vector<double> v;
    for (const auto i : f.locally_owned_elements())
      v.push_back(f(i));
    return v;
  }

  struct Assembled
  {
    std::vector<double> mass, tangent, newton, residual;
  };

  template <int dim>
  Assembled assemble(ThermalModel<dim> &model, const unsigned int threads)
  {
    MultithreadInfo::set_thread_limit(threads);
    TrilinosWrappers::MPI::Vector f;
    const auto T = model.temperature(dim == 2 ? "300 + 40*sin(x) + 15*y" : "300 + 40*sin(x) + 15*y - 5*z");
    const auto s = model.problem->assemble_system(0.3, T, 2.5e-3, f);
    return {entries(s.mass), entries(s.tangent), entries(s.newton), entries(f)};
  }

  /// max |a − b| / max |a| ≤ @p tolerance (0: bit-identical required).
  void compare(const std::string &what, const std::vector<double> &a, const std::vector<double> &b,
               const std::string &runs, const double tolerance)
  {
    double scale = 0, diff = 0;
    bool   same_size = a.size() == b.size();
    for (std::size_t i = 0; same_size && i < a.size(); ++i)
      {
        scale = std::max(scale, std::abs(a[i]));
        diff  = std::max(diff, std::abs(a[i] - b[i]));
      }
    scale = Utilities::MPI::max(scale, MPI_COMM_WORLD);
    diff  = Utilities::MPI::max(diff, MPI_COMM_WORLD);
    same_size = Utilities::MPI::min(same_size ? 1 : 0, MPI_COMM_WORLD) == 1;
    const double relative = scale > 0 ? diff / scale : diff;
    const bool   ok       = same_size && scale > 0 && relative <= tolerance;
    if (root)
      std::cout << "  " << (ok ? "PASS " : "FAIL ") << std::left << std::setw(7) << what << runs
                << ": max |difference| / max |entry| = " << std::setprecision(3) << relative
                << (diff == 0 && ok ? " (bit-identical)" : "") << ", expected "
                << (tolerance == 0 ? std::string("0") : "<= 1e-14") << std::endl;
    failures += ok ? 0 : 1;
  }

  template <int dim>
  void run_case(const std::string &name, const std::string &text, const bool axisymmetric,
                const double refine_below, const std::string &displacement)
  {
    ThermalModel<dim> model(text, axisymmetric, refine_below, displacement);
    // As the mechanics gives it: a value per quadrature point, read-only.
    model.problem->set_heat_source(
      [](const typename DoFHandler<dim>::active_cell_iterator &cell, const unsigned int q) {
        return 0.5 * std::sin(1.0 + cell->active_cell_index()) + 0.1 * q;
      });
    if (root)
      std::cout << name << ": " << model.problem->n_dofs() << " DoFs, "
                << model.tria.n_global_active_cells() << " cells" << std::endl;
    const Assembled one = assemble(model, 1), two = assemble(model, 2), three = assemble(model, 3);
    const std::vector<std::pair<std::string, std::vector<double> Assembled::*>> parts = {
      {"M", &Assembled::mass}, {"A", &Assembled::tangent}, {"M + gA", &Assembled::newton},
      {"f", &Assembled::residual}};
    for (const auto &[what, part] : parts)
      compare(what, one.*part, two.*part, " 1 vs 2 threads", 1e-14);
    for (const auto &[what, part] : parts)
      compare(what, two.*part, three.*part, " 2 vs 3 threads", 0);
  }

  const std::string heat_nonlinear =
    "subsection Heat\n"
    " set Initial temperature = 300\n"
    " set Source = 0.5*x*(1 + t)\n"
    " subsection Boundary conditions\n"
    "  set Temperature = left: 300 + 50*t\n"
    "  set Convection  = top: 0.02, 280\n"
    "  set Radiation   = right: 0.8, 350\n"
    "  set Flux        = bottom: 0.3*(1 + x); right: 0.1\n"
    " end\n"
    "end\n"
    "subsection Material\n subsection Thermal\n  set Conductivity = 50\n"
    "  set Conductivity temperature coefficient = 2e-3\n end\nend\n";
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, numbers::invalid_unsigned_int);
  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  MultithreadInfo::set_thread_limit(2);
  if (root)
    {
      std::cout << "Heat assembly, 1 thread against 2 threads (" << MultithreadInfo::n_cores()
                << " cores, " << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) << " process(es))"
                << std::endl;
      if (MultithreadInfo::n_threads() < 2)
        std::cout << "  NOTE: only " << MultithreadInfo::n_threads()
                  << " thread allowed (DEAL_II_NUM_THREADS?): both runs are serial" << std::endl;
    }

  run_case<2>("2D plane",
              "subsection Geometry\n set Blocks = body: 0, 0, 4, 2, 16, 8\nend\n" + heat_nonlinear,
              false, 1.0, "0.02*x*y; -0.01*x");
  run_case<2>("2D axisymmetric",
              "subsection Geometry\n set Blocks = body: 1, 0, 5, 2, 16, 8\nend\n" + heat_nonlinear,
              true, 2.0, "0.02*x*y; -0.01*x");
  std::string heat_3d = heat_nonlinear;
  heat_3d.replace(heat_3d.find("right: 0.1"), 10, "back: 0.1");
  heat_3d.replace(heat_3d.find(" subsection Boundary"), 0,
                  " subsection Linear solver\n  set Mass matrix = lumped\n end\n");
  run_case<3>("3D (lumped mass)",
              "subsection Geometry\n set Blocks = body: 0, 0, 0, 2, 1, 1, 8, 4, 4\nend\n" + heat_3d,
              false, 0.5, "0.02*x*y; -0.01*x; 0.01*z*x");
  run_case<2>("2D linear (fast path)",
              "subsection Geometry\n set Blocks = body: 0, 0, 4, 2, 16, 8\nend\n"
              "subsection Heat\n subsection Boundary conditions\n"
              "  set Flux = bottom: 0.3*(1 + x); right: 0.1*t; top: -0.2\n end\nend\n",
              false, 1.0, "0.02*x*y; -0.01*x");

  if (root)
    std::cout << (failures == 0 ? "all checks passed" : std::to_string(failures) + " check(s) failed")
              << std::endl;
  return failures == 0 ? 0 : 1;
}
