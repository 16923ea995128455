// cauchy_tangent (kinematics.h) for Jaumann kinematics of the plane-strain /
// axisymmetric form F = [F_2x2, 0; 0, F₃₃] (IncrementalKinematics::planar).
#include <anvil/material/kinematics.h>
#include <anvil/material/planar_tangent.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// σ += T : d on raw storage, rows 0..N_ROWS, for a d whose nonzero raw
    /// components are @p comps (deal.II's contraction: shear components count twice).
    template <unsigned int N_ROWS, unsigned int n>
    void add_contraction(const double *t, const double (&d)[6], const unsigned int (&comps)[n],
                         SymmetricTensor<2, 3> &sigma)
    {
      // The shear weight 2 on d once, not per row (× 2 is exact: the same sums).
      double dw[n];
      for (unsigned int i = 0; i < n; ++i)
        dw[i] = d[comps[i]] * (comps[i] < 3 ? 1. : 2.);
      double *s = sigma.begin_raw();
      for (unsigned int p = 0; p < N_ROWS; ++p)
        {
          double v = 0;
          for (unsigned int i = 0; i < n; ++i)
            v += t[6 * p + comps[i]] * dw[i];
          s[p] += v;
        }
    }

    /**
     * The entries (p < N_ROWS, q in @p cols) of the factored C (or S if
     * @p SENSITIVITY) on 6x6 raw storage @p T, the others left as they are:
     * the planar contractions read no more, so a point builds these 16 to
     * 24 entries instead of the material writing 72.
     */
    template <unsigned int N_ROWS, bool SENSITIVITY, unsigned int n>
    void expand_rows(const FactoredTangent &f, const unsigned int (&cols)[n], double *T)
    {
      const double  nn = SENSITIVITY ? f.sensitivity_normal : f.normal;
      const double *r  = SENSITIVITY ? f.w : f.v;
      for (unsigned int p = 0; p < N_ROWS; ++p)
        {
          const double fp = nn * f.n[p];
          for (unsigned int i = 0; i < n; ++i)
            T[6 * p + cols[i]] = factored_entry<SENSITIVITY>(f, p, cols[i], fp, r);
        }
    }

    /**
     * σ = C : d + S : e (σ zero before, d and e in-plane: raw 0, 1, 3) in one
     * pass over the rows, the sums of two add_contraction() calls: the same bits.
     */
    template <unsigned int N_ROWS>
    void add_two_contractions(const double *c, const double (&d)[6], const double *t,
                              const double (&e)[6], double *s)
    {
      const double dw[3] = {d[0], d[1], d[3] * 2.}, ew[3] = {e[0], e[1], e[3] * 2.};
      for (unsigned int p = 0; p < N_ROWS; ++p)
        {
          const double vc = c[6 * p] * dw[0] + c[6 * p + 1] * dw[1] + c[6 * p + 3] * dw[2];
          const double vs = t[6 * p] * ew[0] + t[6 * p + 1] * ew[1] + t[6 * p + 3] * ew[2];
          s[p] = vc + vs;
        }
    }

    /**
     * (I + Z) Y Zᵀ of tensors of the form [2x2, 0; 0, (2,2)] except that Y may
     * have the entries 02, 12 (Y symmetric): rows 0 and 1 of the product, as
     * deal.II's Tensor products sum them (the first term, then the others in
     * order), with the products of zero entries left out: the same bits.
     */
    void planar_triple_product(const Tensor<2, 3> &Z, const SymmetricTensor<2, 3> &Y,
                               const bool y_out_of_plane, double (&R)[2][3])
    {
      // X = I + Z: its 2x2 block as the Tensor sum gives it.
      const double X[2][2] = {{1 + Z[0][0], 0 + Z[0][1]}, {0 + Z[1][0], 1 + Z[1][1]}};
      double       XY[2][3];
      #pragma GCC unroll 2
      for (unsigned int i = 0; i < 2; ++i)
        {
          for (unsigned int j = 0; j < 2; ++j)
            XY[i][j] = X[i][0] * Y[0][j] + X[i][1] * Y[1][j];
          XY[i][2] = y_out_of_plane ? X[i][0] * Y[0][2] + X[i][1] * Y[1][2] : 0.;
        }
      #pragma GCC unroll 2
      for (unsigned int i = 0; i < 2; ++i)
        {
          for (unsigned int j = 0; j < 2; ++j)
            R[i][j] = XY[i][0] * Z[j][0] + XY[i][1] * Z[j][1];
          R[i][2] = XY[i][2] * Z[2][2];
        }
    }

    /// planar_cauchy_tangent's δσ, raw components 0..N_ROWS (00, 11, 22, 01[, 02, 12]).
    template <unsigned int N_ROWS>
    void planar_tangent_rows(const IncrementalKinematics &kin,
                             const SymmetricTensor<2, 3> &stress_old,
                             const MaterialResponse      &response,
                             const TangentDirections     &directions,
                             SymmetricTensor<2, 3>       *dsigma)
    {
      // The general cauchy_tangent's outer products with every vector in the
      // plane (a = (I − ½ΔL) e_k, b = F½⁻ᵀ e_L for k, L < 2): δΔε has only the
      // in-plane components, δσ̃ also 02 and 12 if σ_n has them (QS = (I + ΔR)
      // σ_n ΔRᵀ is then not block-diagonal). The hoop direction (2, 2) has
      // a ∥ b ∥ e₂: δΔε = (1 − ½ΔL₂₂)(F½⁻¹)₂₂ e₂⊗e₂ and δσ̃ = 0.
      const Tensor<2, 3> &Rh = kin.half_rotation, &Ah = kin.A_half_inv, &A = kin.A_inv;
      const bool          out_of_plane = stress_old[0][2] != 0 || stress_old[1][2] != 0;
      // PM = (I + R_h) Δε_mid R_hᵀ (block-diagonal), QS = (I + ΔR) σ_n ΔRᵀ: their rows 0, 1.
      double PM[2][3], QS[2][3];
      planar_triple_product(Rh, kin.mid_strain, false, PM);
      planar_triple_product(kin.rotation_increment, stress_old, out_of_plane, QS);

      struct Images
      {
        double Ah[2], pm[2], Rh[2], A[2], qs[3];
      };
      auto images = [&](const double v0, const double v1) {
        Images m;
        #pragma GCC unroll 2
        for (unsigned int i = 0; i < 2; ++i)
          {
            m.Ah[i] = Ah[i][0] * v0 + Ah[i][1] * v1;
            m.Rh[i] = Rh[i][0] * v0 + Rh[i][1] * v1;
            m.A[i]  = A[i][0] * v0 + A[i][1] * v1;
            m.pm[i] = PM[0][i] * v0 + PM[1][i] * v1;
          }
        #pragma GCC unroll 3
        for (unsigned int j = 0; j < 3; ++j)
          m.qs[j] = QS[0][j] * v0 + QS[1][j] * v1;
        return m;
      };
      Images a_img[2], b_img[2];
      #pragma GCC unroll 2
      for (unsigned int k = 0; k < 2; ++k)
        {
          a_img[k] = images((k == 0 ? 1. : 0.) - 0.5 * kin.dL[0][k],
                            (k == 1 ? 1. : 0.) - 0.5 * kin.dL[1][k]);
          b_img[k] = images(kin.F_half_inv[k][0], kin.F_half_inv[k][1]);
        }
      static constexpr unsigned int in_plane[3] = {0, 1, 3}, with_shear[5] = {0, 1, 3, 4, 5},
                                    hoop[1]     = {2};
      // The material's C and S: dense, or the entries the rows below read
      // from the factored form (C: columns 00, 11, 22, 01; S: 00, 11, 01 and
      // 02, 12 with out-of-plane σₙ).
      const double *C = response.tangent.begin_raw(), *S = response.rotated_stress_sensitivity.begin_raw();
      double        C_rows[6 * N_ROWS], S_rows[6 * N_ROWS];
      if (const FactoredTangent &f = response.factored; f.active)
        {
          static constexpr unsigned int c_cols[4] = {0, 1, 2, 3};
          expand_rows<N_ROWS, false>(f, c_cols, C_rows);
          C = C_rows;
          if (!response.sensitivity_is_identity)
            {
              if (out_of_plane)
                expand_rows<N_ROWS, true>(f, with_shear, S_rows);
              else
                expand_rows<N_ROWS, true>(f, in_plane, S_rows);
              S = S_rows;
            }
        }
      for (unsigned int d = 0; d < directions.n; ++d)
        {
          const unsigned int k = directions.kl[d].first, L = directions.kl[d].second;
          double             deps[6] = {0, 0, 0, 0, 0, 0}, drot[6] = {0, 0, 0, 0, 0, 0};
          double            *s       = dsigma[d].begin_raw();
          for (unsigned int c = 0; c < N_ROWS; ++c)
            s[c] = 0;
          if (k == 2 && L == 2)
            {
              deps[2] = (1 - 0.5 * kin.dL[2][2]) * kin.F_half_inv[2][2];
              add_contraction<N_ROWS>(C, deps, hoop, dsigma[d]);
              continue;
            }
          const Images &a = a_img[k], &b = b_img[L];
          // Raw order 00, 11, 22, 01, 02, 12; (i, j) of the in-plane ones.
          static constexpr unsigned int ri[3] = {0, 1, 0}, rj[3] = {0, 1, 1}, raw[3] = {0, 1, 3};
          #pragma GCC unroll 3
          for (unsigned int c = 0; c < 3; ++c)
            {
              const unsigned int i = ri[c], j = rj[c];
              const double       y_ij = a.Ah[i] * b.pm[j] - b.Ah[i] * a.pm[j];
              const double       y_ji = a.Ah[j] * b.pm[i] - b.Ah[j] * a.pm[i];
              deps[raw[c]] = 0.5 * (a.Rh[i] * b.Rh[j] + b.Rh[i] * a.Rh[j]) + 0.125 * (y_ij + y_ji);
              const double x_ij = a.A[i] * b.qs[j] - b.A[i] * a.qs[j];
              const double x_ji = a.A[j] * b.qs[i] - b.A[j] * a.qs[i];
              drot[raw[c]]      = 0.25 * (x_ij + x_ji);
            }
          if (out_of_plane)
            #pragma GCC unroll 2
            for (unsigned int i = 0; i < 2; ++i) // (i, 2): x_2i = 0 (a, b in the plane)
              drot[4 + i] = 0.25 * (a.A[i] * b.qs[2] - b.A[i] * a.qs[2]);
          if (response.sensitivity_is_identity)
            {
              add_contraction<N_ROWS>(C, deps, in_plane, dsigma[d]);
              for (unsigned int c = 0; c < N_ROWS; ++c)
                s[c] += drot[c];
            }
          else if (out_of_plane)
            {
              add_contraction<N_ROWS>(C, deps, in_plane, dsigma[d]);
              add_contraction<N_ROWS>(S, drot, with_shear, dsigma[d]);
            }
          else
            add_two_contractions<N_ROWS>(C, deps, S, drot, s);
        }
    }
  } // namespace

  void planar_cauchy_tangent(const IncrementalKinematics &kin,
                             const SymmetricTensor<2, 3> &stress_old,
                             const MaterialResponse      &response,
                             const TangentDirections     &directions,
                             SymmetricTensor<2, 3>       *dsigma)
  {
    planar_tangent_rows<6>(kin, stress_old, response, directions, dsigma);
  }

  void planar_cauchy_tangent_in_plane(const IncrementalKinematics &kin,
                                      const SymmetricTensor<2, 3> &stress_old,
                                      const MaterialResponse      &response,
                                      const TangentDirections     &directions,
                                      SymmetricTensor<2, 3>       *dsigma)
  {
    planar_tangent_rows<4>(kin, stress_old, response, directions, dsigma);
  }
} // namespace anvil
