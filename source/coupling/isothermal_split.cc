#include <anvil/coupling/split.h>

namespace anvil
{
  template <int dim>
  class IsothermalSplit : public Split<dim, false>
  {};

  ANVIL_REGISTER_COUPLING_SCHEME(
    IsothermalSplit, "isothermal split",
    "mechanics at the temperature of the last thermal phase, then heat at the new geometry "
    "with the step's mechanical heat sources (seed sec. 2.2.1); first order, conditionally "
    "stable for the c_v form (doc/thermal.md).")
} // namespace anvil
