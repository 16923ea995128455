#include <anvil/core/expression.h>
#include <anvil/core/scene.h>
#include <anvil/material/softening/interface.h>

#include <sstream>

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
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        omega                = prm.get_double("Softening coefficient");
        const std::string at = path + "/Softening coefficient";
        std::ostringstream m;
        m << scene.where(at) << ": '" << at << "' = " << omega << " /K with Reference temperature "
          << T_ref << " K makes the yield stress vanish at T = T_ref + 1/omega = "
          << T_ref + 1 / omega << " K, and the run reached T = ";
        vanishing = m.str();
      }
      double factor(const double T) const override
      {
        const double theta = 1 - omega * (T - T_ref);
        // Past T_ref + 1/ω the linear law (eq. 35) has no meaning: the scene's
        // error, named once, not a cascade of failed steps (issue 17).
        if (!(theta > 0))
          record_input_error(vanishing + std::to_string(T) +
                             " K: expected a softening that keeps the yield stress positive over "
                             "the run's temperatures (a smaller coefficient, or a table that "
                             "levels off)");
        return theta;
      }
      double derivative(double) const override { return -omega; }

    private:
      double      omega = 0;
      std::string vanishing;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::LinearSoftening, "linear",
                                 "theta = 1 - omega (T - T_ref) (seed eq. 35; Softening "
                                 "coefficient omega).")
