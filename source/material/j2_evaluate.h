// The J2 point's evaluate() (seed §1.3, eq. 9–19): trial state at a
// temperature, yield test, the linear return in closed form (else
// return_map(), j2_return_map.cc) and the step's heat sources and ΔT_ad —
// all the adiabatic fixed point iterates on. Inline in update()
// (j2_plasticity.cc, its only includer): the trial state then stays in
// registers on its way to finish() (j2_finish.h), no call frames.
#pragma once

#include <anvil/material/j2_plasticity.h>

#include "j2_point.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace anvil
{
  namespace j2
  {
    template <bool simple>
    [[gnu::always_inline]] inline void J2Point::evaluate(const MaterialIncrement &inc, const double T, const double dT,
                                  const Rotated &rotated, const bool adiabatic, Trial &t) const
    {
      const ElasticLaw &el   = model.elastic;
      const J2Model::Kernel &k = model.kernel();
      // (simple: the constant laws' values, K₀ g, G₀ g, β₀ f, and (β₀ f) ΔT as
      // thermal_strain() forms it: the same bits.)
      const double      K    = simple ? k.K : el.bulk_modulus(T);
      const double      G    = simple ? k.G : el.shear_modulus(T);
      // Thermal strain over the step and its T-derivative (β(T), eq. 19).
      const double      eth  = simple ? k.beta * dT : el.thermal_strain(T, dT);
      t.T = T, t.dT = dT, t.K = K, t.G = G, t.eth = eth;
      t.deth = simple ? k.beta : el.thermal_strain_derivative(T, dT);
      t.beta = simple ? k.beta : el.thermal_expansion(T);
      if (!simple && !(G > 0 && K > 0))
        throw MaterialPointError(
          "the elastic moduli are not positive at T = " + std::to_string(T) +
          " K (modulus temperature factor g(T) = " +
          std::to_string(el.shear_modulus() > 0 ? G / el.shear_modulus() : K / el.bulk_modulus()) +
          ")");

      // Trial state: rotated σ_n plus H(T) : (Δε − βΔT I), eq. (9), (10), (19),
      // on the raw components (00, 11, 22, 01, 02, 12).
      double *trial = t.trial, *s = t.s, de[6];
      const double *dstrain = inc.strain_increment.begin_raw();
      #pragma GCC unroll 6
      for (unsigned int c = 0; c < 6; ++c)
        de[c] = dstrain[c] - (c < 3 ? eth : 0.);
      const double tr_de   = de[0] + de[1] + de[2];
      const double mean_de = tr_de / 3;
      t.tr_de              = tr_de;
      // σ̃ₙ + H : Δεᵉ in one pass (a copy first became a memmove call).
      #pragma GCC unroll 6
      for (unsigned int c = 0; c < 6; ++c)
        trial[c] = rotated.trial[c] + (c < 3 ? K * tr_de + 2 * G * (de[c] - mean_de) : 2 * G * de[c]);
      const double mean_trial = (trial[0] + trial[1] + trial[2]) / 3;
      #pragma GCC unroll 6
      for (unsigned int c = 0; c < 6; ++c) // dev(trial)
        s[c] = c < 3 ? trial[c] - mean_trial : trial[c];
      const double norm2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                           2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
      // |dev σ_tr| and q_tr = √(3/2)|dev σ_tr| only where the yield test can
      // pass: the square root is the longest latency of the elastic update.
      double norm_s = 0, q_trial = 0;

      double       dp = 0, H = 0;
      // Y, Y_start, V and rate are read only after a plastic return (dp > 0),
      // which sets them. Locals, copied into t at the end: no address of t's
      // is passed to a call (return_map(), the laws' returns by value), so t
      // stays in registers (its fields were stored and reloaded).
      HardeningLaw::Value Y, Y_start;
      PerzynaLaw::Value   V;
      PerzynaLaw::Rate    rate;
      bool                linear_return = false;
      unsigned int        iterations    = 0;
      if (simple || model.plastic)
        {
          Y = Y_start = yield<simple>(eps_n, T);
          if (!(Y.stress > 0))
            throw MaterialPointError("the yield stress is " + std::to_string(Y.stress) +
                                     " MPa <= 0 at T = " + std::to_string(T) +
                                     " K (thermal softening removed all strength)");
          // q_tr² against σᵥ² first, with a margin far above the rounding
          // of either side: the test on q_tr itself decides, as ever.
          if (1.5 * norm2 > (1 - 1e-10) * (Y.stress * Y.stress))
            {
              norm_s  = std::sqrt(norm2);
              q_trial = std::sqrt(1.5) * norm_s;
            }
          if (q_trial > Y.stress)
            {
              if (!simple && model.viscosity.active())
                {
                  PerzynaLaw::Rate r = model.viscosity.at(T, inc.time_step);
                  rate                     = r;
                }
              else
                rate.dt = inc.time_step;
              if (simple || k.closed_form ||
                  (k.linear && !rate.active() && !model.johnson_cook_rate.active()))
                {
                  // Linear hardening, rate-independent: r is linear in Δε̄.
                  const double h = Y_start.slope;
                  if (!simple && !(h >= 0))
                    {
                      const double hi = q_trial / (3 * G);
                      if (q_trial - 3 * G * hi - yield(eps_n + hi, T).stress > 0)
                        throw no_plastic_solution(T);
                    }
                  dp                  = (q_trial - Y_start.stress) / (3 * G + h);
                  V             = PerzynaLaw::Value();
                  iterations    = 1;
                  linear_return = true;
                  // (∂σᵥ/∂T at the end of the step: finish(), if asked.)
                  Y.stress = Y_start.stress + h * dp;
                }
              else
                {
                  const PerzynaLaw::Rate    r  = rate;
                  const HardeningLaw::Value Y0 = Y_start;
                  HardeningLaw::Value       Yr;
                  PerzynaLaw::Value         Vr;
                  unsigned int              its = 0;
                  dp = return_map(q_trial, G, T, r, Y0, its, Yr, Vr);
                  Y = Yr, V = Vr, iterations = its;
                }
              H = Y.slope + V.derivative;
            }
        }
      t.norm_s = norm_s, t.q_trial = q_trial, t.dp = dp, t.H = H;
      t.Y = Y, t.Y_start = Y_start, t.V = V, t.rate = rate;
      t.linear_return = linear_return, t.return_iterations = iterations;

      // Heat sources over the step (always cheap; needed by the adiabatic loop).
      double work = 0, dwork_dq = 0;
      if (dp > 0)
        {
          // Ẇirr = σ̄ ε̄̇ (eq. 21) with σ̄ averaged over the step (exact for linear
          // hardening); flow starts at the yield stress if the step began elastic.
          const double q_end   = q_trial - 3 * G * dp;
          const double q_start = std::max(q_n, Y_start.stress);
          work                 = 0.5 * (q_start + q_end) * dp;
          // d(work)/dq_trial with dΔε̄/dq_tr = 1/(3G + H), dq_end/dq_tr = H/(3G + H):
          // the adiabatic tangent's only (finish()).
          if (adiabatic)
            dwork_dq = 0.5 * (H * dp + q_start + q_end) / (3 * G + H);
        }
      t.work = work, t.dwork_dq = dwork_dq;
      // Reversible volume change that heats or cools (doc/thermodynamics.md):
      // with c at constant stress, the stress-producing part tr(Δε − βΔT I);
      // with c at constant volume (the seed's eq. 8 and 22), all of tr Δε.
      t.tr_rev = el.capacity_at_constant_volume ? tr_de + 3 * eth : tr_de;
      // Sources per current volume, capacity per reference volume (ρ₀c/J per
      // current volume). Only the adiabatic update reads ΔT_ad (two divisions
      // of the isothermal one's eleven).
      t.rho_c = t.adiabatic_temperature_increment = 0;
      if (adiabatic)
        {
          t.rho_c = el.density * el.heat_capacity / inc.volume_ratio;
          t.adiabatic_temperature_increment =
            (el.taylor_quinney * work - 3 * K * t.beta * T * t.tr_rev) / t.rho_c;
        }
    }
  } // namespace j2
} // namespace anvil
