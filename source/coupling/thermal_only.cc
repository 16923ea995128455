#include <anvil/coupling/interface.h>

namespace anvil
{
  /**
   * The heat equation alone, on the undeformed bodies (seed eq. 26): no
   * mechanics is built, and mechanical loads in the scene are refused.
   */
  template <int dim>
  class ThermalOnly : public CouplingScheme<dim>
  {
  public:
    bool needs_mechanics() const override { return false; }
    bool needs_heat_equation() const override { return true; }

    StepReport<dim> advance(const double t_old, const double t_new) override
    {
      StepReport<dim> r;
      if (!this->problem->solve_heat(t_old, t_new, r))
        {
          this->problem->revert();
          return r.fail("heat: " + r.thermal.failure);
        }
      return r;
    }
  };

  ANVIL_REGISTER_COUPLING_SCHEME(ThermalOnly, "thermal only",
                                 "the heat equation on the undeformed bodies, no mechanics.")
} // namespace anvil
