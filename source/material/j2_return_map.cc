// The J2 point's return map (seed §1.3, eq. 9–18): the radial return to
// f = 0 or f̄ = 0 by safeguarded Newton where it has no closed form (the
// trial state and the closed form: evaluate(), j2_evaluate.h).
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
  } // namespace j2
} // namespace anvil
