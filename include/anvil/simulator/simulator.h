#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <anvil/core/scene.h>
#include <anvil/coupling/coupled_problem.h>
#include <anvil/coupling/interface.h>
#include <anvil/geometry/geometry.h>
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/step_breakpoints.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * One simulation of a scene: builds the mesh, the physics the coupling
   * scheme needs and the outputs, then runs the time loop with cut-back and
   * re-growth of the step, checkpoints and restart. It knows no scheme and no
   * output by name: both come from their registries (coupling/interface.h,
   * postprocess/interface.h).
   */
  template <int dim>
  class Simulator
  {
  public:
    /// Every parameter of a scene of this dimension with these bodies.
    static void declare_parameters(dealii::ParameterHandler       &prm,
                                   const std::vector<std::string> &body_names,
                                   const std::vector<std::string> &contact_pair_names = {},
                                   const std::vector<std::string> &contact_tool_names = {});

    /// Parse the scene and check it against the mesh; throws InputError.
    Simulator(Scene &scene, MPI_Comm communicator);
    ~Simulator();

    /// Run the time loop. Returns false if a step could not be recovered, after
    /// writing the last converged state, a checkpoint and summary.json;
    /// failure() says why.
    bool run();
    /// --check: build the mesh the run would use and check the scene against
    /// it (mesh file, size, cells, probes), then stop; throws InputError.
    void check();
    const std::string &failure() const { return failure_reason; }

    /// The output directory of this run.
    const std::string &output_directory() const { return output_dir; }

    /// Quantities of interest as evaluated at the end of the run (name, value).
    std::vector<std::pair<std::string, double>> quantities_of_interest() const;

  private:
    struct TimeParameters
    {
      double       end_time, time_step, minimum_time_step, maximum_time_step, growth_factor;
      unsigned int easy_iterations;
      // Time/Breakpoints and the step the loop restarts with after each.
      StepBreakpoints breakpoints;
      double          step_after_breakpoint;
    };

    bool run_steps();
    void parse_time(dealii::ParameterHandler &prm);
    void parse_output(dealii::ParameterHandler &prm);
    /// Refuses (InputError) an output directory that cannot be created or written.
    void check_output_directory() const;
    void setup();
    /// After setup: every output checks the scene against the mesh.
    void check_against_mesh();
    /// The state outputs read, at time @p t after @p step accepted steps.
    SimulationState<dim> state(double t, unsigned int step, bool last = false) const;
    void print_start() const;
    void print_step(const StepReport<dim> &r, double t, double step) const;
    /// The last line of a run: where the results are and what was written.
    void print_results() const;
    /// Every output's accepted() under the Output timer.
    void output_step(const StepReport<dim> *r, double t, bool last);
    void write_summary(const std::string &status);
    /// Stop after an unrecoverable step: last converged fields, checkpoint, summary.
    void stop(const std::string &status, double t, double last_accepted_step);

    // Checkpoints (simulator/checkpoint.cc): named, versioned entries in state.txt.
    void write_checkpoint(double time, double time_step);
    void read_checkpoint(double &time, double &time_step);
    void write_state(const std::string &filename, double time, double time_step,
                     const std::string                        &contact_state,
                     const std::map<std::string, std::string> &output_state) const;
    /// Refuses (InputError) a checkpoint of another scene, scheme or format.
    void check_checkpoint() const;

    Scene                                            &scene;
    MPI_Comm                                          mpi_communicator;
    dealii::ConditionalOStream                        pcout;
    std::unique_ptr<dealii::TimerOutput>              timer; // made by run(), not at parse
    // Geometry/Partition's kind: p4est's or fully distributed (per body).
    std::unique_ptr<dealii::parallel::DistributedTriangulationBase<dim>> triangulation;
    Geometry<dim>                                     geometry;
    std::string                                       coupling; // Physics/Coupling
    std::unique_ptr<CouplingScheme<dim>>              scheme;
    CoupledProblem<dim>                               physics;
    SceneContents<dim>                                contents;
    std::vector<std::unique_ptr<Postprocessor<dim>>>  outputs;
    TimeParameters                                    time;
    RunStatistics                                     statistics;

    std::string output_dir;
    unsigned int checkpoint_interval = 0;
    std::string restart_directory;
    bool        quiet        = false;
    double      current_time = 0;
    double      wall_start   = 0;
    // Resident memory before the mesh and the physics (MPI, libraries): the
    // baseline subtracted from the peak for memory_per_dof_bytes.
    double      baseline_memory_mb = 0;
    // Wall and CPU seconds of the step loop's own work (attempts, commit,
    // newton.csv, the step line; no outputs, checkpoints, set-up or closing):
    // summary.json's step_loop_*_time, perf.py's Newton ratio.
    double      step_loop_wall = 0;
    double      step_loop_cpu  = 0;
    // (wall clock, time) at the last accepted steps: the ETA from the recent
    // rate, failed attempts included (honest during a cut-back cascade).
    mutable std::vector<std::pair<double, double>> recent_steps;
    std::string failure_reason;
  };

  /// The program: parse the command line, read the scene, dispatch on dimension.
  int run_anvil(int argc, char **argv);
} // namespace anvil
