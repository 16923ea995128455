#pragma once

// The heat half-step as the linear problem it is (issue 15): anvil's own DIRK
// loop for M ẏ = f(t, y) = −A y + g(t), one linear solve per implicit stage.

#include "arkode_integrator.h"

#include <vector>

namespace anvil
{
  namespace thermal
  {
    /// A diagonally implicit Runge–Kutta table: A lower triangular, weights b,
    /// nodes c, embedded weights d of order p (empty without an embedding).
    struct ButcherTable
    {
      unsigned int                     q = 0, p = 0;
      std::vector<std::vector<double>> A;
      std::vector<double>              b, c, d;
      unsigned int                     stages() const { return b.size(); }
    };

    /// ARKode's default DIRK table of this order (what ARKStep takes for it),
    /// 1: backward Euler without an embedding. Defined in arkode_integrator.cc,
    /// the one file that includes SUNDIALS.
    ButcherTable dirk_table(unsigned int order);

    /**
     * Integrate M ẏ = f(t, y), f linear in y with a t-independent Jacobian J
     * (settings.linear and jacobian_constant), from (t0, y) to t1 with
     * @p table, which system.can_solve_exactly() must allow. Stage i at
     * tᵢ = t + cᵢh, γ = h aᵢᵢ: since f(tᵢ, y + δ) = f(tᵢ, y) + Jδ exactly,
     * the stage equation M(zᵢ − y) = h Σ_{j<i} aᵢⱼ fⱼ + γ f(tᵢ, zᵢ) is the one
     * solve (M − γJ) δ = h Σ_{j<i} aᵢⱼ fⱼ + γ f(tᵢ, y), zᵢ = y + δ, then
     * fᵢ = f(tᵢ, zᵢ) (evaluated, not deduced: the heat balance closes to
     * round-off). Stiffly accurate tables take y(t + h) = z_s and f(t + h,
     * z_s) as the next step's explicit first stage; the error estimate is
     * M⁻¹ h Σ (bⱼ − dⱼ) fⱼ in ARKode's weighted RMS norm, the step control
     * ARKode's (PID, safety 0.96, error bias 1.5; see the .cc), each call
     * from the last one's proposal cut into equal steps (first_step), so γ
     * and the factorisation of M − γJ stay for the call.
     */
    IntegratorStatistics integrate_linear_dirk(ImplicitSystem &system, Vector &y, double t0, double t1,
                                               const IntegratorSettings &settings, const ButcherTable &table);
  } // namespace thermal
} // namespace anvil
