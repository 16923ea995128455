// The linearisation of the Green-Naghdi and logarithmic updates (kinematics.h):
// the kinematics by central differences, the material exactly.
#include <anvil/material/kinematics.h>

namespace anvil
{
  using namespace dealii;

  void rate_cauchy_tangent(const IncrementalKinematics &kin,
                           const SymmetricTensor<2, 3> &stress_old,
                           const MaterialResponse      &response,
                           const TangentDirections     &directions,
                           SymmetricTensor<2, 3>       *dsigma)
  {
    // F is O(1): h = 1e-6 balances the O(h²) truncation against round-off
    // ε|Δε|/h of the differences (both ~1e-12..1e-10).
    const double       h    = 1e-6;
    const Tensor<2, 3> &R   = kin.rotation_increment;
    const Tensor<2, 3> sn   = Tensor<2, 3>(stress_old);
    IncrementalKinematics plus, minus;
    for (unsigned int d = 0; d < directions.n; ++d)
      {
        const unsigned int k = directions.kl[d].first, L = directions.kl[d].second;
        Tensor<2, 3>       F_plus = kin.F, F_minus = kin.F;
        F_plus[k][L] += h;
        F_minus[k][L] -= h;
        plus.reinit(F_plus, kin.F_old, kin.rate);
        minus.reinit(F_minus, kin.F_old, kin.rate);
        const SymmetricTensor<2, 3> deps =
          (plus.strain_increment - minus.strain_increment) / (2 * h);
        const Tensor<2, 3> dR = (plus.rotation_increment - minus.rotation_increment) / (2 * h);
        // δσ̃ = δΔR σ_n ΔRᵀ + ΔR σ_n δΔRᵀ (symmetric by construction).
        const SymmetricTensor<2, 3> drot = 2 * symmetrize(dR * sn * transpose(R));
        dsigma[d] = contract_material_tangent(response, deps, drot);
      }
  }
} // namespace anvil
