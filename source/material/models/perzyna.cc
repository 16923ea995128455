#include <anvil/material/j2_plasticity.h>

namespace anvil
{
  namespace
  {
    /// J2 viscoplasticity returning to the generalized criterion f̄ = 0 (seed eq. 14, 17, 18).
    class Perzyna : public J2Model
    {
    public:
      Perzyna() { viscous = true; }
      static void declare_parameters(dealii::ParameterHandler &prm)
      {
        declare_elasticity_parameters(prm);
        declare_hardening_parameters(prm);
        PerzynaLaw::declare_parameters(prm);
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_MATERIAL_MODEL(anvil::Perzyna, "Perzyna",
                              "J2 viscoplasticity returning to the generalized criterion of "
                              "eq. 18: Elasticity, Hardening, Viscosity")
