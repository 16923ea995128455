// The J2 point (seed §1.3, §2.3), private to source/material: the class
// that the files implementing it share, one concern each —
//   j2_plasticity.cc  the model's parameters and factory, the update and its
//                     adiabatic fixed point, the rotation of σₙ;
//   j2_evaluate.h     trial state, yield test, linear return, ΔT_ad (evaluate());
//   j2_return_map.cc  the return map where it has no closed form;
//   j2_finish.h       stress, consistent and adiabatic tangents, ∂σ/∂T, heat
//                     sources (finish()).
// evaluate() and finish() are inline in update_isothermal() and
// update_adiabatic() (their only callers): the trial state is not passed
// through call frames (J2 bench, 3D plastic, stress + tangent: 654 → 556
// instructions per update). Trial carries one return
// map from evaluate() to finish(); it stays in registers only if no call gets
// the address of one of its fields and every loop over its arrays is unrolled
// before GCC's scalar replacement (-O2 unrolls after it without
// `#pragma GCC unroll`): 492 → 455 instructions per update with the split.
#pragma once

#include <anvil/material/j2_plasticity.h>

#include <cmath>
#include <memory>

namespace anvil
{
  namespace j2
  {
    using dealii::SymmetricTensor;
    using dealii::Tensor;

    class J2Point : public MaterialPoint
    {
    public:
      explicit J2Point(const J2Model &model)
        : model(model)
      {}

      void update(const MaterialIncrement &increment,
                  const MaterialRequest    request,
                  MaterialResponse        &response) override;

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
        #pragma GCC unroll 6
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            state.push_back(stress_n[i][j]);
        state.push_back(eps_n);
        return state;
      }
      void load_state(const std::vector<double> &state) override
      {
        unsigned int k = 0;
        #pragma GCC unroll 6
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            stress_n[i][j] = state.at(k++);
        eps_n   = state.at(k);
        current = stress_n;
        eps_c   = eps_n;
        q_n     = equivalent_stress(stress_n);
      }

    private:
      /// σ̃ₙ = ΔR σₙ ΔRᵀ (raw): an update's return maps share it.
      struct Rotated { double trial[6]; };
      Rotated rotate(const Tensor<2, 3> &R) const;

      /// One return map at temperature T: what finish() turns into the
      /// response, and ΔT_ad (all the adiabatic iteration needs).
      struct Trial
      {
        // (Every number is set by evaluate(), none is read before.)
        double T, dT, K, G, eth, deth, beta;
        double trial[6], s[6]; // (Δεᵉ: elastic_strain_increment(), where needed)
        double tr_de, norm_s, q_trial, dp, H;
        HardeningLaw::Value Y, Y_start;
        PerzynaLaw::Value   V;
        PerzynaLaw::Rate    rate;
        bool                linear_return; // the closed form: Y.stress = Y_start.stress + h Δε̄
        unsigned int        return_iterations;
        double              work, dwork_dq, tr_rev, rho_c;
        double              adiabatic_temperature_increment;
      };
      /// Δεᵉ = Δε − Δε_th I of @p t, as evaluate() forms it (recomputed
      /// where ∂/∂T needs it: six stores fewer per update).
      static void elastic_strain_increment(const MaterialIncrement &inc, const Trial &t, double *de)
      {
        const double *dstrain = inc.strain_increment.begin_raw();
        #pragma GCC unroll 6
        for (unsigned int c = 0; c < 6; ++c)
          de[c] = dstrain[c] - (c < 3 ? t.eth : 0.);
      }
      // Hidden (and return_map()): update() reaches them by a direct jump,
      // not through the PLT (an exported symbol of a shared library).
      /// update() without the adiabatic split; @p simple: the instance for
      /// J2Model::Kernel::simple (its constants, no branch on the laws).
      template <bool simple>
      [[gnu::visibility("hidden")]] void update_isothermal(const MaterialIncrement &increment, MaterialRequest request,
                             MaterialResponse &response);

      /// Trial state, yield test, return map and heat sources at (T, ΔT);
      /// ΔT_ad and what its tangent needs only if @p adiabatic (a constant
      /// at both callers: the isothermal update has neither).
      template <bool simple = false>
      void evaluate(const MaterialIncrement &inc, double T, double dT, const Rotated &rotated,
                    bool adiabatic, Trial &t) const;
      /// Stress, state, and what @p request asks beyond it, from @p t
      /// (@p adiabatic as for evaluate()).
      template <bool simple = false>
      void finish(const MaterialIncrement &inc, MaterialRequest request, bool adiabatic, Trial &t,
                  MaterialResponse &response);
      /// σᵥ(ε̄, T): inline where the law is linear with linear or no softening.
      template <bool simple = false>
      HardeningLaw::Value yield(const double eps, const double T) const
      {
        const J2Model::Kernel &k = model.kernel();
        if (simple || k.plain_yield)
          {
            // LinearForm::evaluate() at θ = 1, dθ/dT = 0 (1 x is x): the same bits.
            HardeningLaw::Value v;
            v.stress                 = k.yield.sigma0 + k.yield.h * eps;
            v.slope                  = k.yield.h;
            // (simple: h ≥ 0 and ε̄ ≥ 0, so 0 σ₀ + 0 h ε̄ is +0, a constant.)
            v.temperature_derivative = simple ? 0. : 0. * k.yield.sigma0 + 0. * k.yield.h * eps;
            return v;
          }
        return k.inline_yield ? k.yield.evaluate(eps, T) : model.hardening->evaluate(eps, T);
      }
      static double equivalent_stress(const SymmetricTensor<2, 3> &sigma)
      {
        return std::sqrt(1.5) * deviator(sigma).norm();
      }
      /// Δε̄ solving r(Δε̄) = q_tr − 3GΔε̄ − σᵥ(ε̄ₙ + Δε̄) − V(Δε̄) = 0 (0: the root
      /// is below working precision), with σᵥ and V at the returned Δε̄ in @p Y and
      /// @p V. @p Y0 is σᵥ at ε̄ₙ.
      [[gnu::visibility("hidden")]] double return_map(double                     q_tr,
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

    protected:
      /// What only the adiabatic update keeps (112 B): a J2AdiabaticPoint
      /// carries it inline, so the points of the other scenes do not (136 B
      /// against 248 B; 232 and 344 before session 21 left the energy audit
      /// its own kinematics), and those of an adiabatic scene are not a heap
      /// object each (session 19 made it on a point's first adiabatic update).
      struct AdiabaticState
      {
        // ∂ΔT_ad/∂Δε and ∂ΔT_ad/∂σ̃ₙ at fixed temperature (adiabatic tangent).
        SymmetricTensor<2, 3> strain_derivative, stress_derivative;
        // ∂ΔT_ad/∂T at fixed Δε and σ̃ₙ (the fixed point's ∂f/∂x).
        double temperature_derivative = 0;
        // The last ΔT_ad found: the start of the next fixed-point iteration
        // (a start only: the converged value does not depend on it beyond the
        // iteration's 1e-12 tolerance).
        double guess = 0;
      };
      /// update() with the adiabatic split (Armero–Simo): only a
      /// J2AdiabaticPoint's (its update() is the only caller).
      [[gnu::visibility("hidden")]] void update_adiabatic(const MaterialIncrement &increment, MaterialRequest request,
                            MaterialResponse &response);
      /// The state of update_adiabatic(): this point is a J2AdiabaticPoint.
      AdiabaticState &adiabatic_state();
    };

    /**
     * A J2 point of a scene with the adiabatic split (PointOptions::adiabatic):
     * the J2 point and the adiabatic iteration's state, in the body's block.
     * A plain J2Point refuses an adiabatic increment.
     */
    class J2AdiabaticPoint : public J2Point
    {
    public:
      using J2Point::J2Point;

      void update(const MaterialIncrement &increment,
                  const MaterialRequest    request,
                  MaterialResponse        &response) override
      {
        if (!increment.adiabatic)
          return J2Point::update(increment, request, response);
        update_adiabatic(increment, request, response);
      }

    private:
      friend class J2Point;
      AdiabaticState state;
    };

    inline J2Point::AdiabaticState &J2Point::adiabatic_state()
    {
      return static_cast<J2AdiabaticPoint &>(*this).state;
    }

    MaterialPointError no_plastic_solution(double T);
    /// A plain J2Point's answer to an adiabatic increment (cold: off the update's path).
    [[noreturn]] void no_adiabatic_state();
  } // namespace j2
} // namespace anvil
