#include <anvil/postprocess/interface.h>

namespace anvil
{
  /// thermal.csv: what the heat integration and the staggered iteration
  /// cost each step (ARKode counters, wall time of each half).
  template <int dim>
  class HeatStatistics : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return c.heat; }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      // A sequence of steady states has no ARKode counters (steady_heat.cc).
      active = s.physics.transient_heat();
      if (!active)
        return;
      csv.open(s.output_directory + "/thermal.csv",
               {"step", "time [s]", "time_step [s]", "arkode_steps", "arkode_attempts",
                "error_test_failures", "nonlinear_iterations", "nonlinear_failures",
                "linear_setups", "linear_solves", "linear_iterations", "mass_solves",
                "rhs_evaluations", "last_internal_step [s]", "staggered_iterations",
                "staggered_change [K]", "staggered_contraction [-]", "mechanics_wall_time [s]",
                "thermal_wall_time [s]"},
               s.is_root(), append, s.time);
    }
    void initial(const SimulationState<dim> &) override {}

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *r) override
    {
      if (!active)
        return;
      const auto &a = r->thermal;
      csv.add_row({double(s.step), s.time, r->time_step, double(a.internal_steps),
                   double(a.attempted_steps), double(a.error_test_failures),
                   double(a.nonlinear_iterations), double(a.nonlinear_failures),
                   double(a.linear_setups), double(a.linear_solves), double(a.linear_iterations),
                   double(a.mass_solves), double(a.rhs_evaluations), a.last_internal_step,
                   double(r->staggered_iterations), r->staggered_change, r->contraction,
                   r->mechanical_wall, r->thermal_wall});
    }

    void add_to_summary(const SimulationState<dim> &s, Summary &summary) const override
    {
      if (!active)
        return;
      const auto &n = s.statistics;
      summary.set("heat", "arkode_internal_steps", double(n.heat_internal_steps));
      summary.set("heat", "arkode_steps_per_step",
                  n.steps ? double(n.heat_internal_steps) / n.steps : 0.);
      summary.set("heat", "arkode_nonlinear_iterations", double(n.heat_nonlinear_iterations));
      summary.set("heat", "staggered_iterations", double(n.staggered_iterations));
    }

  private:
    CsvHistory csv;
    bool       active = true;
  };

  ANVIL_REGISTER_POSTPROCESSOR(HeatStatistics, "heat statistics",
                               "thermal.csv: ARKode steps, failures, nonlinear and linear "
                               "iterations, staggered iterations and wall time of each half, "
                               "per step.")
} // namespace anvil
