#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>
#include <anvil/material/table.h>

#include <vector>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// σᵥ from (ε̄, σ) pairs, linear in between, extended with the last slope;
    /// the thermal softening multiplies the whole yield stress.
    class TableHardening : public HardeningLaw
    {
    public:
      static void declare_parameters(ParameterHandler &prm) { declare_common_entry(prm, "Table"); }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        parse_table(prm.get("Table"), scene, path + "/Table", eps_table, sigma_table);
        if (eps_table.front() != 0 || !(sigma_table.front() > 0))
          scene.fail(path + "/Table", "must start at plastic strain 0 with a yield stress > 0");
        nondecreasing = true;
        for (unsigned int i = 1; i < sigma_table.size(); ++i)
          nondecreasing = nondecreasing && sigma_table[i] >= sigma_table[i - 1];
      }

      Value evaluate(const double eps, const double T) const override
      {
        const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
        const auto [s, slope] = interpolate(eps_table, sigma_table, eps, true);
        Value v;
        v.stress                 = theta * s;
        v.slope                  = theta * slope;
        v.temperature_derivative = dtheta * s;
        return v;
      }

      // θ multiplies the whole table, whatever `Softened parameters` says.
      StrengthLimit strength_limit() const override { return softening_limit(true); }

      bool is_nondecreasing(const double T) const override
      {
        return thermal->factor(T) >= 0 && nondecreasing;
      }

    private:
      std::vector<double> eps_table, sigma_table;
      bool                nondecreasing = true;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::TableHardening, "table",
                             "a table of 'eps : sigma' pairs (Table), linear in between, the last slope "
                             "beyond")
