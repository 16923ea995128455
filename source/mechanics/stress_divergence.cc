// The stress divergence ∫ P : ∇_X δv dV and its exact linearisation, for
// plane strain, axisymmetric and 3D elements, standard or F-bar
// (assembly_kernels.h, doc/mechanics.md).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/material/planar_tangent.h>
#include <anvil/mechanics/assembly_kernels.h>
#include <anvil/mechanics/plane_strain_rows.h>

#include <algorithm>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    namespace
    {
      /**
       * K += G (A Gᵀ + T0 ⊗ tr) w, i.e. K_ab += G_a : AG_b with
       * AG_b = (A : G_b + T0 tr_b) w, on dense arrays: @p Gt is Gᵀ
       * (n_dir x n_dofs), @p K row-major n_dofs x n_dofs; @p tr null without
       * F-bar. Every sum adds its nonzero terms in the order of the
       * directions, as the sparse G_a did: the same bits. A zero G_ac (the
       * other components' directions) is skipped, which changes no sum.
       * N_DIR, N_DOFS: the sizes at compile time, so that the work arrays
       * live on the stack and the loops over b vectorise.
       */
      template <unsigned int N_DIR, unsigned int N_DOFS>
      void add_dense_tangent(const std::array<std::array<double, 9>, 9> &A,
                             const double *__restrict Gt_in, const double *__restrict T0,
                             const double *__restrict tr, const double w, double *__restrict K)
      {
        double Gt[N_DIR][N_DOFS], AG[N_DIR][N_DOFS];
        for (unsigned int d = 0; d < N_DIR; ++d)
          for (unsigned int b = 0; b < N_DOFS; ++b)
            Gt[d][b] = Gt_in[d * N_DOFS + b];
        for (unsigned int c = 0; c < N_DIR; ++c)
          {
            double s[N_DOFS] = {};
            for (unsigned int d = 0; d < N_DIR; ++d)
              {
                const double Acd = A[c][d];
                for (unsigned int b = 0; b < N_DOFS; ++b)
                  s[b] += Acd * Gt[d][b];
              }
            if (tr)
              for (unsigned int b = 0; b < N_DOFS; ++b)
                s[b] += T0[c] * tr[b];
            for (unsigned int b = 0; b < N_DOFS; ++b)
              AG[c][b] = s[b] * w;
          }
        for (unsigned int a = 0; a < N_DOFS; ++a)
          {
            double s[N_DOFS] = {};
            for (unsigned int c = 0; c < N_DIR; ++c)
              if (const double Gac = Gt[c][a]; Gac != 0)
                for (unsigned int b = 0; b < N_DOFS; ++b)
                  s[b] += Gac * AG[c][b];
            for (unsigned int b = 0; b < N_DOFS; ++b)
              K[a * N_DOFS + b] += s[b];
          }
      }

      /// add_dense_tangent for sizes known at run time only (@p AGt: n_dir + 1 rows).
      void add_dense_tangent(const unsigned int n_dir, const unsigned int n_dofs,
                             const std::array<std::array<double, 9>, 9> &A, const double *Gt,
                             const double *T0, const double *tr, const double w, double *AGt,
                             double *K)
      {
        for (unsigned int c = 0; c < n_dir; ++c)
          {
            double *ag = AGt + c * n_dofs;
            for (unsigned int b = 0; b < n_dofs; ++b)
              ag[b] = 0;
            for (unsigned int d = 0; d < n_dir; ++d)
              for (unsigned int b = 0; b < n_dofs; ++b)
                ag[b] += A[c][d] * Gt[d * n_dofs + b];
            if (tr)
              for (unsigned int b = 0; b < n_dofs; ++b)
                ag[b] += T0[c] * tr[b];
            for (unsigned int b = 0; b < n_dofs; ++b)
              ag[b] *= w;
          }
        double *s = AGt + n_dir * n_dofs;
        for (unsigned int a = 0; a < n_dofs; ++a)
          {
            for (unsigned int b = 0; b < n_dofs; ++b)
              s[b] = 0;
            for (unsigned int c = 0; c < n_dir; ++c)
              if (const double Gac = Gt[c * n_dofs + a]; Gac != 0)
                for (unsigned int b = 0; b < n_dofs; ++b)
                  s[b] += Gac * AGt[c * n_dofs + b];
            for (unsigned int b = 0; b < n_dofs; ++b)
              K[a * n_dofs + b] += s[b];
          }
      }

      /**
       * The planar kernel's quantities of one point: F⁻¹ of a true F = [F_2x2,
       * 0; 0, F₃₃] and σF⁻ᵀ. F⁻¹ is deal.II's invert() without its products
       * of zeros, σF⁻ᵀ the Tensor product's sums without their zero terms
       * ((F⁻¹)_J2 = 0 for J < 2): the same bits as the general loop.
       */
      struct PlanarPoint
      {
        double Fi[3][3], sFiT[3][3]; // sFiT: the entries (i, J < 2) and (2, 2) only

        PlanarPoint(const Tensor<2, 3> &F, const SymmetricTensor<2, 3> &sigma)
        {
          const double r00 = F[1][1] * F[2][2], r01 = -(F[0][1] * F[2][2]),
                       r10 = -(F[1][0] * F[2][2]), r11 = F[0][0] * F[2][2],
                       r22 = F[0][0] * F[1][1] - F[0][1] * F[1][0];
          const double inv = 1.0 / (F[0][0] * r00 + F[0][1] * r10);
          Fi[0][0] = r00 * inv, Fi[0][1] = r01 * inv, Fi[0][2] = 0;
          Fi[1][0] = r10 * inv, Fi[1][1] = r11 * inv, Fi[1][2] = 0;
          Fi[2][0] = 0, Fi[2][1] = 0, Fi[2][2] = r22 * inv;
          // σ's entries by raw index (00, 11, 22, 01): SymmetricTensor's
          // [i][j] goes through accessor objects.
          const double *sr     = sigma.begin_raw();
          const double  s[2][2] = {{sr[0], sr[3]}, {sr[3], sr[1]}};
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int J = 0; J < 2; ++J)
              sFiT[i][J] = s[i][0] * Fi[J][0] + s[i][1] * Fi[J][1];
          sFiT[2][2] = sr[2] * Fi[2][2];
          sFiT[0][2] = sFiT[1][2] = sFiT[2][0] = sFiT[2][1] = 0; // enter A times (F⁻¹)_J2 = 0
        }
      };

      /// Direction d = (k, L) of TangentDirections::in_plane(2, hoop).
      constexpr unsigned int planar_k[5] = {0, 0, 1, 1, 2}, planar_L[5] = {0, 1, 0, 1, 2};

      /**
       * (s F⁻ᵀ)_c of a symmetric s given by its raw components 00, 11, 22, 01
       * (the rest enter times zeros of F⁻¹) for the planar direction c.
       */
      inline double planar_times_FiT(const double (&s)[4], const double (&Fi)[3][3],
                                     const unsigned int c)
      {
        if (c == 4)
          return s[2] * Fi[2][2];
        const unsigned int i = planar_k[c], J = planar_L[c];
        return (i == 0 ? s[0] : s[3]) * Fi[J][0] + (i == 0 ? s[3] : s[1]) * Fi[J][1];
      }

      /**
       * A = ∂P/∂F over the N_DIR planar directions and T0 (F-bar) as
       * StressDivergence::add_tangent computes them, with the zeros of the
       * block structure left out of the sums: only the components 00, 11,
       * 22, 01 of each δσ enter (the others meet (F⁻¹)_J2 = 0), and the
       * terms σF⁻ᵀ_iL (F⁻ᵀ)_kJ vanish between an in-plane and the hoop
       * direction. The same bits.
       */
      template <unsigned int N_DIR>
      void planar_tangent_matrix(const PointValues &p, const PlanarPoint &pp,
                                 const SymmetricTensor<2, 3> *dsigma, const bool f_bar_on,
                                 const double alpha, std::array<std::array<double, 9>, 9> &A,
                                 std::array<double, 9> &T0)
      {
        const double(&Fi)[3][3] = pp.Fi;
        const double(&sFiT)[3][3] = pp.sFiT;
        const double J = p.J;
        double       ds_Fbar[4] = {0, 0, 0, 0}; // δσ in the direction F̄ (FBar::stress_along)
        if (f_bar_on)
          for (unsigned int d = 0; d < N_DIR; ++d)
            {
              const double f = p.F_mat[planar_k[d]][planar_L[d]];
              for (unsigned int r = 0; r < 4; ++r)
                ds_Fbar[r] += f * dsigma[d].access_raw_entry(r);
            }
        const SymmetricTensor<2, 3> &vrs = p.response.volume_ratio_sensitivity;
        for (unsigned int d = 0; d < N_DIR; ++d)
          {
            const unsigned int k = planar_k[d], L = planar_L[d];
            double             ds[4];
            for (unsigned int r = 0; r < 4; ++r)
              ds[r] = dsigma[d].access_raw_entry(r);
            if (f_bar_on) // FBar::stress_derivative
              {
                const double a = alpha * Fi[L][k];
                for (unsigned int r = 0; r < 4; ++r)
                  ds[r] = p.beta * ds[r] - a * ds_Fbar[r];
              }
            if (p.adiabatic)
              for (unsigned int r = 0; r < 4; ++r)
                ds[r] += Fi[L][k] * vrs.access_raw_entry(r);
            for (unsigned int c = 0; c < N_DIR; ++c)
              {
                const unsigned int i = planar_k[c], J_ = planar_L[c];
                double a = Fi[L][k] * sFiT[i][J_] + planar_times_FiT(ds, Fi, c);
                if ((c == 4) == (d == 4))
                  a -= sFiT[i][L] * Fi[J_][k];
                A[c][d] = J * a;
              }
          }
        if (f_bar_on) // FBar::centre_coupling
          for (unsigned int c = 0; c < N_DIR; ++c)
            T0[c] = J * alpha * planar_times_FiT(ds_Fbar, Fi, c);
      }

      /**
       * add_dense_tangent for the interleaved planar layout (dof b has
       * component b mod 2; ∂F/∂u_b has the entries (0, J) = ∂N_b/∂X_J and
       * with HOOP (2, 2) = N_b/R for component 0, (1, J) for component 1):
       * only the nonzero terms of its sums, in the same order. The same bits.
       */
      template <unsigned int N_DOFS, bool HOOP>
      void add_planar_tangent(const std::array<std::array<double, 9>, 9> &A,
                              const double *__restrict gx, const double *__restrict gy,
                              const double *__restrict h, const double *__restrict T0,
                              const double *__restrict tr, const double w, double *__restrict K)
      {
        constexpr unsigned int N_DIR = HOOP ? 5 : 4;
        double                 AG[N_DIR][N_DOFS];
        for (unsigned int c = 0; c < N_DIR; ++c)
          for (unsigned int b = 0; b < N_DOFS; b += 2)
            {
              double s0 = A[c][0] * gx[b] + A[c][1] * gy[b];
              if (HOOP)
                s0 += A[c][4] * h[b];
              double s1 = A[c][2] * gx[b + 1] + A[c][3] * gy[b + 1];
              if (tr)
                {
                  s0 += T0[c] * tr[b];
                  s1 += T0[c] * tr[b + 1];
                }
              AG[c][b]     = s0 * w;
              AG[c][b + 1] = s1 * w;
            }
        for (unsigned int a = 0; a < N_DOFS; a += 2)
          {
            double *K0 = K + a * N_DOFS, *K1 = K0 + N_DOFS;
            double  s[N_DOFS];
            for (unsigned int b = 0; b < N_DOFS; ++b)
              s[b] = gx[a] * AG[0][b] + gy[a] * AG[1][b];
            if (HOOP)
              for (unsigned int b = 0; b < N_DOFS; ++b)
                s[b] += h[a] * AG[N_DIR - 1][b];
            for (unsigned int b = 0; b < N_DOFS; ++b)
              K0[b] += s[b];
            for (unsigned int b = 0; b < N_DOFS; ++b)
              K1[b] += gx[a + 1] * AG[2][b] + gy[a + 1] * AG[3][b];
          }
      }

      /// Four doubles; unaligned loads and stores through v4u.
      typedef double v4 __attribute__((vector_size(32)));
      typedef double v4u __attribute__((vector_size(32), aligned(8)));

      /**
       * planar_tangent_matrix<4> (plane strain), four directions c at once:
       * A's column d and T0 as vectors over c = (0,0), (0,1), (1,0), (1,1),
       * each entry the same products and sums in the same order (no FMA),
       * so the same bits. @p At: Aᵀ (At[d][c] = A[c][d]).
       */
      __attribute__((target_clones("avx2", "default"))) void
      plane_strain_tangent_matrix(const PointValues &p, const PlanarPoint &pp,
                                  const SymmetricTensor<2, 3> *dsigma, const bool f_bar_on,
                                  const double alpha, double (&At)[4][4], double (&T0)[4])
      {
        constexpr unsigned int k_of[4] = {0, 0, 1, 1}, L_of[4] = {0, 1, 0, 1};
        const double(&Fi)[3][3]   = pp.Fi;
        const double(&sFiT)[3][3] = pp.sFiT;
        const double J            = p.J;
        // δσ's raw components 00, 11, 22, 01 of each direction (22 unused off the hoop).
        v4 D[4];
        for (unsigned int d = 0; d < 4; ++d)
          D[d] = *reinterpret_cast<const v4u *>(&dsigma[d].access_raw_entry(0));
        v4 dF = {0, 0, 0, 0}; // δσ in the direction F̄ (FBar::stress_along)
        if (f_bar_on)
          for (unsigned int d = 0; d < 4; ++d)
            dF += p.F_mat[k_of[d]][L_of[d]] * D[d];
        const v4 vrs = *reinterpret_cast<const v4u *>(
          &p.response.volume_ratio_sensitivity.access_raw_entry(0));
        // (F⁻¹)_{J_c 0}, (F⁻¹)_{J_c 1} and (σF⁻ᵀ)_{i_c J_c} over c
        const v4 FiJ0 = {Fi[0][0], Fi[1][0], Fi[0][0], Fi[1][0]},
                 FiJ1 = {Fi[0][1], Fi[1][1], Fi[0][1], Fi[1][1]},
                 SF   = {sFiT[0][0], sFiT[0][1], sFiT[1][0], sFiT[1][1]};
        for (unsigned int d = 0; d < 4; ++d)
          {
            const unsigned int k = k_of[d], L = L_of[d];
            const double       FiLk = Fi[L][k];
            v4                 ds   = D[d];
            if (f_bar_on) // FBar::stress_derivative
              ds = p.beta * ds - (alpha * FiLk) * dF;
            if (p.adiabatic)
              ds += FiLk * vrs;
            // (δσ F⁻ᵀ)_c: (i == 0 ? ds00 : ds01) F⁻¹_J0 + (i == 0 ? ds01 : ds11) F⁻¹_J1
            const v4 s0 = {ds[0], ds[0], ds[3], ds[3]}, s1 = {ds[3], ds[3], ds[1], ds[1]};
            const v4 sL = {sFiT[0][L], sFiT[0][L], sFiT[1][L], sFiT[1][L]},
                     Fk = {Fi[0][k], Fi[1][k], Fi[0][k], Fi[1][k]};
            const v4 a = (FiLk * SF + (s0 * FiJ0 + s1 * FiJ1)) - sL * Fk;
            *reinterpret_cast<v4u *>(At[d]) = J * a;
          }
        if (f_bar_on) // FBar::centre_coupling
          {
            const v4 s0 = {dF[0], dF[0], dF[3], dF[3]}, s1 = {dF[3], dF[3], dF[1], dF[1]};
            *reinterpret_cast<v4u *>(T0) = (J * alpha) * (s0 * FiJ0 + s1 * FiJ1);
          }
      }

      typedef long long v4i __attribute__((vector_size(32)));

      /**
       * The internal forces of one point of a plane-strain Q1 element:
       * f_a += (P_c0 ∂N_a/∂X + P_c1 ∂N_a/∂Y) w with c the component of dof a,
       * as assemble_planar's loop (the same bits), four dofs at once; the
       * shape gradients @p grad ([a][d]) split into @p gx and @p gy.
       */
      __attribute__((target_clones("avx2", "default"))) void
      plane_strain_forces(const double *__restrict grad, const double P00, const double P01,
                          const double P10, const double P11, const double w,
                          double *__restrict f, double *__restrict gx, double *__restrict gy)
      {
        const v4 Pc0 = {P00, P10, P00, P10}, Pc1 = {P01, P11, P01, P11};
        for (unsigned int h = 0; h < 2; ++h)
          {
            const v4 g0 = *reinterpret_cast<const v4u *>(grad + 8 * h),
                     g1 = *reinterpret_cast<const v4u *>(grad + 8 * h + 4);
            const v4 x = __builtin_shuffle(g0, g1, v4i{0, 2, 4, 6}),
                     y = __builtin_shuffle(g0, g1, v4i{1, 3, 5, 7});
            *reinterpret_cast<v4u *>(gx + 4 * h) = x;
            *reinterpret_cast<v4u *>(gy + 4 * h) = y;
            v4u *const fh = reinterpret_cast<v4u *>(f + 4 * h);
            *fh += (Pc0 * x + Pc1 * y) * w;
          }
      }

      /// The cell's points of a plane-strain Q1 element, for the tangent.
      struct PlaneStrainPoints
      {
        static constexpr unsigned int max_points = 9;
        double At[max_points][4][4], T0[max_points][4]; // Aᵀ per point
        double gx[max_points][8], gy[max_points][8], w[max_points];
      };

      /**
       * K += Σ_q G_qᵀ (A_q G_q + T0_q ⊗ tr) w_q for plane-strain Q1 (8
       * interleaved dofs): add_planar_tangent<8, false>'s products and sums,
       * element by element in the same order (AG = (A_c0 gx + A_c1 gy +
       * T0_c tr) w; K_ab += gx_a AG_0b + gy_a AG_1b), so the same bits; four
       * entries per operation, and each row of K added over the points
       * before it is stored (the points' updates in their order). Compiled
       * for AVX2 and for base x86-64 (no FMA: the same rounding on either).
       */
      __attribute__((target_clones("avx2", "default"))) void
      add_plane_strain_tangent(const PlaneStrainPoints &pts, const unsigned int n_q,
                               const double *__restrict tr, double *__restrict K)
      {
        v4 AG[PlaneStrainPoints::max_points][4][2];
        v4 TR[2] = {};
        if (tr)
          TR[0] = *reinterpret_cast<const v4u *>(tr), TR[1] = *reinterpret_cast<const v4u *>(tr + 4);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const v4 GX[2] = {*reinterpret_cast<const v4u *>(pts.gx[q]),
                              *reinterpret_cast<const v4u *>(pts.gx[q] + 4)};
            const v4 GY[2] = {*reinterpret_cast<const v4u *>(pts.gy[q]),
                              *reinterpret_cast<const v4u *>(pts.gy[q] + 4)};
            const double w = pts.w[q];
            for (unsigned int c = 0; c < 4; ++c)
              {
                const double(&At)[4][4] = pts.At[q];
                // even dofs (component 0) read A_c0, A_c1; odd ones A_c2, A_c3
                const v4 ax = {At[0][c], At[2][c], At[0][c], At[2][c]},
                         ay = {At[1][c], At[3][c], At[1][c], At[3][c]};
                for (unsigned int h = 0; h < 2; ++h)
                  {
                    v4 s = ax * GX[h] + ay * GY[h];
                    if (tr)
                      s += pts.T0[q][c] * TR[h];
                    AG[q][c][h] = s * w;
                  }
              }
          }
        for (unsigned int a = 0; a < 8; a += 2)
          for (unsigned int h = 0; h < 2; ++h)
            {
              v4u *const K0 = reinterpret_cast<v4u *>(K + a * 8 + 4 * h);
              v4u *const K1 = reinterpret_cast<v4u *>(K + (a + 1) * 8 + 4 * h);
              v4         k0 = *K0, k1 = *K1;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  k0 += pts.gx[q][a] * AG[q][0][h] + pts.gy[q][a] * AG[q][1][h];
                  k1 += pts.gx[q][a + 1] * AG[q][2][h] + pts.gy[q][a + 1] * AG[q][3][h];
                }
              *K0 = k0;
              *K1 = k1;
            }
      }
    } // namespace

    template <int dim>
    StressDivergence<dim>::StressDivergence(const Context<dim> &context, const bool planar_kernel)
      : context(context)
      , f_bar(*context.formulation)
    {
      if (planar_kernel)
        planar_dofs = context.formulation->planar_dofs;
    }

    template <int dim>
    template <unsigned int N_DOFS, bool HOOP>
    void StressDivergence<dim>::assemble_planar(ScratchData<dim> &scratch, CopyData &copy) const
    {
      constexpr unsigned int  N_DIR       = HOOP ? 5 : 4;
      const Formulation<dim> &formulation = *context.formulation;
      const bool              f_bar_on    = formulation.f_bar;
      const ReferenceCellValues &cell     = scratch.cell;
      double                  gx[N_DOFS], gy[N_DOFS], h[N_DOFS];
      // Plane-strain Q1: each point's A and shape gradients kept, K added
      // once per cell (add_plane_strain_tangent).
      constexpr bool plane_q1 = N_DOFS == 8 && !HOOP;
      const unsigned int n_q  = scratch.points.size();
      const bool         fused = plane_q1 && context.with_matrix && n_q <= PlaneStrainPoints::max_points;
      PlaneStrainPoints  pts;
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const PointValues &p = scratch.points[q];
          // P = J σ F⁻ᵀ with the true J and F: ∫ σ : ∇ₓδv dv on the current volume.
          const PlanarPoint pp(p.F, p.response.stress);
          const double      P00 = p.J * pp.sFiT[0][0], P01 = p.J * pp.sFiT[0][1],
                       P10 = p.J * pp.sFiT[1][0], P11 = p.J * pp.sFiT[1][1],
                       P22 = p.J * pp.sFiT[2][2];
          const double *grad = cell.grad + q * N_DOFS * 2;
          if constexpr (plane_q1)
            {
              plane_strain_forces(grad, P00, P01, P10, P11, p.w, copy.internal.begin(),
                                  fused ? pts.gx[q] : gx, fused ? pts.gy[q] : gy);
              (void)P22;
            }
          else
            for (unsigned int a = 0; a < N_DOFS; ++a)
              {
                gx[a] = grad[2 * a];
                gy[a] = grad[2 * a + 1];
              }
          for (unsigned int a = 0; a < N_DOFS && !plane_q1; a += 2)
            {
              double f0 = P00 * gx[a] + P01 * gy[a];
              if (HOOP) // δF₃₃ = δu_r/R
                {
                  h[a] = cell.value[q * N_DOFS + a] / p.R;
                  f0 += P22 * h[a];
                }
              copy.internal(a) += f0 * p.w;
              copy.internal(a + 1) += (P10 * gx[a + 1] + P11 * gy[a + 1]) * p.w;
            }
          if (!context.with_matrix)
            continue;
          // Only δσ's components 00, 11, 22, 01 enter: the planar Jaumann
          // tangent computes no others (cauchy_tangent's dispatch, without them).
          auto &dsigma = scratch.dsigma;
          // Plane strain reads only 00, 11, 01 (22 meets no direction).
          if (!HOOP && p.kin.planar && p.kin.rate == ObjectiveRate::jaumann &&
              plane_strain_tangent_rows(p.kin, p.point->committed_stress(), p.response,
                                        formulation.directions, dsigma.data()))
            ;
          else if (p.kin.planar && p.kin.rate == ObjectiveRate::jaumann)
            planar_cauchy_tangent_in_plane(p.kin, p.point->committed_stress(), p.response,
                                           formulation.directions, dsigma.data());
          else
            cauchy_tangent(p.kin, p.point->committed_stress(), p.response, formulation.directions,
                           dsigma.data());
          if constexpr (plane_q1)
            if (fused)
              {
                plane_strain_tangent_matrix(p, pp, dsigma.data(), f_bar_on, formulation.alpha,
                                            pts.At[q], pts.T0[q]);
                pts.w[q] = p.w;
                continue;
              }
          planar_tangent_matrix<N_DIR>(p, pp, dsigma.data(), f_bar_on, formulation.alpha, scratch.A,
                                       scratch.T0);
          add_planar_tangent<N_DOFS, HOOP>(scratch.A, gx, gy, h, scratch.T0.data(),
                                           f_bar_on ? scratch.center_trace.data() : nullptr, p.w,
                                           &copy.matrix(0, 0));
        }
      if (fused)
        add_plane_strain_tangent(pts, n_q, f_bar_on ? scratch.center_trace.data() : nullptr,
                                 &copy.matrix(0, 0));
    }

    template <int dim>
    void StressDivergence<dim>::assemble(ScratchData<dim> &scratch, CopyData &copy) const
    {
      if (planar_dofs == 8)
        return context.formulation->axisymmetric ? assemble_planar<8, true>(scratch, copy) :
                                                   assemble_planar<8, false>(scratch, copy);
      if (planar_dofs == 18)
        return context.formulation->axisymmetric ? assemble_planar<18, true>(scratch, copy) :
                                                   assemble_planar<18, false>(scratch, copy);
      const Formulation<dim> &formulation = *context.formulation;
      const auto             &directions  = formulation.directions;
      const unsigned int      n_dofs      = formulation.n_dofs;
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          const PointValues &p = scratch.points[q];
          // P = J σ F⁻ᵀ with the true J and F: ∫ σ : ∇ₓδv dv on the current volume.
          const Tensor<2, 3> F_inv     = invert(p.F);
          const Tensor<2, 3> F_inv_T   = transpose(F_inv);
          const Tensor<2, 3> sigma_FiT = Tensor<2, 3>(p.response.stress) * F_inv_T;
          const Tensor<2, 3> P         = p.J * sigma_FiT;
          for (unsigned int a = 0; a < n_dofs; ++a)
            {
              ShapeGradient &g = scratch.G[a];
              formulation.shape_gradient(scratch.cell, a, q, p.R, g);
              double f = 0;
              for (unsigned int e = 0; e < g.n; ++e)
                {
                  const auto &kl = directions.kl[g.c[e]];
                  f += P[kl.first][kl.second] * g.v[e];
                }
              copy.internal(a) += f * p.w;
            }
          if (context.with_matrix)
            add_tangent(p, F_inv, F_inv_T, sigma_FiT, scratch, copy);
        }
    }

    template <int dim>
    void StressDivergence<dim>::add_tangent(const PointValues &p, const Tensor<2, 3> &F_inv,
                                            const Tensor<2, 3> &F_inv_T,
                                            const Tensor<2, 3> &sigma_FiT,
                                            ScratchData<dim> &scratch, CopyData &copy) const
    {
      const Formulation<dim> &formulation = *context.formulation;
      const auto             &directions  = formulation.directions;
      const unsigned int      n_dir       = directions.n;
      const unsigned int      n_dofs      = formulation.n_dofs;
      const bool              f_bar_on    = formulation.f_bar;
      const double            J = p.J, w = p.w;
      auto                   &dsigma = scratch.dsigma;
      auto                   &A      = scratch.A;
      const auto             &G      = scratch.G;

      cauchy_tangent(p.kin, p.point->committed_stress(), p.response, directions, dsigma.data());
      SymmetricTensor<2, 3> dsigma_Fbar; // δσ in the direction F̄ (F-bar)
      if (f_bar_on)
        dsigma_Fbar = f_bar.stress_along(p.F_mat, dsigma);

      for (unsigned int d = 0; d < n_dir; ++d)
        {
          const unsigned int    k = directions.kl[d].first, L = directions.kl[d].second;
          SymmetricTensor<2, 3> ds = dsigma[d];
          if (f_bar_on)
            ds = f_bar.stress_derivative(dsigma[d], p.beta, F_inv[L][k], dsigma_Fbar);
          if (p.adiabatic) // ΔT_ad ∝ J: δ ln J = tr(δF F⁻¹) of the true F
            ds += F_inv[L][k] * p.response.volume_ratio_sensitivity;
          // ds as a full matrix: SymmetricTensor's (i, m) look-up is the inner loop's cost.
          const double dsm[3][3] = {{ds[0][0], ds[0][1], ds[0][2]},
                                    {ds[0][1], ds[1][1], ds[1][2]},
                                    {ds[0][2], ds[1][2], ds[2][2]}};
          for (unsigned int c = 0; c < n_dir; ++c)
            {
              const unsigned int i = directions.kl[c].first, J_ = directions.kl[c].second;
              double             ds_FiT = 0;
              for (unsigned int m = 0; m < 3; ++m)
                ds_FiT += dsm[i][m] * F_inv_T[m][J_];
              // δP = J [tr(δF F⁻¹) σF⁻ᵀ + δσ F⁻ᵀ − σF⁻ᵀ δFᵀ F⁻ᵀ]
              A[c][d] = J * (F_inv[L][k] * sigma_FiT[i][J_] + ds_FiT -
                             sigma_FiT[i][L] * F_inv_T[k][J_]);
            }
        }
      if (f_bar_on)
        f_bar.centre_coupling(J, F_inv_T, dsigma_Fbar, scratch.T0);

      // G_a as the dense columns of Gᵀ (zeros where a's component has no
      // direction): the products below run over every direction in the
      // order of the directions, so each sum adds the same nonzero terms in
      // the same order as the sparse G_a did, plus exact zeros.
      double *Gt = scratch.Gt.data();
      std::fill(Gt, Gt + n_dir * n_dofs, 0.);
      for (unsigned int b = 0; b < n_dofs; ++b)
        for (unsigned int e = 0; e < G[b].n; ++e)
          Gt[G[b].c[e] * n_dofs + b] = G[b].v[e];
      const double *tr = f_bar_on ? scratch.center_trace.data() : nullptr;
      double       *K  = &copy.matrix(0, 0);
      // Sizes known at compile time for the Q1 elements (the loops unroll
      // and vectorise over b); any other element takes the general loop.
      const double *T0 = scratch.T0.data();
      if (n_dir == 5 && n_dofs == 8)
        add_dense_tangent<5, 8>(A, Gt, T0, tr, w, K);
      else if (n_dir == 4 && n_dofs == 8)
        add_dense_tangent<4, 8>(A, Gt, T0, tr, w, K);
      else if (n_dir == 9 && n_dofs == 24)
        add_dense_tangent<9, 24>(A, Gt, T0, tr, w, K);
      else
        add_dense_tangent(n_dir, n_dofs, A, Gt, T0, tr, w, scratch.AGt.data(), K);
    }

    ANVIL_INSTANTIATE_CLASS(StressDivergence)
  } // namespace MechanicsAssembly
} // namespace anvil
