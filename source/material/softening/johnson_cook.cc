#include <anvil/core/scene.h>
#include <anvil/material/number_format.h>
#include <anvil/material/softening/interface.h>

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// θ = 1 − T*^m, T* = (T − T_ref)/(T_melt − T_ref) clamped to [0, 1] (Johnson & Cook 1983).
    class JohnsonCookSoftening : public ThermalSoftening
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Melting temperature", "1800", Patterns::Double(0),
                          "T_melt of the Johnson-Cook model, K.");
        prm.declare_entry("Exponent", "1", Patterns::Double(0), "m of the Johnson-Cook model.");
      }
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        T_melt   = prm.get_double("Melting temperature");
        exponent = prm.get_double("Exponent");
        if (!(T_melt > T_ref))
          scene.fail(path + "/Melting temperature", "must exceed the Reference temperature");
        if (!(exponent > 0))
          scene.fail(path + "/Exponent", "must be > 0");
      }
      double factor(const double T) const override
      {
        const double s = std::clamp((T - T_ref) / (T_melt - T_ref), 0., 1.);
        return 1 - std::pow(s, exponent);
      }
      double derivative(const double T) const override
      {
        const double s = (T - T_ref) / (T_melt - T_ref);
        if (s <= 0 || s >= 1)
          return 0;
        return -exponent * std::pow(s, exponent - 1) / (T_melt - T_ref);
      }

      double      vanishing_temperature() const override { return T_melt; }
      std::string vanishing_formula() const override { return "T_melt = " + short_number(T_melt); }
      std::string vanishing_entry() const override { return "Melting temperature"; }

    private:
      double T_melt = 1800, exponent = 1;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::JohnsonCookSoftening, "johnson-cook",
                                 "theta = 1 - ((T - T_ref)/(T_melt - T_ref))^m, "
                                 "clamped to [0, 1] (Melting temperature, Exponent).")
