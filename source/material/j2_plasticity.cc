// The J2 point (seed §1.3, §2.3): trial state, return map, consistent and
// adiabatic tangents, heat sources. Long because the point is one class with
// internal linkage (its helpers in j2_tangent.h are inlined only so, see
// there): evaluate() and finish() share its Trial and state; splitting the
// return map into another file would need the class in a header.
#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>

#include "j2_tangent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  // ---------------------------------------------------------------- J2Model

  void J2Model::declare_elasticity_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Elasticity");
    ElasticLaw::declare_parameters(prm);
    prm.leave_subsection();
  }

  void J2Model::parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path)
  {
    prm.enter_subsection("Elasticity");
    elastic.parse_parameters(prm, scene, path + "/Elasticity");
    prm.leave_subsection();
    if (plastic)
      hardening = create_hardening_law(prm, scene, path);
    if (viscous)
      viscosity.parse_parameters(prm, scene, path, elastic.reference_temperature);
  }

  namespace
  {
    class J2Point : public MaterialPoint
    {
    public:
      explicit J2Point(const J2Model &model)
        : model(model)
      {}

      void update(const MaterialIncrement &increment,
                  const MaterialRequest    request,
                  MaterialResponse        &response) override
      {
        response.volume_ratio_sensitivity = SymmetricTensor<2, 3>();
        const Rotated rotated = rotate(increment.rotation_increment); // independent of T: once for every return map below
        Trial         t;
        if (!increment.adiabatic)
          {
            evaluate(increment, increment.temperature, increment.temperature_increment, rotated, t);
            finish(increment, request, t, response);
            keep_for_audit(increment, rotated);
            return;
          }
        // Armero–Simo: the step's own heating changes the temperature the
        // return map sees. ΔT_ad = Δt (χẆirr + Ẇthel)/(ρc) is a scalar
        // fixed point x = f(Δε, σ̃ₙ, x); secant iteration (it contracts for
        // metals: f' ≈ τ = 9Kβ²T/(ρc) ≈ 0.01–0.05). The iterates need the
        // return map and ΔT_ad only (evaluate()); the stress, the tangent and
        // ∂σ/∂T come once, from the converged iterate (finish()): the same
        // numbers as a compute at the converged x.
        const bool            tangent = request & request_tangent;
        const MaterialRequest inner =
          tangent ? request | request_temperature_derivative : request;
        // From this point's last ΔT_ad (the previous Newton iterate's, or the
        // previous step's): within Newton the state moves little, so the
        // first residual is already small and the secant needs fewer return
        // maps than from 0.
        double x0 = 0, f0 = 0, x1 = adiabatic_guess, f1 = 0;
        for (unsigned int it = 0; it < 50; ++it)
          {
            evaluate(increment, increment.temperature + x1, increment.temperature_increment + x1,
                     rotated, t);
            f1 = t.adiabatic_temperature_increment - x1;
            if (std::abs(f1) <= 1e-12 * (1 + std::abs(x1)))
              break;
            double next = x1 + f1; // plain fixed point first
            if (it > 0 && f1 != f0)
              next = x1 - f1 * (x1 - x0) / (f1 - f0);
            x0 = x1, f0 = f1, x1 = next;
            if (it == 49)
              throw MaterialPointError("the adiabatic temperature change did not converge");
          }
        finish(increment, inner, t, response);
        keep_for_audit(increment, rotated);
        response.adiabatic_temperature_increment = x1;
        adiabatic_guess                          = x1;
        if (tangent)
          {
            // Consistent tangent of the adiabatic update: with x = f(Δε, σ̃ₙ, x),
            //   dx/dΔε = ∂f/∂Δε / (1 − ∂f/∂x),  dσ/dΔε = C + ∂σ/∂T ⊗ dx/dΔε
            // (and likewise for σ̃ₙ); ∂f/∂x in closed form from the tangent's
            // finish() (adiabatic_temperature_derivative).
            const SymmetricTensor<2, 3> &df_de = adiabatic_strain_derivative,
                                        &df_ds = adiabatic_stress_derivative;
            const double                 df_dx = adiabatic_temperature_derivative;
            const double                amplification = 1 / (1 - df_dx);
            const SymmetricTensor<2, 3> &dsigma_dT = response.stress_temperature_derivative;
            add_outer_product(response.tangent, amplification, dsigma_dT, df_de);
            if (response.sensitivity_is_identity)
              fill_identity(response.rotated_stress_sensitivity);
            response.sensitivity_is_identity = false;
            add_outer_product(response.rotated_stress_sensitivity, amplification, dsigma_dT, df_ds);
            // f ∝ J (sources per current volume): ∂f/∂ln J = f(x1) = x1 + f1.
            response.volume_ratio_sensitivity = (amplification * (x1 + f1)) * dsigma_dT;
          }
      }

      void commit() override
      {
        stress_n = current;
        eps_n    = eps_c;
        q_n      = equivalent_stress(stress_n);
      }
      void revert() override
      {
        current = stress_n;
        eps_c   = eps_n;
      }
      const SymmetricTensor<2, 3> &stress() const override { return current; }
      const SymmetricTensor<2, 3> &committed_stress() const override { return stress_n; }
      double equivalent_plastic_strain() const override { return eps_c; }
      double committed_equivalent_plastic_strain() const override { return eps_n; }
      void   set_stress(const SymmetricTensor<2, 3> &s) override
      {
        stress_n = current = s;
        q_n                = equivalent_stress(stress_n);
      }

      std::vector<double> save_state() const override
      {
        std::vector<double> state;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            state.push_back(stress_n[i][j]);
        state.push_back(eps_n);
        return state;
      }
      void load_state(const std::vector<double> &state) override
      {
        unsigned int k = 0;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            stress_n[i][j] = state.at(k++);
        eps_n   = state.at(k);
        current = stress_n;
        eps_c   = eps_n;
        q_n     = equivalent_stress(stress_n);
      }

    private:
      /// σ̃ₙ = ΔR σₙ ΔRᵀ (raw): an update's return maps share it; and its
      /// entries below the diagonal, (1,0), (2,0), (2,1), as computed (the
      /// audit's mean stress symmetrises the two, last_step()).
      struct Rotated { double trial[6], lower[3]; };
      Rotated rotate(const Tensor<2, 3> &R) const;

      /// One return map at temperature T: what finish() turns into the
      /// response, and ΔT_ad (all the adiabatic iteration needs).
      struct Trial
      {
        // (Every number is set by evaluate(), none is read before.)
        double T, dT, K, G, eth, deth, beta;
        double trial[6], de[6], s[6];
        double tr_de, norm_s, q_trial, dp, H;
        HardeningLaw::Value Y, Y_start;
        PerzynaLaw::Value   V;
        PerzynaLaw::Rate    rate;
        bool                linear_return; // the closed form: Y.stress = Y_start.stress + h Δε̄
        unsigned int        return_iterations;
        double              work, dwork_dq, tr_rev, rho_c;
        double              adiabatic_temperature_increment;
      };
      /// Trial state, yield test, return map and heat sources at (T, ΔT).
      void evaluate(const MaterialIncrement &inc, double T, double dT, const Rotated &rotated,
                    Trial &t) const;
      /// Stress, state, and what @p request asks beyond it, from @p t.
      void finish(const MaterialIncrement &inc, MaterialRequest request, Trial &t,
                  MaterialResponse &response);
      /// σᵥ(ε̄, T): inline where the law is linear with linear or no softening.
      HardeningLaw::Value yield(const double eps, const double T) const
      {
        const J2Model::Kernel &k = model.kernel();
        return k.inline_yield ? k.yield.evaluate(eps, T) : model.hardening->evaluate(eps, T);
      }
      /// σ̄ = ½(σ̃ₙ + σ) and Δε of this update (J2Model::last_step()): the
      /// operations of the audit's mean_stress(), entry for entry.
      void keep_for_audit(const MaterialIncrement &inc, const Rotated &rotated)
      {
        static constexpr unsigned int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
        for (unsigned int c = 0; c < 3; ++c)
          audit_mean[c][c] = 0.5 * (rotated.trial[c] + current[c][c]);
        for (unsigned int c = 3; c < 6; ++c)
          audit_mean[row[c]][col[c]] =
            0.5 * ((rotated.trial[c] + rotated.lower[c - 3]) * 0.5 + current[row[c]][col[c]]);
        audit_strain = inc.strain_increment;
      }

    public:
      SymmetricTensor<2, 3> audit_mean, audit_strain; // keep_for_audit()

    private:
      static double equivalent_stress(const SymmetricTensor<2, 3> &sigma)
      {
        return std::sqrt(1.5) * deviator(sigma).norm();
      }
      /// Δε̄ solving r(Δε̄) = q_tr − 3GΔε̄ − σᵥ(ε̄ₙ + Δε̄) − V(Δε̄) = 0 (0: the root
      /// is below working precision), with σᵥ and V at the returned Δε̄ in @p Y and
      /// @p V. @p Y0 is σᵥ at ε̄ₙ.
      double return_map(double                     q_tr,
                        double                     G,
                        double                     T,
                        const PerzynaLaw::Rate    &rate,
                        const HardeningLaw::Value &Y0,
                        unsigned int              &iterations,
                        HardeningLaw::Value       &Y,
                        PerzynaLaw::Value         &V) const;

      const J2Model        &model;
      SymmetricTensor<2, 3> stress_n, current;
      double                eps_n = 0, eps_c = 0;
      double                q_n = 0; // √(3/2)|dev σₙ|, kept with σₙ (the plastic work's start)
      // ∂ΔT_ad/∂Δε and ∂ΔT_ad/∂σ̃ₙ at fixed temperature (adiabatic tangent).
      SymmetricTensor<2, 3> adiabatic_strain_derivative, adiabatic_stress_derivative;
      // ∂ΔT_ad/∂T at fixed Δε and σ̃ₙ (the fixed point's ∂f/∂x).
      double adiabatic_temperature_derivative = 0;
      // The last ΔT_ad found: the start of the next fixed-point iteration
      // (a start only: the converged value does not depend on it beyond the
      // iteration's 1e-12 tolerance).
      double adiabatic_guess = 0;
    };

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

    J2Point::Rotated J2Point::rotate(const Tensor<2, 3> &R) const
    { // σ̃ = ΔR σ_n ΔRᵀ; σ_n as a full matrix, A = ΔR σ_n, σ̃_ij = A_il ΔR_jl.
      static constexpr unsigned int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
      Rotated             rotated;
      const double *sn = stress_n.begin_raw();
      if (R[0][2] == 0 && R[1][2] == 0 && R[2][0] == 0 && R[2][1] == 0 && sn[4] == 0 && sn[5] == 0)
        {
          // Plane strain and axisymmetric: ΔR and σₙ are [2x2 block, 0; 0, (2,2)].
          // The products below are the general ones' nonzero terms (the others
          // add exact zeros), so the values are the same.
          const double A00 = R[0][0] * sn[0] + R[0][1] * sn[3], A01 = R[0][0] * sn[3] + R[0][1] * sn[1];
          const double A10 = R[1][0] * sn[0] + R[1][1] * sn[3], A11 = R[1][0] * sn[3] + R[1][1] * sn[1];
          const double A22 = R[2][2] * sn[2];
          rotated.trial[0] = A00 * R[0][0] + A01 * R[0][1];
          rotated.trial[1] = A10 * R[1][0] + A11 * R[1][1];
          rotated.trial[2] = A22 * R[2][2];
          rotated.trial[3] = A00 * R[1][0] + A01 * R[1][1];
          rotated.trial[4] = rotated.trial[5] = 0;
          rotated.lower[0]                    = A10 * R[0][0] + A11 * R[0][1];
          rotated.lower[1] = rotated.lower[2] = 0;
          return rotated;
        }
      const double S[3][3] = {{sn[0], sn[3], sn[4]}, {sn[3], sn[1], sn[5]}, {sn[4], sn[5], sn[2]}};
      double       A[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int l = 0; l < 3; ++l)
          A[i][l] = R[i][0] * S[0][l] + R[i][1] * S[1][l] + R[i][2] * S[2][l];
      for (unsigned int c = 0; c < 6; ++c)
        rotated.trial[c] = A[row[c]][0] * R[col[c]][0] + A[row[c]][1] * R[col[c]][1] +
                           A[row[c]][2] * R[col[c]][2];
      for (unsigned int c = 3; c < 6; ++c)
        rotated.lower[c - 3] = A[col[c]][0] * R[row[c]][0] + A[col[c]][1] * R[row[c]][1] +
                               A[col[c]][2] * R[row[c]][2];
      return rotated;
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
      std::copy(rotated.trial, rotated.trial + 6, trial);
      const double *dstrain = inc.strain_increment.begin_raw();
      for (unsigned int c = 0; c < 6; ++c)
        de[c] = dstrain[c] - (c < 3 ? eth : 0.);
      const double tr_de   = de[0] + de[1] + de[2];
      const double mean_de = tr_de / 3;
      t.tr_de              = tr_de;
      for (unsigned int c = 0; c < 6; ++c)
        trial[c] += c < 3 ? K * tr_de + 2 * G * (de[c] - mean_de) : 2 * G * de[c];
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

    void J2Point::finish(const MaterialIncrement &inc, const MaterialRequest request, Trial &t,
                         MaterialResponse &response)
    {
      const ElasticLaw &el = model.elastic;
      const double      T = t.T, K = t.K, G = t.G, beta = t.beta, deth = t.deth;
      const double      dp = t.dp, H = t.H, norm_s = t.norm_s, q_trial = t.q_trial, tr_de = t.tr_de;
      const double     *trial = t.trial, *de = t.de, *s = t.s;
      HardeningLaw::Value &Y = t.Y;
      PerzynaLaw::Value   &V = t.V;
      const HardeningLaw::Value &Y_start = t.Y_start;
      response.return_iterations = t.return_iterations;
      if (t.linear_return && (request & request_temperature_derivative))
        Y = yield(eps_n + dp, T);

      // Radial return: σ = trial − √6 G Δε̄ n, n = s/|s|.
      // n enters only through Δε̄ > 0 terms (elastic: zero, as for |s| = 0).
      double n[6] = {0, 0, 0, 0, 0, 0};
      if (dp > 0)
        {
          const double inv_norm = 1 / norm_s;
          for (unsigned int c = 0; c < 6; ++c)
            n[c] = s[c] * inv_norm;
        }
      double *sigma = response.stress.begin_raw();
      if (dp > 0)
        {
          const double radial = std::sqrt(6.) * G * dp;
          for (unsigned int c = 0; c < 6; ++c)
            sigma[c] = trial[c] - radial * n[c];
        }
      else
        for (unsigned int c = 0; c < 6; ++c)
          sigma[c] = trial[c];
      current = response.stress;
      eps_c   = eps_n + dp;
      response.equivalent_plastic_strain = eps_c;

      if (request & request_tangent)
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

      if (request & request_temperature_derivative)
        {
          // ∂σ/∂T_{n+1} at fixed Δε and σ_n (T_n fixed, so ∂ΔT/∂T = 1).
          static const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
          SymmetricTensor<2, 3>              de_t, n_t;
          for (unsigned int c = 0; c < 6; ++c)
            {
              de_t.access_raw_entry(c) = de[c];
              n_t.access_raw_entry(c)  = n[c];
            }
          const double                g = el.relative_modulus_derivative(T);
          const SymmetricTensor<2, 3> dtrial =
            g * (K * tr_de * I + 2 * G * deviator(de_t)) - 3 * K * deth * I;
          SymmetricTensor<2, 3> ds = dtrial;
          if (dp > 0)
            {
              // Johnson-Cook: V = σ_h C ln(ε̄̇/ε̇₀), so ∂V/∂T = (V/σ_h) ∂σ_h/∂T.
              V.temperature_derivative =
                model.johnson_cook_rate.active() ?
                  (Y.stress > 0 ? V.stress / Y.stress * Y.temperature_derivative : 0.) :
                  model.viscosity.temperature_derivative(t.rate, T, eps_c, dp, V.stress);
              const double dG  = g * G;
              const double dq  = std::sqrt(1.5) * (n_t * dtrial);
              const double ddp = (dq - 3 * dG * dp - Y.temperature_derivative -
                                  V.temperature_derivative) / (3 * G + H);
              const SymmetricTensor<2, 3> dn = (deviator(dtrial) - (n_t * dtrial) * n_t) / norm_s;
              ds -= std::sqrt(6.) * ((dG * dp + G * ddp) * n_t + G * dp * dn);
            }
          response.stress_temperature_derivative = ds;
        }

      const double dt   = inc.time_step;
      const double work = t.work, tr_rev = t.tr_rev, rho_c = t.rho_c;
      response.plastic_work_rate        = work / dt;
      response.plastic_dissipation_rate = el.taylor_quinney * work / dt;
      // Ẇthel = −3Kβ T tr(Δεᵉ)/Δt (plastic flow is isochoric), doc/thermodynamics.md.
      response.thermoelastic_heating_rate      = -3 * K * beta * T * tr_rev / dt;
      response.adiabatic_temperature_increment = t.adiabatic_temperature_increment;
      if (inc.adiabatic && (request & request_tangent))
        {
          // Partial derivatives of ΔT_ad at fixed T: ∂q_tr/∂Δε = √6 G n,
          // ∂q_tr/∂σ̃ₙ = √(3/2) n, ∂tr_rev/∂Δε = I.
          SymmetricTensor<2, 3> n_t;
          for (unsigned int c = 0; c < 6; ++c)
            n_t.access_raw_entry(c) = n[c];
          const double chi = el.taylor_quinney;
          adiabatic_strain_derivative =
            (chi * t.dwork_dq * std::sqrt(6.) * G * n_t - 3 * K * beta * T * unit_symmetric_tensor<3>()) /
            rho_c;
          adiabatic_stress_derivative = (chi * t.dwork_dq * std::sqrt(1.5) / rho_c) * n_t;
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
              double n_de = 0;
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
          adiabatic_temperature_derivative =
            (chi * dwork_dT - 3 * ((dK * beta + K * dbeta) * T * tr_rev + K * beta * tr_rev +
                                   K * beta * T * dtr_rev)) /
            rho_c;
        }
    }
  } // namespace

  void J2Model::last_step(const MaterialPoint                &point,
                          const SymmetricTensor<2, 3>       *&mean_stress,
                          const SymmetricTensor<2, 3>       *&strain_increment) const
  {
    // Every point of a J2Model is a J2Point (create_point(s)).
    const auto &p    = static_cast<const J2Point &>(point);
    mean_stress      = &p.audit_mean;
    strain_increment = &p.audit_strain;
  }

  void J2Model::prepare_kernel() const
  {
    std::call_once(kernel_once, [this]() {
      if (!plastic)
        return;
      kernel_cache.linear       = hardening->is_linear();
      kernel_cache.inline_yield = hardening->linear_form(kernel_cache.yield);
    });
  }

  std::unique_ptr<MaterialPoint> J2Model::create_point() const
  {
    prepare_kernel();
    return std::make_unique<J2Point>(*this);
  }

  std::vector<std::shared_ptr<MaterialPoint>> J2Model::create_points(const std::size_t n) const
  {
    prepare_kernel();
    return contiguous_points<J2Point>(n, *this);
  }
} // namespace anvil
