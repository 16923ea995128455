#include <anvil/material/number_format.h>
#include <anvil/material/softening/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// θ = 1 − ω (T − T_ref), seed eq. (35).
    class LinearSoftening : public ThermalSoftening
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Softening coefficient", "0", Patterns::Double(),
                          "omega of the linear model, 1/K (e.g. 2e-3).");
      }
      void parse_parameters(ParameterHandler &prm, const Scene &, const std::string &) override
      {
        omega = prm.get_double("Softening coefficient");
      }
      double factor(const double T) const override { return 1 - omega * (T - T_ref); }
      double derivative(double) const override { return -omega; }
      bool   linear_form(bool &constant, double &omega_out) const override
      {
        constant  = false;
        omega_out = omega;
        return true;
      }
      double vanishing_temperature() const override
      {
        return omega > 0 ? T_ref + 1 / omega : ThermalSoftening::vanishing_temperature();
      }
      std::string vanishing_formula() const override
      {
        return "T_ref + 1/omega = " + short_number(T_ref) + " + 1/" + short_number(omega);
      }
      std::string vanishing_entry() const override { return "Softening coefficient"; }

    private:
      double omega = 0;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::LinearSoftening, "linear",
                                 "theta = 1 - omega (T - T_ref) (seed eq. 35; Softening "
                                 "coefficient omega).")
