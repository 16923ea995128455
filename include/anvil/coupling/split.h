#pragma once

#include <anvil/coupling/interface.h>

namespace anvil
{
  /**
   * The staggered splits of seed §2.2: the mechanics over the step at the
   * temperature the points last saw, then the heat equation on the new
   * geometry with the step's mechanical heat. @p adiabatic is the only
   * difference between the isothermal split (§2.2.1) and the adiabatic one
   * (Armero & Simo 1992, §2.2.2), where each material point carries its own
   * adiabatic heating ρc ΔT = Δt (χ Ẇirr + Ẇthel) within the mechanical phase
   * (material/j2_plasticity.cc: the update and its consistent tangent).
   */
  template <int dim, bool adiabatic>
  class Split : public CouplingScheme<dim>
  {
  public:
    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return true; }

    void initialize(CoupledProblem<dim> &p) override
    {
      CouplingScheme<dim>::initialize(p);
      p.connect_fields(adiabatic);
    }

    StepReport<dim> advance(const double t_old, const double t_new) override
    {
      StepReport<dim> r;
      if (!this->problem->solve_mechanics(t_old, t_new, false, r))
        {
          this->problem->revert();
          return r.fail(r.mechanics().failure);
        }
      if (!this->problem->solve_heat(t_old, t_new, r))
        {
          this->problem->revert();
          return r.fail("heat: " + r.thermal.failure);
        }
      return r;
    }
  };
} // namespace anvil
