// The J2 model (seed §1.3, §2.3): its parameters and points, and the point's
// update — the adiabatic fixed point around evaluate() (j2_evaluate.h, with
// return_map() in j2_return_map.cc) and finish() (j2_finish.h), both inline
// here; the class is in j2_point.h.
#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>

#include "j2_evaluate.h"
#include "j2_finish.h"
#include "j2_point.h"
#include "j2_tangent.h"

#include <cmath>
#include <cstdint>
#include <cstring>

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

  namespace j2
  {
    // Inline: update() is its only caller.
    [[gnu::always_inline]] inline J2Point::Rotated J2Point::rotate(const Tensor<2, 3> &R) const
    { // σ̃ = ΔR σ_n ΔRᵀ; σ_n as a full matrix, A = ΔR σ_n, σ̃_ij = A_il ΔR_jl.
      static constexpr unsigned int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
      Rotated             rotated;
      const double *sn = stress_n.begin_raw();
      // All six ±0 (x == 0 for each), tested on the bits at once: one branch,
      // not six compare-and-branch pairs (each x == 0 is also two jumps).
      auto bits = [](const double x) {
        std::uint64_t b;
        std::memcpy(&b, &x, sizeof b);
        return b;
      };
      if (((bits(R[0][2]) | bits(R[1][2]) | bits(R[2][0]) | bits(R[2][1]) | bits(sn[4]) | bits(sn[5]))
           << 1) == 0)
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
          return rotated;
        }
      const double S[3][3] = {{sn[0], sn[3], sn[4]}, {sn[3], sn[1], sn[5]}, {sn[4], sn[5], sn[2]}};
      double       A[3][3];
      #pragma GCC unroll 6
      for (unsigned int i = 0; i < 3; ++i)
        #pragma GCC unroll 6
        for (unsigned int l = 0; l < 3; ++l)
          A[i][l] = R[i][0] * S[0][l] + R[i][1] * S[1][l] + R[i][2] * S[2][l];
      #pragma GCC unroll 6
      for (unsigned int c = 0; c < 6; ++c)
        rotated.trial[c] = A[row[c]][0] * R[col[c]][0] + A[row[c]][1] * R[col[c]][1] +
                           A[row[c]][2] * R[col[c]][2];
      return rotated;
    }

    // One return map at the given temperature, in a function of its own:
    // in update() the adiabatic loop's values kept the isothermal path's in
    // memory (register pressure of the whole function; J2 bench, 3D plastic,
    // stress + tangent, with the locals and early unrolling of evaluate(): 492 → 474
    // instructions per update).
    // Without SLP vectorisation (both updates): GCC paired the six-entry
    // loops' scalars into two-lane registers at the price of shuffles and
    // stack round trips (J2 bench, 3D plastic, stress + factored tangent,
    // 477 → 418 instructions per update; tube adiabatic bench 189.0 → 186.4 M).
    // The simple instance (J2Model::Kernel::simple) has no branch on the laws:
    // 418 → 358.
    template <bool simple>
    [[gnu::noinline, gnu::no_stack_protector, gnu::optimize("no-tree-slp-vectorize")]] void J2Point::update_isothermal(
      const MaterialIncrement &increment, const MaterialRequest request, MaterialResponse &response)
    {
      response.volume_ratio_sensitivity = SymmetricTensor<2, 3>();
      Rotated rotated = rotate(increment.rotation_increment);
      Trial t;
      evaluate<simple>(increment, increment.temperature, increment.temperature_increment, rotated,
                       false, t);
      finish<simple>(increment, request, false, t, response);
    }

    // update_isothermal() and update_adiabatic() have no stack canary
    // (-fstack-protector-strong puts one in every function with a local
    // array): their arrays are doubles indexed by constants, and the check
    // was 7 of ~520 instructions per update.
    void J2Point::update(const MaterialIncrement &increment,
                         const MaterialRequest    request,
                         MaterialResponse        &response)
    {
      // Two tail calls: neither path's frame and saved registers are set up
      // for the other (21 instructions per isothermal update when
      // update_adiabatic()'s body was here).
      if (!increment.adiabatic)
        {
          if (model.kernel().simple)
            return update_isothermal<true>(increment, request, response);
          return update_isothermal<false>(increment, request, response);
        }
      no_adiabatic_state();
    }

    [[noreturn, gnu::noinline, gnu::cold]] void no_adiabatic_state()
    {
      throw std::logic_error("a J2 point made without PointOptions::adiabatic was given an "
                             "adiabatic increment (MaterialModel::create_points)");
    }

    [[gnu::noinline, gnu::no_stack_protector, gnu::optimize("no-tree-slp-vectorize")]] void J2Point::update_adiabatic(
      const MaterialIncrement &increment, const MaterialRequest request, MaterialResponse &response)
    {
      response.volume_ratio_sensitivity = SymmetricTensor<2, 3>();
      AdiabaticState &state = adiabatic_state();
      Rotated rotated = rotate(increment.rotation_increment); // independent of T: once for every return map below
      Trial         t;
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
      // maps than from 0. The first step is Newton's with the last tangent's
      // ∂f/∂x (state.temperature_derivative; 0 before the first: the
      // plain fixed point): x + (f(x) − x)/(1 − ∂f/∂x).
      const double first_slope = 1 - state.temperature_derivative;
      const double first_scale = first_slope > 0.5 && first_slope < 2 ? 1 / first_slope : 1.;
      double       x0 = 0, f0 = 0, x1 = state.guess, f1 = 0;
      for (unsigned int it = 0; it < 50; ++it)
        {
          evaluate(increment, increment.temperature + x1, increment.temperature_increment + x1,
                   rotated, true, t);
          f1 = t.adiabatic_temperature_increment - x1;
          if (std::abs(f1) <= 1e-12 * (1 + std::abs(x1)))
            break;
          double next = x1 + first_scale * f1;
          if (it > 0 && f1 != f0)
            next = x1 - f1 * (x1 - x0) / (f1 - f0);
          x0 = x1, f0 = f1, x1 = next;
          if (it == 49)
            throw MaterialPointError("the adiabatic temperature change did not converge");
        }
      finish(increment, inner, true, t, response);
      response.adiabatic_temperature_increment = x1;
      state.guess                              = x1;
      if (tangent)
        {
          // Consistent tangent of the adiabatic update: with x = f(Δε, σ̃ₙ, x),
          //   dx/dΔε = ∂f/∂Δε / (1 − ∂f/∂x),  dσ/dΔε = C + ∂σ/∂T ⊗ dx/dΔε
          // (and likewise for σ̃ₙ); ∂f/∂x in closed form from the tangent's
          // finish() (state.temperature_derivative).
          const SymmetricTensor<2, 3> &df_de = state.strain_derivative,
                                      &df_ds = state.stress_derivative;
          const double                 df_dx = state.temperature_derivative;
          const double                amplification = 1 / (1 - df_dx);
          const SymmetricTensor<2, 3> &dsigma_dT = response.stress_temperature_derivative;
          // ∂f/∂σ̃ₙ ∝ the plastic work's n: zero at an elastic point, whose
          // ∂σ/∂σ̃ₙ stays the identity (flagged: the mechanics skips S : δσ̃).
          if (FactoredTangent &f = response.factored; f.active)
            {
              // The rank-one terms of the factored form: u = ∂σ/∂T, v, w amplified.
              f.rank_one = true;
              const double *u = dsigma_dT.begin_raw(), *v = df_de.begin_raw(),
                           *w = df_ds.begin_raw();
              #pragma GCC unroll 6
              for (unsigned int c = 0; c < 6; ++c)
                f.u[c] = u[c], f.v[c] = amplification * v[c],
                f.w[c] = t.dp > 0 ? amplification * w[c] : 0.;
            }
          else
            {
              add_outer_product(response.tangent, amplification, dsigma_dT, df_de);
              if (t.dp > 0)
                add_outer_product(response.rotated_stress_sensitivity, amplification, dsigma_dT,
                                  df_ds);
            }
          // f ∝ J (sources per current volume): ∂f/∂ln J = f(x1) = x1 + f1.
          response.volume_ratio_sensitivity = (amplification * (x1 + f1)) * dsigma_dT;
        }
    }

  } // namespace j2


  void J2Model::prepare_kernel() const
  {
    std::call_once(kernel_once, [this]() {
      if (!plastic)
        return;
      kernel_cache.linear       = hardening->is_linear();
      kernel_cache.inline_yield = hardening->linear_form(kernel_cache.yield);
      kernel_cache.closed_form =
        kernel_cache.linear && !viscosity.active() && !johnson_cook_rate.active();
      const HardeningLaw::LinearForm &y = kernel_cache.yield;
      kernel_cache.plain_yield =
        kernel_cache.inline_yield && !(y.theta_linear && (y.soft_sigma0 || y.soft_h));
      const double T = elastic.reference_temperature; // (any: the laws are constant)
      kernel_cache.K    = elastic.bulk_modulus(T);
      kernel_cache.G    = elastic.shear_modulus(T);
      kernel_cache.beta = elastic.thermal_expansion(T);
      kernel_cache.simple = kernel_cache.plain_yield && kernel_cache.closed_form && y.h >= 0 &&
                            elastic.constant() && kernel_cache.K > 0 && kernel_cache.G > 0;
    });
  }

  std::unique_ptr<MaterialPoint> J2Model::create_point(const PointOptions &options) const
  {
    prepare_kernel();
    if (options.adiabatic)
      return std::make_unique<j2::J2AdiabaticPoint>(*this);
    return std::make_unique<j2::J2Point>(*this);
  }

  PointBlock J2Model::create_points(const std::size_t n, const PointOptions &options) const
  {
    prepare_kernel();
    if (options.adiabatic)
      return contiguous_points<j2::J2AdiabaticPoint>(n, *this);
    return contiguous_points<j2::J2Point>(n, *this);
  }
} // namespace anvil
