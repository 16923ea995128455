#include <anvil/core/instantiate.h>
#include <anvil/material/kinematics.h>

#include <array>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// F = [F_2x2 0; 0 F₃₃]: plane strain and axisymmetric gradients.
    bool is_planar(const Tensor<2, 3> &F)
    {
      return F[0][2] == 0 && F[1][2] == 0 && F[2][0] == 0 && F[2][1] == 0;
    }

    /**
     * For a skew h with axial vector w, |w|² = h₀₁² + h₀₂² + h₁₂²:
     *   (I − h)⁻¹ = I + g,  (I − h)⁻¹(I + h) = I + 2g,  g = (h + h²)/(1 + |w|²)
     * (h³ = −|w|² h), the closed forms of the Cayley transforms below.
     */
    Tensor<2, 3> cayley_part(const Tensor<2, 3> &h)
    {
      const double w2 = h[0][1] * h[0][1] + h[0][2] * h[0][2] + h[1][2] * h[1][2];
      return (1 / (1 + w2)) * (h + h * h);
    }
  } // namespace

  void IncrementalKinematics::reinit(const Tensor<2, 3> &F_new, const Tensor<2, 3> &F_old_in,
                                     const ObjectiveRate rate_in, const unsigned int what)
  {
    rate   = rate_in;
    F      = F_new;
    F_old  = F_old_in;
    planar = false;
    if (rate == ObjectiveRate::jaumann && (what & kinematics_planar_path) && is_planar(F) &&
        is_planar(F_old))
      return reinit_planar(what);
    off_block_zero = false;
    if (what & kinematics_inverse)
      {
        J     = determinant(F);
        F_inv = invert(F);
      }
    F_half_inv = invert(0.5 * (F + F_old));
    dL         = (F - F_old) * F_half_inv;
    const Tensor<2, 3> I         = unit_symmetric_tensor<3>();
    mid_strain                   = symmetrize(dL);
    if (rate == ObjectiveRate::jaumann)
      {
        // ½Δω = ½ skew ΔL: ΔR and R_h by the closed-form Cayley transforms.
        const Tensor<2, 3> half_spin = 0.25 * (dL - transpose(dL));
        const Tensor<2, 3> g = cayley_part(half_spin), g_half = cayley_part(0.5 * half_spin);
        rotation_increment = I + 2 * g;
        half_rotation      = I + 2 * g_half;
        if (what & kinematics_tangent)
          {
            A_inv      = I + g;
            A_half_inv = I + g_half;
          }
        strain_increment =
          symmetrize(half_rotation * Tensor<2, 3>(mid_strain) * transpose(half_rotation));
        return;
      }
    if (rate == ObjectiveRate::green_naghdi)
      {
        // ΔR = R_n+1 R_nᵀ, R_h = R_n+1 R_½ᵀ (polar rotations; A_inv, A_half_inv unused).
        const Tensor<2, 3> R = polar_rotation(F);
        rotation_increment   = R * transpose(polar_rotation(F_old));
        half_rotation        = R * transpose(polar_rotation(0.5 * (F + F_old)));
        strain_increment =
          symmetrize(half_rotation * Tensor<2, 3>(mid_strain) * transpose(half_rotation));
        return;
      }
    // ½Δω: the log spin (logarithmic_rate.cc).
    const Tensor<2, 3> half_spin =
      Tensor<2, 3>(0.5 * logarithmic_spin_increment(0.5 * (F + F_old), dL));
    A_inv                        = invert(I - half_spin);
    rotation_increment           = A_inv * (I + half_spin);
    // The strain increment lives on the mid-point configuration: rotate it
    // forward by half the step (Cayley transform of ¼Δω) so that the update
    // is second-order accurate for the Jaumann rate, not only first.
    A_half_inv                   = invert(I - 0.5 * half_spin);
    half_rotation                = A_half_inv * (I + 0.5 * half_spin);
    strain_increment =
      symmetrize(half_rotation * Tensor<2, 3>(mid_strain) * transpose(half_rotation));
  }

  void IncrementalKinematics::reinit_planar(const unsigned int what)
  {
    planar = true;
    // Every tensor is [2x2 block, 0; 0, (2,2)]: the spin has the one
    // component s = h₀₁ of ½Δω, and the Cayley transforms are plane rotations,
    // (I − h)⁻¹ = I + g with g₀₀ = g₁₁ = −s²/(1 + s²), g₀₁ = −g₁₀ = s/(1 + s²).
    // Only the block entries are written: the others are zeroed once, and stay
    // zero while the planar path alone writes (off_block_zero).
    if (!off_block_zero)
      {
        for (Tensor<2, 3> *T : {&F_inv, &F_half_inv, &dL, &A_inv, &A_half_inv, &half_rotation,
                                &rotation_increment})
          *T = Tensor<2, 3>();
        mid_strain = strain_increment = SymmetricTensor<2, 3>();
        off_block_zero                 = true;
      }
    {
      // (½(F + F_n))⁻¹ on the block's entries.
      const double H00 = 0.5 * (F[0][0] + F_old[0][0]), H01 = 0.5 * (F[0][1] + F_old[0][1]);
      const double H10 = 0.5 * (F[1][0] + F_old[1][0]), H11 = 0.5 * (F[1][1] + F_old[1][1]);
      const double H22 = 0.5 * (F[2][2] + F_old[2][2]);
      const double d   = H00 * H11 - H01 * H10;
      F_half_inv[0][0] = H11 / d;
      F_half_inv[0][1] = -H01 / d;
      F_half_inv[1][0] = -H10 / d;
      F_half_inv[1][1] = H00 / d;
      F_half_inv[2][2] = 1 / H22;
    }
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        dL[i][j] = (F[i][0] - F_old[i][0]) * F_half_inv[0][j] +
                   (F[i][1] - F_old[i][1]) * F_half_inv[1][j];
    dL[2][2] = (F[2][2] - F_old[2][2]) * F_half_inv[2][2];
    if (what & kinematics_inverse)
      {
        J              = (F[0][0] * F[1][1] - F[0][1] * F[1][0]) * F[2][2];
        const double d = F[0][0] * F[1][1] - F[0][1] * F[1][0];
        F_inv[0][0]    = F[1][1] / d;
        F_inv[0][1]    = -F[0][1] / d;
        F_inv[1][0]    = -F[1][0] / d;
        F_inv[1][1]    = F[0][0] / d;
        F_inv[2][2]    = 1 / F[2][2];
      }
    const double s = 0.25 * (dL[0][1] - dL[1][0]);
    // I + c g: c = 1 the inverse, c = 2 the rotation (cayley_part()).
    auto plane = [](Tensor<2, 3> &T, const double s, const double c) {
      const double w = 1 / (1 + s * s);
      T[0][0] = T[1][1] = 1 - c * s * s * w;
      T[0][1]           = c * s * w;
      T[1][0]           = -c * s * w;
      T[2][2]           = 1;
    };
    plane(rotation_increment, s, 2);
    plane(half_rotation, 0.5 * s, 2);
    if (what & kinematics_tangent)
      {
        plane(A_inv, s, 1);
        plane(A_half_inv, 0.5 * s, 1);
      }
    mid_strain[0][0] = dL[0][0];
    mid_strain[1][1] = dL[1][1];
    mid_strain[0][1] = 0.5 * (dL[0][1] + dL[1][0]);
    mid_strain[2][2] = dL[2][2];
    // R_h Δε_mid R_hᵀ on the 2x2 block.
    const Tensor<2, 3> &Q = half_rotation;
    double              M[2][2];
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int l = 0; l < 2; ++l)
        M[i][l] = Q[i][0] * mid_strain[0][l] + Q[i][1] * mid_strain[1][l];
    strain_increment[0][0] = M[0][0] * Q[0][0] + M[0][1] * Q[0][1];
    strain_increment[1][1] = M[1][0] * Q[1][0] + M[1][1] * Q[1][1];
    strain_increment[0][1] =
      0.5 * ((M[0][0] * Q[1][0] + M[0][1] * Q[1][1]) + (M[1][0] * Q[0][0] + M[1][1] * Q[0][1]));
    strain_increment[2][2] = mid_strain[2][2];
  }

  Tensor<2, 3> first_piola_stress(const IncrementalKinematics &kin,
                                  const SymmetricTensor<2, 3> &cauchy)
  {
    return kin.J * Tensor<2, 3>(cauchy) * transpose(kin.F_inv);
  }

  void cauchy_tangent(const IncrementalKinematics &kin,
                      const SymmetricTensor<2, 3> &stress_old,
                      const MaterialResponse      &response,
                      const TangentDirections     &directions,
                      SymmetricTensor<2, 3>       *dsigma)
  {
    if (kin.rate != ObjectiveRate::jaumann)
      return rate_cauchy_tangent(kin, stress_old, response, directions, dsigma);
    bool in_plane_directions = kin.planar;
    for (unsigned int d = 0; d < directions.n; ++d)
      if ((directions.kl[d].first == 2) != (directions.kl[d].second == 2))
        in_plane_directions = false;
    if (in_plane_directions)
      return planar_cauchy_tangent(kin, stress_old, response, directions, dsigma);
    const Tensor<2, 3> I          = unit_symmetric_tensor<3>();
    const Tensor<2, 3> I_minus    = I - 0.5 * kin.dL;
    const Tensor<2, 3> one_plus_R = I + kin.rotation_increment;
    const Tensor<2, 3> sn_RT      = Tensor<2, 3>(stress_old) * transpose(kin.rotation_increment);
    const Tensor<2, 3> I_plus_Rh  = I + kin.half_rotation;
    const Tensor<2, 3> mid_Rh_T   = Tensor<2, 3>(kin.mid_strain) * transpose(kin.half_rotation);
    const Tensor<2, 3> PM         = I_plus_Rh * mid_Rh_T;
    const Tensor<2, 3> QS         = one_plus_R * sn_RT;

    // δF = e_k ⊗ e_L gives δΔL = a ⊗ b with a = (I − ½ΔL) e_k, b = F½⁻ᵀ e_L, so
    // every product below is a sum of outer products of vectors computed once:
    //   R_h sym(δΔL) R_hᵀ = ½[(R_h a)⊗(R_h b) + (R_h b)⊗(R_h a)]
    //   δR_h Δε_mid R_hᵀ  = ⅛[(A_h a)⊗(PMᵀ b) − (A_h b)⊗(PMᵀ a)],  PM = (I + R_h) Δε_mid R_hᵀ
    //   δΔR σₙ ΔRᵀ        = ¼[(A a)⊗(QSᵀ b) − (A b)⊗(QSᵀ a)],      QS = (I + ΔR) σₙ ΔRᵀ
    struct Images
    {
      Tensor<1, 3> Ah, pm, Rh, A, qs;
    };
    std::array<Images, 3> a_img, b_img;
    std::array<bool, 3>   have_a{{false, false, false}}, have_b{{false, false, false}};
    auto images = [&](const Tensor<1, 3> &v) {
      return Images{kin.A_half_inv * v, transpose(PM) * v, kin.half_rotation * v, kin.A_inv * v,
                    transpose(QS) * v};
    };
    for (unsigned int d = 0; d < directions.n; ++d)
      {
        const unsigned int k = directions.kl[d].first, L = directions.kl[d].second;
        if (!have_a[k])
          {
            Tensor<1, 3> a;
            for (unsigned int i = 0; i < 3; ++i)
              a[i] = I_minus[i][k];
            a_img[k]  = images(a);
            have_a[k] = true;
          }
        if (!have_b[L])
          {
            Tensor<1, 3> b;
            for (unsigned int i = 0; i < 3; ++i)
              b[i] = kin.F_half_inv[L][i];
            b_img[L]  = images(b);
            have_b[L] = true;
          }
        const Images         &a = a_img[k], &b = b_img[L];
        SymmetricTensor<2, 3> deps, drot;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              const double y_ij = a.Ah[i] * b.pm[j] - b.Ah[i] * a.pm[j];
              const double y_ji = a.Ah[j] * b.pm[i] - b.Ah[j] * a.pm[i];
              deps[i][j] = 0.5 * (a.Rh[i] * b.Rh[j] + b.Rh[i] * a.Rh[j]) + 0.125 * (y_ij + y_ji);
              const double x_ij = a.A[i] * b.qs[j] - b.A[i] * a.qs[j];
              const double x_ji = a.A[j] * b.qs[i] - b.A[j] * a.qs[i];
              drot[i][j] = 0.25 * (x_ij + x_ji);
            }
        dsigma[d] = contract_material_tangent(response, deps, drot);
      }
  }

  TangentDirections TangentDirections::in_plane(const unsigned int dim, const bool hoop)
  {
    TangentDirections t;
    for (unsigned int k = 0; k < dim; ++k)
      for (unsigned int L = 0; L < dim; ++L)
        t.kl[t.n++] = {k, L};
    if (hoop)
      t.kl[t.n++] = {2, 2};
    return t;
  }

  template <int dim>
  Tensor<4, dim> first_piola_tangent(const IncrementalKinematics &kin,
                                     const SymmetricTensor<2, 3> &stress_old,
                                     const MaterialResponse      &response)
  {
    const TangentDirections directions = TangentDirections::in_plane(dim, false);
    std::array<SymmetricTensor<2, 3>, 9> dsigma;
    cauchy_tangent(kin, stress_old, response, directions, dsigma.data());

    const Tensor<2, 3> F_inv_T   = transpose(kin.F_inv);
    const Tensor<2, 3> sigma_FiT = Tensor<2, 3>(response.stress) * F_inv_T;
    Tensor<4, dim>     A;
    for (unsigned int d = 0; d < directions.n; ++d)
      {
        const unsigned int k = directions.kl[d].first, L = directions.kl[d].second;
        // δP = J [tr(δF F⁻¹) σF⁻ᵀ + δσ F⁻ᵀ − σF⁻ᵀ δFᵀ F⁻ᵀ], tr(δF F⁻¹) = (F⁻¹)_Lk.
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int J = 0; J < dim; ++J)
            {
              double ds_FiT = 0;
              for (unsigned int m = 0; m < 3; ++m)
                ds_FiT += dsigma[d][i][m] * F_inv_T[m][J];
              A[i][J][k][L] = kin.J * (kin.F_inv[L][k] * sigma_FiT[i][J] + ds_FiT -
                                       sigma_FiT[i][L] * F_inv_T[k][J]);
            }
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

#define INSTANTIATE(dim)                                                                           \
  template Tensor<4, dim> first_piola_tangent<dim>(const IncrementalKinematics &,                 \
                                                   const SymmetricTensor<2, 3> &,                 \
                                                   const MaterialResponse &);                     \
  template Tensor<2, 3> embed<dim>(const Tensor<2, dim> &, double);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
