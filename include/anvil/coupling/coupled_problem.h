#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/point_data.h>
#include <anvil/geometry/geometry.h>
#include <anvil/mechanics/boundary_conditions.h>
#include <anvil/mechanics/mechanical_problem.h>
#include <anvil/thermal/thermal_problem.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * What one coupled step did: every mechanical solve (the iterated staggered
   * scheme solves the mechanics several times per step), the heat solves
   * summed, the staggered iteration, the wall time of each half.
   */
  template <int dim>
  struct StepReport
  {
    bool                                                     converged = true;
    std::string                                              failure;
    std::vector<typename MechanicalProblem<dim>::StepResult> mechanical_solves; // in order
    typename ThermalProblem<dim>::Statistics                 thermal; // summed over the heat solves
    unsigned int staggered_iterations = 0;
    double       staggered_change = 0, contraction = 0; // K, ratio of successive changes
    double       mechanical_wall = 0, thermal_wall = 0; // s
    double       time_step = 0;                         // s, of the attempt
    // Monolithic Newton: |R_T| (mJ) and max |δT| (K) per iteration, beside the
    // mechanics' residuals in mechanical_solves.
    std::vector<double> thermal_residuals, thermal_increments;

    unsigned int mechanics_iterations() const
    {
      unsigned int n = 0;
      for (const auto &m : mechanical_solves)
        n += m.iterations;
      return n;
    }
    unsigned int linear_iterations() const
    {
      unsigned int n = 0;
      for (const auto &m : mechanical_solves)
        n += m.linear_iterations;
      return n;
    }

    /// The last mechanical solve (empty result if the scheme has no mechanics).
    const typename MechanicalProblem<dim>::StepResult &mechanics() const
    {
      static const typename MechanicalProblem<dim>::StepResult none;
      return mechanical_solves.empty() ? none : mechanical_solves.back();
    }
    StepReport &fail(const std::string &why)
    {
      converged = false;
      failure   = why;
      return *this;
    }
  };

  /**
   * The physics a scene switched on — the mechanics, the heat equation,
   * contact — and the operations every coupling scheme composes: solve one
   * half, revert both, commit both with the step's heat audit, and carry
   * temperatures to the mechanics' quadrature points. A scheme (coupling/
   * interface.h) decides the order; this class builds only what the scheme
   * needs, so a mechanical-only scene has no temperature field and a
   * thermal-only one no mechanics.
   */
  template <int dim>
  class CoupledProblem
  {
  public:
    /// Body materials, mechanics, heat and contact parameters of the scene.
    static void declare_parameters(dealii::ParameterHandler       &prm,
                                   const std::vector<std::string> &body_names,
                                   const std::vector<std::string> &contact_pair_names,
                                   const std::vector<std::string> &contact_tool_names);

    /// Reads what @p with_mechanics / @p with_heat need; throws InputError.
    void parse_parameters(dealii::ParameterHandler &prm, Scene &scene, const Geometry<dim> &geometry,
                          bool with_mechanics, bool with_heat, const std::string &scheme_name);

    /**
     * Before any work (--check and run), on the mesh: the temperatures the
     * scene sets — Heat/Initial temperature at every node, the prescribed
     * boundary temperatures at t = 0 and @p end_time, Mechanics/Temperature
     * if @p uniform_temperature — are finite absolute temperatures and ones
     * every body's yield stress survives (MaterialModel::strength_lost).
     * Throws one InputError on every process (temperature_check.cc).
     */
    void check_temperatures(const dealii::parallel::DistributedTriangulationBase<dim> &triangulation,
                            const Scene &scene, double end_time, bool uniform_temperature) const;

    /// Builds the problems on the mesh (after it exists); @p quiet silences log().
    /// With Heat/Initial temperature field = steady (or Method = steady) the
    /// temperature starts from the steady field at t = 0; if that Newton
    /// fails, initial_failure() says why (the run stops with results written).
    void setup(const dealii::parallel::DistributedTriangulationBase<dim> &triangulation,
               dealii::TimerOutput &timer, bool quiet);
    /// Notes for the user: rank 0, unless the scene is quiet.
    dealii::ConditionalOStream &log() { return *log_stream; }

    const std::string &initial_failure() const { return initial_steady_failure; }
    /// A heat equation integrated in time (not a sequence of steady states):
    /// its heat content balance (energy.csv) applies.
    bool transient_heat() const { return thermal && !thermal_parameters.steady; }
    /// One line per steady solve: iterations, |f| first and last, contraction orders.
    void log_steady(const std::string &what);
    /// Refuses (InputError) a steady solve the scene cannot have.
    void check_steady(const Scene &scene, const std::string &scheme_name) const;

    MechanicalProblem<dim>       *mechanics() { return mechanical.get(); }
    const MechanicalProblem<dim> *mechanics() const { return mechanical.get(); }
    ThermalProblem<dim>          *heat() { return thermal.get(); }
    const ThermalProblem<dim>    *heat() const { return thermal.get(); }
    ContactProblem<dim>          &contact_problem() { return contact; }
    const ContactProblem<dim>    &contact_problem() const { return contact; }
    const typename ThermalProblem<dim>::Parameters &heat_parameters() const
    {
      return thermal_parameters;
    }
    const typename MechanicalProblem<dim>::Parameters &mechanics_parameters() const
    {
      return mechanical_parameters;
    }

    /// The mechanics from tₙ to tₙ₊₁ (again: from its last solution), with the
    /// step limits (plastic increment, contact penetration) as failures.
    bool solve_mechanics(double t_old, double t_new, bool again, StepReport<dim> &report);
    /// The heat equation from tₙ to tₙ₊₁ on the current configuration.
    bool solve_heat(double t_old, double t_new, StepReport<dim> &report);
    /// Both halves back to tₙ (and the points' temperatures to Tₙ).
    void revert();
    /// Accept the step: its heat audit, then both halves commit.
    void commit(double time_step);

    /**
     * Temperatures the mechanics reads at its quadrature points. Coupled
     * schemes fill them from the heat field (from_heat_field()), the
     * prescribed-temperature scheme from its expression. Each material point
     * remembers what it saw last; @p adiabatic makes it add its own adiabatic
     * heating within the step (Armero–Simo split, seed §2.2.2).
     */
    void connect_point_temperatures(bool adiabatic);
    PointData<double> &point_temperatures() { return point_temperature; }
    /// Tₙ₊₁ of the heat field at the mechanics' quadrature points.
    void point_temperatures_from_heat_field();
    /// Where the mechanics' quadrature points are (reference mesh), for expressions.
    template <class Function>
    void for_each_point(const Function &f) const;

    /// Connects the mechanics' heat sources and the contact heat to the heat problem.
    void connect_heat_sources();
    /**
     * Both fields solved, one feeding the other: the mechanics reads the heat
     * field's temperature at its points (each point starting from T₀), the
     * heat problem the mechanics' and the contact's heat.
     */
    void connect_fields(bool adiabatic);
    /// After a checkpoint is loaded: the points' temperatures from the loaded field.
    void restarted();

    /// Heat made in the bodies, accumulated over accepted steps (mJ).
    struct HeatAudit
    {
      double plastic = 0, thermoelastic = 0, contact = 0; // contact: friction + tools
    };
    /// The heat balance since t = 0 (mJ), and its relative error.
    struct HeatBalance
    {
      double content = 0, change = 0, boundary = 0, source = 0, plastic = 0, thermoelastic = 0,
             contact = 0, error = 0;
    };
    HeatBalance heat_balance() const;
    HeatAudit       &heat_audit() { return audit; }
    const HeatAudit &heat_audit() const { return audit; }
    double          &initial_heat_content() { return heat_content_at_start; }
    double           initial_heat_content() const { return heat_content_at_start; }

    /// Cell means of the temperature the scene has (heat field, or prescribed
    /// at the points); empty if it has none.
    dealii::Vector<double> cell_temperature() const;
    bool                   has_temperature() const { return thermal || !point_temperature.empty(); }

  private:
    typename MechanicalProblem<dim>::Parameters                                mechanical_parameters;
    std::map<dealii::types::material_id, std::shared_ptr<const MaterialModel>> materials;
    BoundaryConditions<dim>                                                    boundary_conditions;
    typename ThermalProblem<dim>::Parameters                                   thermal_parameters;
    ThermalBoundaryConditions<dim>                        thermal_boundary_conditions;
    std::map<dealii::types::material_id, ThermalMaterial> thermal_materials;
    bool                                                  with_mechanics = true, with_heat = false;

    const dealii::parallel::DistributedTriangulationBase<dim> *triangulation = nullptr;
    std::unique_ptr<MechanicalProblem<dim>>                  mechanical;
    std::unique_ptr<ThermalProblem<dim>>                     thermal;
    ContactProblem<dim>                                      contact; // empty unless pairs
    PointData<double>                                        point_temperature;
    std::unique_ptr<dealii::ConditionalOStream>              log_stream;
    HeatAudit                                                audit;
    double                                                   heat_content_at_start = 0;
    std::string                                              initial_steady_failure;
    /// point_temperatures_from_heat_field()'s table: FE_Q's values at the
    /// points (j · n_q + q: they do not depend on the cell) and each owned
    /// cell's dofs by position in the ghosted temperature's local array (in
    /// cell order), made once per layout of that vector (`map`).
    struct PointInterpolation
    {
      std::vector<double>              shape;
      std::vector<int>                 local_dofs;
      std::unique_ptr<Epetra_BlockMap> map;
    } point_interpolation;
  };

  template <int dim>
  template <class Function>
  void CoupledProblem<dim>::for_each_point(const Function &f) const
  {
    const auto                &q = mechanical->get_quadrature();
    dealii::FEValues<dim>      fe_values(mechanical->get_mapping(), mechanical->get_dof_handler().get_fe(),
                                    q, dealii::update_quadrature_points);
    for (const auto &cell : mechanical->get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (unsigned int k = 0; k < q.size(); ++k)
            f(cell, k, fe_values.quadrature_point(k));
        }
  }
} // namespace anvil
