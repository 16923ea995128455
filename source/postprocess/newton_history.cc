#include <anvil/postprocess/interface.h>

namespace anvil
{
  /// newton.csv: every Newton iteration of every attempted step (failed
  /// ones too: they say why a step was cut back).
  template <int dim>
  class NewtonHistory : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return c.mechanics; }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      csv.open(s.output_directory + "/newton.csv",
               {"step", "time [s]", "iteration", "residual [N]", "increment [mm]", "line_search [-]",
                "converged"},
               s.is_root(), append, s.time);
    }
    void initial(const SimulationState<dim> &) override {}

    void attempt(const SimulationState<dim> &s, const StepReport<dim> &r) override
    {
      for (const auto &m : r.mechanical_solves)
        for (unsigned int k = 0; k < m.residuals.size(); ++k)
          csv.add_row({double(s.step + 1), s.time, double(k), m.residuals[k],
                       k < m.increments.size() ? m.increments[k] : 0.,
                       k < m.line_search_steps.size() ? m.line_search_steps[k] : 1.,
                       m.converged ? 1. : 0.});
    }

  private:
    CsvHistory csv;
  };

  ANVIL_REGISTER_POSTPROCESSOR(NewtonHistory, "newton",
                               "newton.csv: residual, increment and line-search step of every "
                               "Newton iteration.")
} // namespace anvil
