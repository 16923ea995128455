#include <anvil/material/number_format.h>
#include <anvil/material/softening/interface.h>
#include <anvil/material/table.h>

#include <algorithm>
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

      // θ is linear between the nodes and constant outside: the first
      // crossing of 0 above T_ref is on the first segment that reaches it.
      double vanishing_temperature() const override
      {
        if (!(factor(T_ref) > 0))
          return T_ref;
        for (unsigned int i = 1; i < T_table.size(); ++i)
          if (T_table[i] > T_ref && !(f_table[i] > 0))
            {
              const double T0 = std::max(T_table[i - 1], T_ref), f0 = factor(T0);
              return T0 + (T_table[i] - T0) * f0 / (f0 - f_table[i]);
            }
        return ThermalSoftening::vanishing_temperature();
      }
      std::string vanishing_formula() const override
      {
        return "where theta = 0 in the table (T_ref = " + short_number(T_ref) + " K)";
      }
      std::string vanishing_entry() const override { return "Table"; }

    private:
      std::vector<double> T_table, f_table;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::TableSoftening, "table",
                                 "theta from 'T : theta' pairs (Table), linear in between, "
                                 "constant outside.")
