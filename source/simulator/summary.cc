#include <deal.II/base/mpi.h>

#include <anvil/core/instantiate.h>
#include <anvil/simulator/simulator.h>

#include <fstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    double peak_memory_mb()
    {
      std::ifstream status("/proc/self/status");
      std::string   line;
      while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0)
          return std::stod(line.substr(6)) / 1024.;
      return 0;
    }
  } // namespace

  /// summary.json: what the run was, what it cost, and every output's section.
  template <int dim>
  void Simulator<dim>::write_summary(const std::string &status)
  {
    const auto *mechanical = physics.mechanics();
    const auto *thermal    = physics.heat();
    Summary     s;
    s.set("scene", scene.filename());
    s.set("status", status);
    s.set("dimension", dim);
    s.set("processes", Utilities::MPI::n_mpi_processes(mpi_communicator));
    s.set("cells", triangulation->n_global_active_cells());
    s.set("coupling", coupling);
    s.set("dofs", mechanical ? double(mechanical->n_dofs()) : 0.);
    if (thermal)
      s.set("temperature_dofs", double(thermal->n_dofs()));
    s.set("time", current_time);
    s.set("steps", statistics.steps);
    s.set("cut_backs", statistics.cut_backs);
    s.set("newton_iterations", double(statistics.newton_iterations));
    s.set("linear_iterations", double(statistics.linear_iterations));
    s.set("wall_time", MPI_Wtime() - wall_start);
    // The step loop without outputs, checkpoints, set-up and closing (the
    // slowest process's wall clock, the processes' CPU seconds summed).
    s.set("step_loop_wall_time", Utilities::MPI::max(step_loop_wall, mpi_communicator));
    s.set("step_loop_cpu_time", Utilities::MPI::sum(step_loop_cpu, mpi_communicator));
    for (const auto &[section, seconds] : timer->get_summary_data(TimerOutput::total_wall_time))
      s.set("wall_time_per_phase", section, Utilities::MPI::max(seconds, mpi_communicator));
    // CPU seconds per phase, summed over the processes: what a loaded
    // machine does not inflate (contrib/bench/perf.py's CPU ratio).
    for (const auto &[section, seconds] : timer->get_summary_data(TimerOutput::total_cpu_time))
      s.set("cpu_time_per_phase", section, Utilities::MPI::sum(seconds, mpi_communicator));
    if (mechanical)
      s.set("assembly_cells_per_second_per_process",
            Utilities::MPI::min(mechanical->last_assembly_rate(), mpi_communicator));
    const double memory = Utilities::MPI::sum(peak_memory_mb(), mpi_communicator);
    s.set("peak_memory_MB", memory);
    const double all_dofs =
      (mechanical ? mechanical->n_dofs() : 0) + (thermal ? thermal->n_dofs() : 0);
    // Above the memory before the mesh (MPI, deal.II, Trilinos: ~100 MB per
    // process), which would otherwise dominate a small scene's figure.
    const double baseline = Utilities::MPI::sum(baseline_memory_mb, mpi_communicator);
    s.set("memory_per_dof_bytes",
          std::max(0., memory - baseline) * 1024. * 1024. / std::max<double>(1, all_dofs));
    const auto now = state(current_time, statistics.steps);
    for (const auto &o : outputs)
      o->add_to_summary(now, s);
    // Units beside the numbers (the quantities of interest add theirs above).
    s.set("units", "time", "s");
    s.set("units", "wall_time", "s");
    s.set("units", "step_loop_wall_time", "s");
    s.set("units", "step_loop_cpu_time", "s");
    s.set("units", "peak_memory_MB", "MB");
    s.set("units", "energy", "N mm");
    s.set("units", "heat", "mJ");
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      s.write(output_dir + "/summary.json");
  }

#define INSTANTIATE(dim) template void Simulator<dim>::write_summary(const std::string &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
