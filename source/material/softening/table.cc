#include <anvil/material/softening/interface.h>
#include <anvil/material/table.h>

#include <vector>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// θ from (T, θ) pairs, linear in between, constant outside.
    class TableSoftening : public ThermalSoftening
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Table", "", Patterns::Anything(),
                          "Table model: 'T1 : theta1, T2 : theta2, ...' (K, dimensionless).");
      }
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        parse_table(prm.get("Table"), scene, path + "/Table", T_table, f_table);
      }
      double factor(const double T) const override
      {
        return interpolate(T_table, f_table, T, false).first;
      }
      double derivative(const double T) const override
      {
        return interpolate(T_table, f_table, T, false).second;
      }

    private:
      std::vector<double> T_table, f_table;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::TableSoftening, "table",
                                 "theta from 'T : theta' pairs (Table), linear in between, "
                                 "constant outside.")
