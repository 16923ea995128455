// The J2 point's return map (seed §1.3, eq. 9–18): trial state at a
// temperature, yield test, radial return to f = 0 or f̄ = 0, and the step's
// heat sources and ΔT_ad — all the adiabatic fixed point iterates on.
#include <anvil/material/j2_plasticity.h>

#include "j2_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace anvil
{
  namespace j2
  {
    MaterialPointError no_plastic_solution(const double T)
    {
      return MaterialPointError("no plastic solution: the yield stress is not positive after "
                                "the increment (T = " + std::to_string(T) + " K)");
    }

    double J2Point::return_map(const double               q_tr,
                               const double               G,
                               const double               T,
                               const PerzynaLaw::Rate    &rate,
                               const HardeningLaw::Value &Y0,
                               unsigned int              &iterations,
                               HardeningLaw::Value       &Y,
                               PerzynaLaw::Value         &V) const
    {
      const PerzynaLaw      &viscosity = model.viscosity;
      const JohnsonCookRate &jc        = model.johnson_cook_rate;
      // r and rx = Δε̄ r'(Δε̄) = dr/d ln Δε̄ (finite where r' is not: V ∝ Δε̄^{1/m}),
      // with σᵥ and V at Δε̄ in y and v.
      auto residual = [&](const double dp, double &rx, HardeningLaw::Value &y, PerzynaLaw::Value &v) {
        y  = yield(eps_n + dp, T);
        v  = jc.active() ? jc.evaluate(y.stress, y.slope, dp, rate.dt) :
                           viscosity.evaluate(rate, eps_n + dp, dp);
        rx = -(3 * G + y.slope) * dp - v.log_derivative;
        return q_tr - 3 * G * dp - y.stress - v.stress;
      };
      auto elastic = [&]() {
        Y = Y0;
        V = PerzynaLaw::Value();
        return 0.;
      };
      // The root is bracketed by [0, q_tr/3G]: r(0) > 0 (plastic branch) and
      // r(q_tr/3G) = −σᵥ − V < 0 while the yield stress is positive, which
      // only needs checking if σᵥ may decrease.
      double     hi = q_tr / (3 * G), rx = 0;
      const bool nondecreasing = model.kernel().inline_yield ?
                                   model.kernel().yield.is_nondecreasing(T) :
                                   model.hardening->is_nondecreasing(T);
      iterations               = 0;
      if (!nondecreasing && residual(hi, rx, Y, V) > 0)
        throw no_plastic_solution(T);
      const double hi_safe = hi;
      // Below dp_min the plastic increment is zero to working precision.
      const double dp_min = std::max(1e-300 * hi, std::numeric_limits<double>::min());
      double dp = std::min(0.5 * hi, (q_tr - Y0.stress) / (3 * G + std::max(Y0.slope, 0.)));
      // With σᵥ nondecreasing, V(root) ≤ q_tr − σᵥ(ε̄ₙ), and V(Δε̄) ≥ η_min^{1/n}
      // (Δε̄/Δt)^{1/m} with η_min the smallest η(ε̄) on the bracket (at ε̄ₙ for
      // a ≥ 0, at ε̄ₙ + q_tr/3G for a < 0): the rate law bounds the root, by
      // many orders of magnitude for η ≫ 1, m ≫ 1. The root is then close to
      // the bound (the overstress takes almost all of q_tr − σᵥ): start there.
      if (rate.active() && nondecreasing)
        {
          const double eps_min = viscosity.strain_exponent_value() >= 0 ? eps_n : eps_n + hi;
          const double bound   = viscosity.rate_bound(rate, eps_min, q_tr - Y0.stress);
          if (!(bound > dp_min))
            return elastic();
          if (bound < dp)
            dp = hi = bound;
        }
      double       lo        = 0;
      const double tolerance = 1e-13 * q_tr;
      for (iterations = 1; iterations <= 200; ++iterations)
        {
          const double r = residual(dp, rx, Y, V);
          if (std::abs(r) <= tolerance)
            return dp;
          (r > 0 ? lo : hi) = dp;
          if (!(lo < hi)) // r > 0 at the rate bound (by rounding): the root is just above
            hi = hi_safe;
          // Newton; right of the root (r < 0), also Newton in x = ln Δε̄ on
          // g(x) = ln(A/V) = 0, A = q_tr − 3GΔε̄ − σᵥ = r + V, which is exact where the
          // overstress is a power of Δε̄ and A constant (η ≫ 1: V ≫ 3GΔε̄) and does
          // not overshoot (g is concave for linear hardening), where plain Newton
          // only creeps (m < 1: Δε̄ ← (1 − m) Δε̄); the longer step inside the
          // bracket wins. Where Newton leaves the bracket, Newton in x (on g, or
          // on r if A ≤ 0); then bisection in x.
          const double A      = r + V.stress;
          // (Not for Johnson-Cook: its V is logarithmic, not a power of Δε̄.)
          const bool   loglog = A > 0 && V.stress > 0 && !jc.active();
          auto         newton_x = [&]() {
            return loglog ? dp * std::exp(-std::log(A / V.stress) /
                                          ((rx + V.log_derivative) / A - V.log_derivative / V.stress)) :
                            dp * std::exp(-r / rx);
          };
          double next = dp - dp * r / rx;
          if (r < 0 && loglog)
            if (const double x_step = newton_x(); x_step > lo && !(next > lo && next < x_step))
              next = x_step;
          bool bisect = false;
          if (!(next > lo && next < hi))
            {
              next   = newton_x();
              bisect = !(next > lo && next < hi);
            }
          if (bisect || next < dp_min)
            {
              // While lo = 0, bisect from dp_min, once it is known that r(dp_min) > 0:
              // else the root is below working precision.
              if (lo < dp_min)
                {
                  ++iterations;
                  HardeningLaw::Value y;
                  PerzynaLaw::Value   v;
                  double              rx_min;
                  if (residual(dp_min, rx_min, y, v) <= 0)
                    return elastic();
                  lo = dp_min;
                }
              next = std::sqrt(lo) * std::sqrt(hi); // no underflow
            }
          if (std::abs(next - dp) <= 1e-16 * dp || hi - lo <= 1e-16 * hi)
            return dp;
          dp = next;
        }
      throw MaterialPointError("the return map did not converge in 200 iterations");
    }

    void J2Point::evaluate(const MaterialIncrement &inc, const double T, const double dT,
                           const Rotated &rotated, Trial &t) const
    {
      const ElasticLaw &el   = model.elastic;
      const double      K    = el.bulk_modulus(T);
      const double      G    = el.shear_modulus(T);
      // Thermal strain over the step and its T-derivative (β(T), eq. 19).
      const double      eth  = el.thermal_strain(T, dT);
      t.T = T, t.dT = dT, t.K = K, t.G = G, t.eth = eth;
      t.deth = el.thermal_strain_derivative(T, dT);
      t.beta = el.thermal_expansion(T);
      if (!(G > 0 && K > 0))
        throw MaterialPointError(
          "the elastic moduli are not positive at T = " + std::to_string(T) +
          " K (modulus temperature factor g(T) = " +
          std::to_string(el.shear_modulus() > 0 ? G / el.shear_modulus() : K / el.bulk_modulus()) +
          ")");

      // Trial state: rotated σ_n plus H(T) : (Δε − βΔT I), eq. (9), (10), (19),
      // on the raw components (00, 11, 22, 01, 02, 12).
      double *trial = t.trial, *de = t.de, *s = t.s;
      const double *dstrain = inc.strain_increment.begin_raw();
      for (unsigned int c = 0; c < 6; ++c)
        de[c] = dstrain[c] - (c < 3 ? eth : 0.);
      const double tr_de   = de[0] + de[1] + de[2];
      const double mean_de = tr_de / 3;
      t.tr_de              = tr_de;
      // σ̃ₙ + H : Δεᵉ in one pass (a copy first became a memmove call).
      for (unsigned int c = 0; c < 6; ++c)
        trial[c] = rotated.trial[c] + (c < 3 ? K * tr_de + 2 * G * (de[c] - mean_de) : 2 * G * de[c]);
      const double mean_trial = (trial[0] + trial[1] + trial[2]) / 3;
      for (unsigned int c = 0; c < 6; ++c) // dev(trial)
        s[c] = c < 3 ? trial[c] - mean_trial : trial[c];
      const double norm2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                           2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
      // |dev σ_tr| and q_tr = √(3/2)|dev σ_tr| only where the yield test can
      // pass: the square root is the longest latency of the elastic update.
      double norm_s = 0, q_trial = 0;

      double               dp = 0, H = 0;
      HardeningLaw::Value &Y = t.Y, &Y_start = t.Y_start;
      PerzynaLaw::Value   &V = t.V;
      PerzynaLaw::Rate    &rate = t.rate;
      // Y, Y_start, V and rate are read only after a plastic return (dp > 0),
      // which sets them.
      t.linear_return     = false;
      t.return_iterations = 0;
      if (model.plastic)
        {
          Y = Y_start = yield(eps_n, T);
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
              if (model.viscosity.active())
                rate = model.viscosity.at(T, inc.time_step);
              else
                rate.dt = inc.time_step;
              if (model.kernel().linear && !rate.active() && !model.johnson_cook_rate.active())
                {
                  // Linear hardening, rate-independent: r is linear in Δε̄.
                  const double h = Y_start.slope;
                  if (!(h >= 0))
                    {
                      const double hi = q_trial / (3 * G);
                      if (q_trial - 3 * G * hi - yield(eps_n + hi, T).stress > 0)
                        throw no_plastic_solution(T);
                    }
                  dp                  = (q_trial - Y_start.stress) / (3 * G + h);
                  V                   = PerzynaLaw::Value();
                  t.return_iterations = 1;
                  t.linear_return     = true;
                  // (∂σᵥ/∂T at the end of the step: finish(), if asked.)
                  Y.stress = Y_start.stress + h * dp;
                }
              else
                dp = return_map(q_trial, G, T, rate, Y_start, t.return_iterations, Y, V);
              H = Y.slope + V.derivative;
            }
        }
      t.norm_s = norm_s, t.q_trial = q_trial, t.dp = dp, t.H = H;

      // Heat sources over the step (always cheap; needed by the adiabatic loop).
      double work = 0, dwork_dq = 0;
      if (dp > 0)
        {
          // Ẇirr = σ̄ ε̄̇ (eq. 21) with σ̄ averaged over the step (exact for linear
          // hardening); flow starts at the yield stress if the step began elastic.
          const double q_end   = q_trial - 3 * G * dp;
          const double q_start = std::max(q_n, Y_start.stress);
          work                 = 0.5 * (q_start + q_end) * dp;
          // d(work)/dq_trial with dΔε̄/dq_tr = 1/(3G + H), dq_end/dq_tr = H/(3G + H).
          dwork_dq = 0.5 * (H * dp + q_start + q_end) / (3 * G + H);
        }
      t.work = work, t.dwork_dq = dwork_dq;
      // Reversible volume change that heats or cools (doc/thermodynamics.md):
      // with c at constant stress, the stress-producing part tr(Δε − βΔT I);
      // with c at constant volume (the seed's eq. 8 and 22), all of tr Δε.
      t.tr_rev = el.capacity_at_constant_volume ? tr_de + 3 * eth : tr_de;
      // Sources per current volume, capacity per reference volume (ρ₀c/J per current volume).
      t.rho_c = el.density * el.heat_capacity / inc.volume_ratio;
      t.adiabatic_temperature_increment =
        (el.taylor_quinney * work - 3 * K * t.beta * T * t.tr_rev) / t.rho_c;
    }
  } // namespace j2
} // namespace anvil
