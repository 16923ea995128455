#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/mechanics/boundary_conditions.h>
#include <anvil/mechanics/mechanical_problem.h>
#include <anvil/output/csv_history.h>
#include <anvil/thermal/thermal_problem.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * One simulation of a scene: builds the mesh and the physics the scene
   * switched on, runs the time loop with cut-back and re-growth of the step,
   * writes fields, histories and summary.json.
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
    /// writing the last converged state and summary.json; failure() says why.
    bool run();
    const std::string &failure() const { return failure_reason; }

    /// The output directory of this run.
    const std::string &output_directory() const { return output_dir; }

    /// Quantities of interest as evaluated at the end of the run (name, value).
    const std::vector<std::pair<std::string, double>> &quantities_of_interest() const
    {
      return qoi_values;
    }


  private:
    struct TimeParameters
    {
      double end_time, time_step, minimum_time_step, maximum_time_step, growth_factor;
      unsigned int easy_iterations;
    };
    struct Probe
    {
      std::string        name;
      dealii::Point<dim> point;
    };
    struct Quantity
    {
      std::string name, kind, target, field;
      dealii::types::boundary_id boundary = 0;
      int                        body     = -1;
      unsigned int               component = 0;
      double                     offset    = 0; // "f(...) + c"
    };

    /// What one coupled step did (both halves, all staggered iterations).
    struct CoupledStep
    {
      bool        converged = true;
      std::string failure;
      typename MechanicalProblem<dim>::StepResult mechanics; // the last mechanical solve
      typename ThermalProblem<dim>::Statistics    thermal;   // summed over the thermal solves
      unsigned int staggered_iterations = 0;
      double       staggered_change = 0, contraction = 0;    // K, ratio of successive changes
      double       mechanical_wall = 0, thermal_wall = 0;    // s
    };
    /// Advance every physics the scene has from @p t_old to @p t_new with the
    /// chosen coupling; on failure both are back at t_old.
    CoupledStep advance(double t_old, double t_new);
    /// Heat made in the bodies, accumulated over accepted steps (mJ).
    struct HeatAudit
    {
      double plastic = 0, thermoelastic = 0, contact = 0; // contact: friction heat + heat from tools
    };

    /// The heat balance since t = 0 (mJ): content, its change, heat in through
    /// boundaries, volume sources, plastic and thermoelastic heat, and the
    /// relative error of change = boundary + all sources.
    struct HeatBalance
    {
      double content = 0, change = 0, boundary = 0, source = 0, plastic = 0, thermoelastic = 0,
             contact = 0, error = 0;
    };
    HeatBalance heat_balance() const;

    void parse_output(dealii::ParameterHandler &prm, Scene &scene);
    void open_histories();
    void write_histories(double time, unsigned int step);
    void write_fields(double time, unsigned int step);
    void write_contact_fields(double time, unsigned int step);
    void evaluate_quantities();
    void write_summary(const std::string &status);
    void write_checkpoint(double time, double time_step);
    void read_checkpoint(double &time, double &time_step);

    Scene                                       &scene;
    MPI_Comm                                     mpi_communicator;
    dealii::ConditionalOStream                   pcout;
    std::unique_ptr<dealii::TimerOutput>         timer; // made by run(), not at parse
    dealii::parallel::distributed::Triangulation<dim> triangulation;
    Geometry<dim>                                geometry;
    BoundaryConditions<dim>                      boundary_conditions;
    typename MechanicalProblem<dim>::Parameters  mechanics_parameters;
    std::map<dealii::types::material_id, std::shared_ptr<const MaterialModel>> materials;
    std::unique_ptr<MechanicalProblem<dim>>      mechanical;
    ContactProblem<dim>                          contact; // empty unless Contact/Pairs names some
    // Heat (built only if Physics/Heat is on).
    bool                                         heat = false, mechanics = true;
    std::string                                  coupling;
    double                                       staggered_tolerance = 0;
    bool                                         staggered_tolerance_noted = false;
    unsigned int                                 max_staggered_iterations = 30;
    HeatAudit                                    heat_audit;
    unsigned long                                n_thermal_nonlinear = 0, n_staggered_iterations = 0;
    typename ThermalProblem<dim>::Parameters     thermal_parameters;
    ThermalBoundaryConditions<dim>               thermal_boundary_conditions;
    std::map<dealii::types::material_id, ThermalMaterial> thermal_materials;
    std::unique_ptr<ThermalProblem<dim>>         thermal;
    // T_n at the mechanics' quadrature points (active_cell_index * n_q + q).
    std::vector<double>                          point_temperature;
    void update_point_temperatures();
    double                                       initial_heat_content = 0;
    unsigned long                                n_thermal_steps = 0;
    /// Temperature T_n at the mechanics' quadrature points (each point
    /// remembers what it saw last, so it takes the thermal phase's change).
    void mechanics_temperatures(const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
                                std::vector<double> &T) const;
    TimeParameters                               time;

    std::string           output_dir;
    unsigned int          output_interval = 1, checkpoint_interval = 0;
    std::string           restart_directory;
    bool                  quiet           = false;
    std::vector<Probe>    probes;
    std::vector<Quantity> quantities;
    std::vector<std::pair<std::string, double>> qoi_values;
    std::vector<std::pair<double, std::string>> pvd_records, contact_records;
    CsvHistory reactions_csv, probes_csv, energy_csv, newton_csv, thermal_csv, contact_csv;
    std::vector<std::pair<std::string, dealii::types::boundary_id>> reaction_boundaries;

    unsigned int n_steps = 0, n_cut_backs = 0, n_newton = 0, n_linear = 0;
    double       current_time = 0;
    double       wall_start   = 0;
    std::string  failure_reason;
  };

  /// The program: parse the command line, read the scene, dispatch on dimension.
  int run_anvil(int argc, char **argv);
} // namespace anvil
