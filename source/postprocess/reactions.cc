#include <anvil/postprocess/interface.h>

namespace anvil
{
  /// reactions.csv: the force each named boundary's support exerts on the
  /// body, per step — what a user plots first.
  template <int dim>
  class Reactions : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return c.mechanics; }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step", "time"};
      for (const auto &[name, id] : s.geometry.boundary_names())
        for (unsigned int d = 0; d < dim; ++d)
          columns.push_back(name + "_F" + "xyz"[d]);
      csv.open(s.output_directory + "/reactions.csv", columns, s.is_root(), append);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      std::vector<double> row = {double(s.step), s.time};
      for (const auto &[name, id] : s.geometry.boundary_names())
        {
          const auto f = s.physics.mechanics()->reaction(id);
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(f[d]);
        }
      csv.add_row(row);
    }

  private:
    CsvHistory csv;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Reactions, "reactions",
                               "reactions.csv: reaction force on every named boundary, N.")
} // namespace anvil
