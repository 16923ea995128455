#include <anvil/material/j2_plasticity.h>

namespace anvil
{
  namespace
  {
    /// Rate-independent von Mises plasticity with isotropic hardening (seed §1.3, eq. 11).
    class J2 : public J2Model
    {
    public:
      static void declare_parameters(dealii::ParameterHandler &prm)
      {
        declare_elasticity_parameters(prm);
        declare_hardening_parameters(prm);
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_MATERIAL_MODEL(anvil::J2, "J2",
                              "rate-independent von Mises plasticity with isotropic hardening, "
                              "radial return: Elasticity, Hardening")
