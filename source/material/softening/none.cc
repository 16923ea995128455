#include <anvil/material/softening/interface.h>

namespace anvil
{
  namespace
  {
    /// θ = 1: the yield stress does not depend on temperature.
    class NoSoftening : public ThermalSoftening
    {
    public:
      double factor(double) const override { return 1; }
      double derivative(double) const override { return 0; }
      bool   linear_form(bool &constant, double &) const override
      {
        constant = true;
        return true;
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_THERMAL_SOFTENING(anvil::NoSoftening, "none", "theta = 1.")
