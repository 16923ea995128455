#include <anvil/mechanics/kinematics.h>

namespace anvil
{
  using namespace dealii;

  void IncrementalKinematics::reinit(const Tensor<2, 3> &F_new, const Tensor<2, 3> &F_old)
  {
    F     = F_new;
    J     = determinant(F);
    F_inv = invert(F);
    F_half_inv = invert(0.5 * (F + F_old));
    dL         = (F - F_old) * F_half_inv;
    const Tensor<2, 3> half_spin = 0.25 * (dL - transpose(dL));
    const Tensor<2, 3> I         = unit_symmetric_tensor<3>();
    A_inv                        = invert(I - half_spin);
    rotation_increment           = A_inv * (I + half_spin);
    // The strain increment lives on the mid-point configuration: rotate it
    // forward by half the step (Cayley transform of ¼Δω) so that the update
    // is second-order accurate for the Jaumann rate, not only first.
    mid_strain                   = symmetrize(dL);
    A_half_inv                   = invert(I - 0.5 * half_spin);
    half_rotation                = A_half_inv * (I + 0.5 * half_spin);
    strain_increment =
      symmetrize(half_rotation * Tensor<2, 3>(mid_strain) * transpose(half_rotation));
  }

  Tensor<2, 3> first_piola_stress(const IncrementalKinematics &kin,
                                  const SymmetricTensor<2, 3> &cauchy)
  {
    return kin.J * Tensor<2, 3>(cauchy) * transpose(kin.F_inv);
  }

  template <int dim>
  Tensor<4, dim> first_piola_tangent(const IncrementalKinematics &kin,
                                     const SymmetricTensor<2, 3> &stress_old,
                                     const MaterialResponse      &response)
  {
    const Tensor<2, 3> I          = unit_symmetric_tensor<3>();
    const Tensor<2, 3> sigma      = response.stress;
    const Tensor<2, 3> F_inv_T    = transpose(kin.F_inv);
    const Tensor<2, 3> sigma_FiT  = sigma * F_inv_T;
    const Tensor<2, 3> I_minus    = I - 0.5 * kin.dL;
    const Tensor<2, 3> one_plus_R = I + kin.rotation_increment;
    const Tensor<2, 3> sn_RT      = Tensor<2, 3>(stress_old) * transpose(kin.rotation_increment);

    const Tensor<2, 3> I_plus_Rh = I + kin.half_rotation;
    const Tensor<2, 3> Rh_T      = transpose(kin.half_rotation);
    const Tensor<2, 3> mid_Rh_T  = Tensor<2, 3>(kin.mid_strain) * Rh_T;

    Tensor<4, dim> A;
    // One directional derivative per unit direction δF = e_k ⊗ e_L; products
    // with δF are outer products of one column and one row.
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int L = 0; L < dim; ++L)
        {
          Tensor<2, 3> ddL; // (I − ½ΔL) e_k ⊗ e_L F½⁻¹
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              ddL[i][j] = I_minus[i][k] * kin.F_half_inv[L][j];
          const Tensor<2, 3> dspin = 0.5 * (ddL - transpose(ddL));
          // δ(R_h Δε R_hᵀ), R_h = (I − ¼Δω)⁻¹(I + ¼Δω): δR_h = ¼ A_h⁻¹ δΔω (I + R_h).
          const Tensor<2, 3> dRh = 0.25 * kin.A_half_inv * dspin * I_plus_Rh;
          const Tensor<2, 3> Y   = dRh * mid_Rh_T;
          const SymmetricTensor<2, 3> deps =
            symmetrize(kin.half_rotation * Tensor<2, 3>(symmetrize(ddL)) * Rh_T + Y +
                       transpose(Y));
          SymmetricTensor<2, 3> dsigma_sym = response.tangent * deps;

          // Rotation of the previous stress.
          const Tensor<2, 3> dR = 0.5 * kin.A_inv * dspin * one_plus_R;
          const Tensor<2, 3> X  = dR * sn_RT;
          const SymmetricTensor<2, 3> drot = symmetrize(X + transpose(X));
          if (response.sensitivity_is_identity)
            dsigma_sym += drot;
          else
            dsigma_sym += response.rotated_stress_sensitivity * drot;

          // tr(δF F⁻¹) = (F⁻¹)_Lk;  σF⁻ᵀ δFᵀ F⁻ᵀ = (σF⁻ᵀ e_L) ⊗ (F⁻ᵀ)_k·
          const double       trace_dF_Finv = kin.F_inv[L][k];
          const Tensor<2, 3> dsigma_FiT    = Tensor<2, 3>(dsigma_sym) * F_inv_T;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int J = 0; J < dim; ++J)
              A[i][J][k][L] = kin.J * (trace_dF_Finv * sigma_FiT[i][J] + dsigma_FiT[i][J] -
                                       sigma_FiT[i][L] * F_inv_T[k][J]);
        }
    return A;
  }

  template <int dim>
  Tensor<2, 3> embed(const Tensor<2, dim> &t, const double out_of_plane)
  {
    Tensor<2, 3> r;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        r[i][j] = t[i][j];
    for (unsigned int i = dim; i < 3; ++i)
      r[i][i] = out_of_plane;
    return r;
  }

  template Tensor<4, 2> first_piola_tangent<2>(const IncrementalKinematics &,
                                               const SymmetricTensor<2, 3> &,
                                               const MaterialResponse &);
  template Tensor<4, 3> first_piola_tangent<3>(const IncrementalKinematics &,
                                               const SymmetricTensor<2, 3> &,
                                               const MaterialResponse &);
  template Tensor<2, 3> embed<2>(const Tensor<2, 2> &, double);
  template Tensor<2, 3> embed<3>(const Tensor<2, 3> &, double);
} // namespace anvil
