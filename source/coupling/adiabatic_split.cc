#include <anvil/coupling/split.h>

namespace anvil
{
  template <int dim>
  class AdiabaticSplit : public Split<dim, true>
  {};

  ANVIL_REGISTER_COUPLING_SCHEME(
    AdiabaticSplit, "adiabatic split",
    "(Armero & Simo 1992, seed sec. 2.2.2) as the isothermal split, but each point carries its "
    "own adiabatic temperature change in the mechanical phase, rho c dT = dt (chi W_irr + "
    "W_thel), with the consistent tangent; unconditionally stable.")
} // namespace anvil
