#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <anvil/core/csv_history.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/registry.h>
#include <anvil/coupling/coupled_problem.h>

#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /// Counters of the whole run (every attempted step counts, failed ones too).
  struct RunStatistics
  {
    unsigned int  steps = 0, cut_backs = 0;
    unsigned long newton_iterations = 0, linear_iterations = 0;
    unsigned long heat_internal_steps = 0, heat_nonlinear_iterations = 0,
                  staggered_iterations = 0;
  };

  /**
   * What an output may read of the running simulation: the mesh, the
   * physics, the time and the run's counters (ASPECT's SimulatorAccess).
   * Read-only: an output never changes the solution.
   */
  template <int dim>
  struct SimulationState
  {
    const Scene                                             &scene;
    MPI_Comm                                                 communicator;
    const dealii::parallel::DistributedTriangulationBase<dim> &triangulation;
    const Geometry<dim>                                     &geometry;
    const CoupledProblem<dim>                               &physics;
    const std::string                                       &coupling; // Physics/Coupling
    const std::string                                       &output_directory;
    const RunStatistics                                     &statistics;
    dealii::TimerOutput                                     &timer;
    double                                                   time = 0;
    unsigned int                                             step = 0;
    bool                                                     last_step = false;

    bool is_root() const { return dealii::Utilities::MPI::this_mpi_process(communicator) == 0; }
  };

  /// What the scene has, for outputs checking their parameters before any work.
  template <int dim>
  struct SceneContents
  {
    bool                       mechanics = true;   // a displacement field
    bool                       heat      = false;  // a heat equation
    bool                       temperature = false; // a temperature (solved or prescribed)
    bool                       steady_heat = false; // a steady heat solve (Method or initial field)
    const Geometry<dim>       *geometry = nullptr;
    const ContactProblem<dim> *contact  = nullptr;
  };

  /**
   * One output: its file (or summary.json section), its columns and its
   * parameters in one place. Every registered postprocessor is created for
   * every run and decides from the scene whether it applies; a step program
   * adds its own with ANVIL_REGISTER_POSTPROCESSOR from outside the library.
   *
   * Call order: parse_parameters (before any work) → start (files opened;
   * appended to after a restart) → initial (t = 0, not after a restart) →
   * for every attempted step attempt(), for every accepted one accepted() →
   * finish (end of run or unrecoverable failure) → add_to_summary.
   */
  template <int dim>
  class Postprocessor
  {
  public:
    virtual ~Postprocessor() = default;

    /// The output's own entries, declared inside `subsection Output`.
    static void declare_parameters(dealii::ParameterHandler & /*prm*/) {}
    /// Read them; check names against the scene (InputError via scene.fail).
    virtual void parse_parameters(dealii::ParameterHandler & /*prm*/, Scene & /*scene*/,
                                  const SceneContents<dim> & /*contents*/)
    {}
    /// Whether it writes anything for this scene.
    virtual bool applies(const SceneContents<dim> & /*contents*/) const { return true; }

    /// The mesh is built (by a run, and by --check): refuse, collectively and
    /// with one line (InputError via state.scene.fail), what does not fit it.
    virtual void check(const SimulationState<dim> & /*state*/) {}
    virtual void start(const SimulationState<dim> & /*state*/, bool /*append*/) {}
    virtual void initial(const SimulationState<dim> &state) { accepted(state, nullptr); }
    virtual void attempt(const SimulationState<dim> & /*state*/, const StepReport<dim> & /*r*/) {}
    /// An accepted step (@p report is null at t = 0).
    virtual void accepted(const SimulationState<dim> & /*state*/,
                          const StepReport<dim> * /*report*/)
    {}
    /// The run ends (@p failed: on an unrecoverable step, with the last converged state).
    virtual void finish(const SimulationState<dim> & /*state*/, bool /*failed*/) {}
    virtual void add_to_summary(const SimulationState<dim> & /*state*/, Summary & /*s*/) const {}
    /// Named results evaluated by finish() (quantities of interest), printed
    /// at the end of a run and returned by Simulator::quantities_of_interest().
    virtual std::vector<std::pair<std::string, double>> results() const { return {}; }
    /// The unit of each of results() by name ("K", "N mm"; "-" dimensionless).
    virtual std::vector<std::pair<std::string, std::string>> units() const { return {}; }
    /// What a result of results() is taken over, printed beside it, by name
    /// ("max over quadrature points"); results without a note are not listed.
    virtual std::vector<std::pair<std::string, std::string>> notes() const { return {}; }

    /// State to carry through a checkpoint (e.g. the records of a .pvd file),
    /// as named entries "key value..." (rank 0 writes; every rank reads).
    virtual void save(std::map<std::string, std::string> & /*entries*/) const {}
    virtual void load(const std::map<std::string, std::string> & /*entries*/) {}
  };

  template <int dim>
  using PostprocessorRegistry = Registry<Postprocessor<dim>>;

  /// Declares every registered output's entries inside `subsection Output`.
  template <int dim>
  void declare_postprocessor_parameters(dealii::ParameterHandler &prm);
} // namespace anvil

#define ANVIL_REGISTER_POSTPROCESSOR_DIM_(Class, name, documentation, dim)                        \
  template class Class<dim>;                                                                      \
  static const bool ANVIL_REGISTRY_UNIQUE(anvil_postprocessor_##dim##_) =                         \
    ::anvil::PostprocessorRegistry<dim>::instance().add(                                          \
      name, documentation,                                                                        \
      []() -> std::unique_ptr<::anvil::Postprocessor<dim>> {                                     \
        return std::make_unique<Class<dim>>();                                                    \
      },                                                                                          \
      &Class<dim>::declare_parameters);
/**
 * Registers postprocessor class template @p Class under @p name for dim 2
 * and 3 and instantiates it; its static declare_parameters() is called inside
 * `subsection Output`.
 */
#define ANVIL_REGISTER_POSTPROCESSOR(Class, name, documentation)                                  \
  ANVIL_REGISTER_POSTPROCESSOR_DIM_(Class, name, documentation, 2)                                \
  ANVIL_REGISTER_POSTPROCESSOR_DIM_(Class, name, documentation, 3)
