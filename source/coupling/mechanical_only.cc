#include <anvil/coupling/interface.h>

namespace anvil
{
  /**
   * The mechanics alone, at the uniform Mechanics/Temperature: no
   * temperature field and no heat integrator are built.
   */
  template <int dim>
  class MechanicalOnly : public CouplingScheme<dim>
  {
  public:
    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return false; }

    StepReport<dim> advance(const double t_old, const double t_new) override
    {
      StepReport<dim> r;
      if (!this->problem->solve_mechanics(t_old, t_new, false, r))
        {
          this->problem->revert();
          return r.fail(r.mechanics().failure);
        }
      return r;
    }
  };

  ANVIL_REGISTER_COUPLING_SCHEME(
    MechanicalOnly, "mechanical only",
    "no temperature field and no heat integrator (Mechanics/Temperature is the uniform "
    "temperature).")
} // namespace anvil
