// The stress divergence ∫ P : ∇_X δv dV and its exact linearisation, for
// plane strain, axisymmetric and 3D elements, standard or F-bar
// (assembly_kernels.h, doc/mechanics.md).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

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
    } // namespace

    template <int dim>
    void StressDivergence<dim>::assemble(ScratchData<dim> &scratch, CopyData &copy) const
    {
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
