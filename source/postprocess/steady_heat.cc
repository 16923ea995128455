#include <anvil/postprocess/interface.h>

#include <sstream>

namespace anvil
{
  /**
   * steady_heat.csv and summary `steady_heat`: each steady heat solve
   * (Heat/Time integration/Method = steady: t = 0 and every step;
   * Heat/Initial temperature field = steady: t = 0) with its Newton
   * iterations and residuals, and its heat balance in mW — heat in through
   * each Flux/Convection/Radiation boundary, from sources, and through the
   * Temperature boundaries from k grad T . n — whose sum is zero in a steady
   * state: balance_error = |sum| / largest term, a check independent of the
   * Newton residual (it converges with the mesh, not with the iterations).
   */
  template <int dim>
  class SteadyHeat : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return c.steady_heat; }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::map<dealii::types::boundary_id, std::string> names;
      for (const auto &[name, id] : s.geometry.boundary_names())
        names[id] = name;
      std::vector<std::string> columns = {"step",          "time [s]",      "newton_iterations",
                                          "residual_first [mW]", "residual_last [mW]",
                                          "increment_last [K]"};
      boundaries.clear();
      for (const auto &[id, q] : s.physics.heat()->steady_balance(s.time).boundary)
        {
          boundaries.emplace_back(id, names.count(id) ? names[id] : std::to_string(id));
          columns.push_back(boundaries.back().second + "_heat_in [mW]");
        }
      columns.insert(columns.end(), {"source_heat_in [mW]", "temperature_boundaries_heat_in [mW]",
                                     "balance_error [-]"});
      csv.open(s.output_directory + "/steady_heat.csv", columns, s.is_root(), append, s.time);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *r) override
    {
      // After t = 0 the field is steady only if every step is a steady solve.
      if (r && !s.physics.heat_parameters().steady)
        return;
      const auto *heat = s.physics.heat();
      const auto &n    = heat->steady_report();
      balance          = heat->steady_balance(s.time);
      report           = n;
      ++solves;
      iterations += n.increments.size();
      std::vector<double> row = {double(s.step), s.time, double(n.increments.size()),
                                 n.residuals.front(), n.residuals.back(),
                                 n.increments.empty() ? 0. : n.increments.back()};
      for (const auto &[id, name] : boundaries)
        row.push_back(balance.boundary.count(id) ? balance.boundary.at(id) : 0.);
      row.insert(row.end(), {balance.source, balance.dirichlet, balance.error});
      csv.add_row(row);
    }

    void add_to_summary(const SimulationState<dim> &, Summary &summary) const override
    {
      if (solves == 0)
        return;
      std::ostringstream residuals, increments;
      residuals.precision(6);
      increments.precision(6);
      for (const double x : report.residuals)
        residuals << (residuals.tellp() > 0 ? " " : "") << x;
      for (const double x : report.increments)
        increments << (increments.tellp() > 0 ? " " : "") << x;
      summary.set("steady_heat", "solves", double(solves));
      summary.set("steady_heat", "newton_iterations", double(iterations));
      summary.set("steady_heat", "last_time", report.time);
      summary.set("steady_heat", "last_newton_iterations", double(report.increments.size()));
      summary.set("steady_heat", "last_residuals", residuals.str());
      summary.set("steady_heat", "last_increments", increments.str());
      for (const auto &[id, name] : boundaries)
        summary.set("steady_heat", name + "_heat_in",
                    balance.boundary.count(id) ? balance.boundary.at(id) : 0.);
      summary.set("steady_heat", "source_heat_in", balance.source);
      summary.set("steady_heat", "temperature_boundaries_heat_in", balance.dirichlet);
      summary.set("steady_heat", "balance_error", balance.error);
      summary.set("units", "steady_heat", "mW (residuals mW, increments K, balance_error -)");
    }

  private:
    CsvHistory                                                   csv;
    std::vector<std::pair<dealii::types::boundary_id, std::string>> boundaries;
    typename ThermalProblem<dim>::SteadyBalance                  balance;
    typename ThermalProblem<dim>::SteadyReport                   report;
    unsigned int                                                 solves = 0;
    unsigned long                                                iterations = 0;
  };

  ANVIL_REGISTER_POSTPROCESSOR(SteadyHeat, "steady heat",
                               "steady_heat.csv: Newton iterations, first and last residual and "
                               "the heat balance (mW) of every steady heat solve.")
} // namespace anvil
