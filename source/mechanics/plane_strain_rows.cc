// The Jaumann tangent δσ of the plane-strain kernel's four directions, on
// the rows and columns it reads (plane_strain_rows.h): planar_tangent.cc's
// operations on the raw components 00, 11, 01 only.
#include <anvil/material/planar_tangent.h>
#include <anvil/mechanics/plane_strain_rows.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    namespace
    {
      /// The raw components a plane-strain δσ has and A reads: 00, 11, 01.
      constexpr unsigned int rows[3] = {0, 1, 3};

      /**
       * The factored C (or S if @p SENSITIVITY) on rows × columns {00, 11,
       * 01}: factored_entry() (planar_tangent.h), as expand_rows() of
       * planar_tangent.cc, @p T[r][c] for raw rows[r], rows[c].
       */
      template <bool SENSITIVITY>
      void expand_in_plane(const FactoredTangent &f, double (&T)[3][3])
      {
        const double  nn = SENSITIVITY ? f.sensitivity_normal : f.normal;
        const double *r  = SENSITIVITY ? f.w : f.v;
        for (unsigned int ip = 0; ip < 3; ++ip)
          {
            const unsigned int p  = rows[ip];
            const double       fp = nn * f.n[p];
            for (unsigned int iq = 0; iq < 3; ++iq)
              T[ip][iq] = factored_entry<SENSITIVITY>(f, p, rows[iq], fp, r);
          }
      }

      /// Rows 0 and 1 of (I + Z) Y Zᵀ for a block-diagonal Y (planar_triple_product
      /// without its column 2, which only out-of-plane σₙ reads): the same sums.
      inline void triple_product_in_plane(const Tensor<2, 3> &Z, const SymmetricTensor<2, 3> &Y,
                                   double (&R)[2][2])
      {
        const double X[2][2] = {{1 + Z[0][0], 0 + Z[0][1]}, {0 + Z[1][0], 1 + Z[1][1]}};
        // Y's block by its raw entries 00, 11, 01 (SymmetricTensor's [i][j]
        // goes through accessor objects: most of this function's cost).
        const double *y    = Y.begin_raw();
        const double  B[2][2] = {{y[0], y[3]}, {y[3], y[1]}};
        double        XY[2][2];
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            XY[i][j] = X[i][0] * B[0][j] + X[i][1] * B[1][j];
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            R[i][j] = XY[i][0] * Z[j][0] + XY[i][1] * Z[j][1];
      }

      /// Four doubles, one per direction (k, L) = (0,0), (0,1), (1,0), (1,1).
      typedef double v4 __attribute__((vector_size(32)));

      /// The images of the directions' vectors that the sums read: lane d
      /// holds the scalar loop's value for direction d (a = a_k, b = b_L).
      struct Images
      {
        v4 Ah[2], pm[2], Rh[2], A[2], qs[2];
      };

      /**
       * The rows for the four directions at once, lane d the scalar loop's
       * operations for direction d, in its order (no FMA in either clone):
       * the same bits. @p S null: the sensitivity is the identity.
       */
      __attribute__((target_clones("avx2", "default"))) void
      direction_rows(const IncrementalKinematics &kin, const double (&PM)[2][2],
                     const double (&QS)[2][2], const double (&C)[3][3], const double (*S)[3],
                     SymmetricTensor<2, 3> *dsigma)
      {
        const Tensor<2, 3> &Rh = kin.half_rotation, &Ah = kin.A_half_inv, &A = kin.A_inv;
        // a_k = (I − ½ΔL) e_k over the lanes' k, b_L = F½⁻ᵀ e_L over their L.
        const double a00 = 1. - 0.5 * kin.dL[0][0], a01 = 0. - 0.5 * kin.dL[1][0],
                     a10 = 0. - 0.5 * kin.dL[0][1], a11 = 1. - 0.5 * kin.dL[1][1];
        const Tensor<2, 3> &Fh = kin.F_half_inv;
        const v4 v0[2] = {{a00, a00, a10, a10}, {Fh[0][0], Fh[1][0], Fh[0][0], Fh[1][0]}},
                 v1[2] = {{a01, a01, a11, a11}, {Fh[0][1], Fh[1][1], Fh[0][1], Fh[1][1]}};
        Images ab[2];
        for (unsigned int x = 0; x < 2; ++x)
          for (unsigned int i = 0; i < 2; ++i)
            {
              Images &m = ab[x];
              m.Ah[i]   = Ah[i][0] * v0[x] + Ah[i][1] * v1[x];
              m.Rh[i]   = Rh[i][0] * v0[x] + Rh[i][1] * v1[x];
              m.A[i]    = A[i][0] * v0[x] + A[i][1] * v1[x];
              m.pm[i]   = PM[0][i] * v0[x] + PM[1][i] * v1[x];
              m.qs[i]   = QS[0][i] * v0[x] + QS[1][i] * v1[x];
            }
        const Images &a = ab[0], &b = ab[1];
        // (i, j) of the raw components 00, 11, 01.
        constexpr unsigned int ri[3] = {0, 1, 0}, rj[3] = {0, 1, 1};
        v4                     deps[3], drot[3];
        for (unsigned int c = 0; c < 3; ++c)
          {
            const unsigned int i = ri[c], j = rj[c];
            const v4           y_ij = a.Ah[i] * b.pm[j] - b.Ah[i] * a.pm[j];
            const v4           y_ji = a.Ah[j] * b.pm[i] - b.Ah[j] * a.pm[i];
            deps[c] = 0.5 * (a.Rh[i] * b.Rh[j] + b.Rh[i] * a.Rh[j]) + 0.125 * (y_ij + y_ji);
            const v4 x_ij = a.A[i] * b.qs[j] - b.A[i] * a.qs[j];
            const v4 x_ji = a.A[j] * b.qs[i] - b.A[j] * a.qs[i];
            drot[c]       = 0.25 * (x_ij + x_ji);
          }
        // The shear weight 2 on the 01 component (deal.II's contraction).
        const v4 dw[3] = {deps[0], deps[1], deps[2] * 2.};
        v4       out[3];
        if (!S)
          for (unsigned int r = 0; r < 3; ++r)
            {
              // add_contraction()'s sum from 0, added to δσ = 0, then + δσ̃: the same bits.
              v4 v = {0, 0, 0, 0};
              v += C[r][0] * dw[0];
              v += C[r][1] * dw[1];
              v += C[r][2] * dw[2];
              v4 sr = {0, 0, 0, 0};
              sr += v;
              out[r] = sr + drot[r];
            }
        else
          {
            const v4 ew[3] = {drot[0], drot[1], drot[2] * 2.};
            for (unsigned int r = 0; r < 3; ++r)
              {
                const v4 vc = C[r][0] * dw[0] + C[r][1] * dw[1] + C[r][2] * dw[2];
                const v4 vs = S[r][0] * ew[0] + S[r][1] * ew[1] + S[r][2] * ew[2];
                out[r]      = vc + vs;
              }
          }
        for (unsigned int d = 0; d < 4; ++d)
          {
            double *s = dsigma[d].begin_raw();
            s[0]      = out[0][d];
            s[1]      = out[1][d];
            s[2]      = 0;
            s[3]      = out[2][d];
          }
      }
    } // namespace

    bool plane_strain_tangent_rows(const IncrementalKinematics &kin,
                                   const SymmetricTensor<2, 3> &stress_old,
                                   const MaterialResponse      &response,
                                   const TangentDirections     &directions,
                                   SymmetricTensor<2, 3>       *dsigma)
    {
      const FactoredTangent &f = response.factored;
      if (!f.active || stress_old[0][2] != 0 || stress_old[1][2] != 0 || directions.n != 4)
        return false;
      for (unsigned int d = 0; d < 4; ++d)
        if (directions.kl[d].first != d / 2 || directions.kl[d].second != d % 2)
          return false;
      // PM = (I + R_h) Δε_mid R_hᵀ, QS = (I + ΔR) σ_n ΔRᵀ: their in-plane blocks.
      double PM[2][2], QS[2][2];
      triple_product_in_plane(kin.half_rotation, kin.mid_strain, PM);
      triple_product_in_plane(kin.rotation_increment, stress_old, QS);
      double C[3][3], S[3][3];
      expand_in_plane<false>(f, C);
      const bool identity = response.sensitivity_is_identity;
      if (!identity)
        expand_in_plane<true>(f, S);
      direction_rows(kin, PM, QS, C, identity ? nullptr : S, dsigma);
      return true;
    }
  } // namespace MechanicsAssembly
} // namespace anvil
