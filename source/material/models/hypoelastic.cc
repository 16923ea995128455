#include <anvil/material/j2_plasticity.h>

namespace anvil
{
  namespace
  {
    /// Thermo-hypoelasticity (seed eq. 9, 10, 19): the J2 point without a yield surface.
    class Hypoelastic : public J2Model
    {
    public:
      Hypoelastic() { plastic = false; }
      static void declare_parameters(dealii::ParameterHandler &prm)
      {
        declare_elasticity_parameters(prm);
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_MATERIAL_MODEL(anvil::Hypoelastic, "hypoelastic",
                              "thermo-elastic, Jaumann rate, subsection Elasticity")
