#include <anvil/material/j2_plasticity.h>
#include <anvil/material/hardening/interface.h>
#include <anvil/material/number_format.h>

namespace anvil
{
  // Issue 17: a softening that drives the yield stress to zero within the
  // run's temperatures is the scene's error. The return map cannot say so (it
  // also sees trial iterates, whose temperatures a converged state may never
  // reach); this is asked at converged states and at the scene's initial
  // temperatures only.
  StrengthLoss J2Model::strength_lost(const double T, const double eps) const
  {
    if (!plastic || !hardening)
      return {};
    // Asked at every point of every step: the limit (with its formatted
    // formula) is the law's constant, built once.
    std::call_once(strength_limit_once,
                   [this]() { strength_limit_cache = hardening->strength_limit(); });
    const auto &limit = strength_limit_cache;
    if (T >= limit.temperature)
      return {limit.location, "makes the yield stress vanish at T >= " +
                                short_number(limit.temperature) + " K (" + limit.formula + ")"};
    try
      {
        // A law may also lose its strength without a limit it can name
        // (an expression in T, a negative softening coefficient).
        const double stress = hardening->evaluate(eps, T).stress;
        if (!(stress > 0))
          return {hardening->location, "gives the yield stress " + short_number(stress) +
                                         " MPa <= 0 at T = " + short_number(T) +
                                         " K and plastic strain " + short_number(eps)};
      }
    catch (const MaterialPointError &e)
      {
        // A temperature the law refuses (Out of range = refuse): every later
        // update of this point would fail the same way.
        return {hardening->location, e.what()};
      }
    return {};
  }

  bool J2Model::may_lose_strength() const
  {
    // No vanishing temperature, no T to refuse, σᵥ ≥ σ₀ > 0 for the linear
    // law with θ = 1; any other law is asked point by point.
    if (!plastic || !hardening)
      return false;
    HardeningLaw::LinearForm form;
    if (!hardening->linear_form(form))
      return true;
    return form.theta_linear || !(form.sigma0 > 0) || !(form.h >= 0);
  }
} // namespace anvil
