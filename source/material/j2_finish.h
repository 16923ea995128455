// The J2 point's finish(): from one return map (evaluate()) the stress and
// state, the consistent tangent and ∂σ/∂σ̃ₙ, ∂σ/∂T, the heat sources and the
// partial derivatives of ΔT_ad the adiabatic tangent needs. Inline in
// update() (j2_plasticity.cc, its only includer), like evaluate().
#pragma once

#include <anvil/material/j2_plasticity.h>

#include "j2_point.h"
#include "j2_tangent.h"

#include <cmath>

namespace anvil
{
  namespace j2
  {
    using dealii::unit_symmetric_tensor;

    namespace
    {
      /// The tangent of the radial return, factored (FactoredTangent) when the
      /// caller asks for it, else as 36 + 36 entries (C and ∂σ/∂σ̃ₙ).
      [[gnu::always_inline]] inline void write_tangent(const MaterialRequest request, const bool adiabatic,
                                const double K, const double G, const double H, const double dp,
                                const double q_trial, const double *n, MaterialResponse &response)
      {
        response.factored.active = false;
        // Not for the adiabatic update: its rank-one terms (J2Point::update) in
        // the factored form change the tangent's round-off, which moves the
        // adiabatic scenes' Newton iterates by up to 1e-5 (necking_bar_thermal).
        if ((request & request_tangent) && (request & request_factored_tangent) && !adiabatic)
          {
            // The same moduli as below, factored (FactoredTangent): the callers'
            // contractions take it as it is, no 72 entries are written.
            FactoredTangent &f = response.factored;
            f.active = true, f.rank_one = false, f.bulk = K;
            if (dp > 0)
              {
                const double a = 3 * G * dp / q_trial, b = 3 * G / (3 * G + H);
                f.deviatoric = 2 * G * (1 - a), f.normal = 2 * G * (a - b);
                f.sensitivity_deviatoric = a, f.sensitivity_normal = a - b;
                #pragma GCC unroll 6
                for (unsigned int c = 0; c < 6; ++c)
                  f.n[c] = n[c];
                response.sensitivity_is_identity = false;
              }
            else
              {
                f.deviatoric = 2 * G, f.normal = 0;
                f.sensitivity_deviatoric = f.sensitivity_normal = 0;
                response.sensitivity_is_identity = true;
              }
          }
        else if (request & request_tangent)
          {
            double *C = response.tangent.begin_raw();
            if (dp > 0)
              {
                // Consistent tangent of the radial return (Simo & Hughes 1998, box 3.2,
                // with H' including the viscous term of eq. 18):
                //   C = K δ⊗δ + 2G ((1 − a) I_dev + (a − b) n⊗n),
                //   ∂σ/∂σ̃ₙ = I_sym − b n⊗n − a (I_dev − n⊗n).
                const double a = 3 * G * dp / q_trial, b = 3 * G / (3 * G + H);
                fill_tangent<true>(C, K, 2 * G * (1 - a), 2 * G * (a - b), n);
                response.sensitivity_is_identity = false;
                fill_sensitivity(response.rotated_stress_sensitivity.begin_raw(), a, b, n);
              }
            else
              {
                fill_tangent<false>(C, K, 2 * G, 0., n);
                response.sensitivity_is_identity = true;
              }
          }
      }
    } // namespace

    template <bool simple>
    [[gnu::always_inline]] inline void J2Point::finish(const MaterialIncrement &inc, const MaterialRequest request,
                                const bool adiabatic, Trial &t, MaterialResponse &response)
    {
      const ElasticLaw &el = model.elastic;
      const double      T = t.T, K = t.K, G = t.G, beta = t.beta, deth = t.deth;
      const double      dp = t.dp, H = t.H, norm_s = t.norm_s, q_trial = t.q_trial, tr_de = t.tr_de;
      const double     *trial = t.trial, *s = t.s;
      HardeningLaw::Value &Y = t.Y;
      PerzynaLaw::Value   &V = t.V;
      const HardeningLaw::Value &Y_start = t.Y_start;
      response.return_iterations = t.return_iterations;
      {
        // The heat sources first: what they need is then not kept (on the
        // stack) through the stress and the tangent.
        const double dt = inc.time_step, work = t.work;
        response.plastic_work_rate        = work / dt;
        response.plastic_dissipation_rate = el.taylor_quinney * work / dt;
        // Ẇthel = −3Kβ T tr(Δεᵉ)/Δt (plastic flow is isochoric), doc/thermodynamics.md.
        response.thermoelastic_heating_rate      = -3 * K * beta * T * t.tr_rev / dt;
        response.adiabatic_temperature_increment = t.adiabatic_temperature_increment;
      }
      if (t.linear_return && (request & request_temperature_derivative))
        {
          HardeningLaw::Value y = yield<simple>(eps_n + dp, T);
          Y                           = y;
        }

      // Radial return: σ = trial − √6 G Δε̄ n, n = s/|s|.
      // n enters only through Δε̄ > 0 terms (elastic: zero, as for |s| = 0).
      double n[6];
      if (dp > 0)
        {
          const double inv_norm = 1 / norm_s;
          #pragma GCC unroll 6
          for (unsigned int c = 0; c < 6; ++c)
            n[c] = s[c] * inv_norm;
        }
      else
        #pragma GCC unroll 6
        for (unsigned int c = 0; c < 6; ++c)
          n[c] = 0;
      double *sigma = response.stress.begin_raw();
      if (dp > 0)
        {
          const double radial = std::sqrt(6.) * G * dp;
          #pragma GCC unroll 6
          for (unsigned int c = 0; c < 6; ++c)
            sigma[c] = trial[c] - radial * n[c];
        }
      else
        #pragma GCC unroll 6
        for (unsigned int c = 0; c < 6; ++c)
          sigma[c] = trial[c];
      current = response.stress;
      eps_c   = eps_n + dp;
      response.equivalent_plastic_strain = eps_c;

      write_tangent(request, adiabatic, K, G, H, dp, q_trial, n, response);

      if (request & request_temperature_derivative)
        {
          // ∂σ/∂T_{n+1} at fixed Δε and σ_n (T_n fixed, so ∂ΔT/∂T = 1).
          //   ∂σ_tr/∂T = g (K tr Δεᵉ I + 2G dev Δεᵉ) − 3K ∂Δε_th/∂T I,
          // entry by entry as deal.II's operators form it (I's zeros included:
          // the same bits), without its temporaries.
          const double          g = el.relative_modulus_derivative(T);
          SymmetricTensor<2, 3> dtrial;
          {
            double de[6];
            elastic_strain_increment(inc, t, de);
            const double k_tr = K * tr_de, two_G = 2 * G, th = 3 * K * deth;
            const double mean = (de[0] + de[1] + de[2]) / 3; // deviator(): trace / dim
            double      *d    = dtrial.begin_raw();
            #pragma GCC unroll 6
            for (unsigned int c = 0; c < 3; ++c)
              d[c] = g * (k_tr * 1. + (de[c] - mean) * two_G) - th * 1.;
            #pragma GCC unroll 6
            for (unsigned int c = 3; c < 6; ++c)
              d[c] = g * (k_tr * 0. + de[c] * two_G) - th * 0.;
          }
          SymmetricTensor<2, 3> ds = dtrial;
          if (dp > 0)
            {
              SymmetricTensor<2, 3> n_t;
              #pragma GCC unroll 6
              for (unsigned int c = 0; c < 6; ++c)
                n_t.access_raw_entry(c) = n[c];
              // Johnson-Cook: V = σ_h C ln(ε̄̇/ε̇₀), so ∂V/∂T = (V/σ_h) ∂σ_h/∂T.
              V.temperature_derivative =
                model.johnson_cook_rate.active() ?
                  (Y.stress > 0 ? V.stress / Y.stress * Y.temperature_derivative : 0.) :
                  [&] {
                    const PerzynaLaw::Rate rate = t.rate; // (t's address not passed)
                    return model.viscosity.temperature_derivative(rate, T, eps_c, dp, V.stress);
                  }();
              const double dG  = g * G;
              const double dq  = std::sqrt(1.5) * (n_t * dtrial);
              const double ddp = (dq - 3 * dG * dp - Y.temperature_derivative -
                                  V.temperature_derivative) / (3 * G + H);
              const SymmetricTensor<2, 3> dn = (deviator(dtrial) - (n_t * dtrial) * n_t) / norm_s;
              ds -= std::sqrt(6.) * ((dG * dp + G * ddp) * n_t + G * dp * dn);
            }
          response.stress_temperature_derivative = ds;
        }

      const double tr_rev = t.tr_rev, rho_c = t.rho_c;
      if (adiabatic && (request & request_tangent))
        {
          // Partial derivatives of ΔT_ad at fixed T: ∂q_tr/∂Δε = √6 G n,
          // ∂q_tr/∂σ̃ₙ = √(3/2) n, ∂tr_rev/∂Δε = I.
          SymmetricTensor<2, 3> n_t;
          #pragma GCC unroll 6
          for (unsigned int c = 0; c < 6; ++c)
            n_t.access_raw_entry(c) = n[c];
          const double chi = el.taylor_quinney;
          AdiabaticState &state = adiabatic_state();
          state.strain_derivative =
            (chi * t.dwork_dq * std::sqrt(6.) * G * n_t - 3 * K * beta * T * unit_symmetric_tensor<3>()) /
            rho_c;
          state.stress_derivative = (chi * t.dwork_dq * std::sqrt(1.5) / rho_c) * n_t;
          // ∂ΔT_ad/∂T at fixed Δε, σ̃ₙ (the adiabatic tangent's request has ∂/∂T,
          // so Y and V carry theirs): K' = gK, β'(T) (eq. 19), tr_rev' = −3
          // ∂Δε_th/∂T at constant stress, and the plastic work's, through Δε̄,
          // q_end and, if the step began elastic, q_start = σᵥ(ε̄ₙ, T) (the
          // softened yield stress; eq. 35 for the linear law). Here, not in the
          // ∂σ/∂T block: the other updates pay nothing for it.
          const double g        = el.relative_modulus_derivative(T);
          double       dwork_dT = 0;
          if (dp > 0)
            {
              // ∂q_tr/∂T = √(3/2) n : ∂σ_tr/∂T = √(3/2) 2G' n : Δεᵉ (n deviatoric).
              double de[6];
              elastic_strain_increment(inc, t, de);
              double n_de = 0;
              #pragma GCC unroll 6
              for (unsigned int c = 0; c < 6; ++c)
                n_de += (c < 3 ? 1. : 2.) * n[c] * de[c];
              const double dG       = g * G;
              const double dq       = std::sqrt(1.5) * 2 * dG * n_de;
              const double ddp      = (dq - 3 * dG * dp - Y.temperature_derivative -
                                  V.temperature_derivative) / (3 * G + H);
              const double q_end    = q_trial - 3 * G * dp;
              const double q_start  = std::max(q_n, Y_start.stress);
              const double dq_end   = dq - 3 * dG * dp - 3 * G * ddp;
              const double dq_start = q_n < Y_start.stress ? Y_start.temperature_derivative : 0.;
              dwork_dT = 0.5 * (dq_start + dq_end) * dp + 0.5 * (q_start + q_end) * ddp;
            }
          const double dK      = g * K;
          const double dbeta   = el.thermal_expansion_derivative(T);
          const double dtr_rev = el.capacity_at_constant_volume ? 0. : -3 * deth;
          state.temperature_derivative =
            (chi * dwork_dT - 3 * ((dK * beta + K * dbeta) * T * tr_rev + K * beta * tr_rev +
                                   K * beta * T * dtr_rev)) /
            rho_c;
        }
    }
  } // namespace j2
} // namespace anvil
