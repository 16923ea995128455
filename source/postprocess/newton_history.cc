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

    // The monolithic Newton solves both fields: their residuals side by side.
    void parse_parameters(dealii::ParameterHandler &prm, Scene &, const SceneContents<dim> &) override
    {
      both_fields = prm.get({"Physics"}, "Coupling") == "monolithic";
    }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step",           "time [s]",        "iteration",
                                          "residual [N]",   "increment [mm]",  "line_search [-]",
                                          "converged"};
      if (both_fields)
        columns.insert(columns.end(), {"heat_residual [mJ]", "heat_increment [K]"});
      csv.open(s.output_directory + "/newton.csv", columns, s.is_root(), append, s.time);
    }
    void initial(const SimulationState<dim> &) override {}

    void attempt(const SimulationState<dim> &s, const StepReport<dim> &r) override
    {
      for (const auto &m : r.mechanical_solves)
        for (unsigned int k = 0; k < m.residuals.size(); ++k)
          {
            std::vector<double> row = {double(s.step + 1), s.time, double(k), m.residuals[k],
                                       k < m.increments.size() ? m.increments[k] : 0.,
                                       k < m.line_search_steps.size() ? m.line_search_steps[k] : 1.,
                                       m.converged ? 1. : 0.};
            // The heat columns belong to the monolithic solve (the last one).
            if (both_fields && &m != &r.mechanical_solves.back())
              row.insert(row.end(), {0., 0.});
            else if (both_fields)
              {
                const auto &rT = r.thermal_residuals, &dT = r.thermal_increments;
                row.push_back(k < rT.size() ? rT[k] : 0.);
                row.push_back(k < dT.size() ? dT[k] : 0.);
              }
            csv.add_row(row);
          }
    }

  private:
    CsvHistory csv;
    bool       both_fields = false;
  };

  ANVIL_REGISTER_POSTPROCESSOR(NewtonHistory, "newton",
                               "newton.csv: residual, increment and line-search step of every "
                               "Newton iteration (and the heat residual, K increment of the "
                               "monolithic Newton).")
} // namespace anvil
