// The stress divergence ∫ P : ∇_X δv dV and its exact linearisation, for
// plane strain, axisymmetric and 3D elements, standard or F-bar
// (assembly_kernels.h, doc/mechanics.md).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

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

      // AG_b = (A : G_b (+ T0 tr_b)) w and K_ab += G_a : AG_b. G_a has 2 or 3
      // entries (3: the hoop term); the sums run in the order of the entries,
      // as the general loop (last branch) does.
      for (unsigned int b = 0; b < n_dofs; ++b)
        {
          const ShapeGradient &g  = G[b];
          auto                &ag = scratch.AG[b];
          const double         tr = f_bar_on ? scratch.center_trace[b] : 0.;
          for (unsigned int c = 0; c < n_dir; ++c)
            {
              const auto &Ac = A[c];
              double      s  = 0;
              if (g.n == 2)
                {
                  s += Ac[g.c[0]] * g.v[0];
                  s += Ac[g.c[1]] * g.v[1];
                }
              else
                for (unsigned int e = 0; e < g.n; ++e)
                  s += Ac[g.c[e]] * g.v[e];
              if (f_bar_on)
                s += scratch.T0[c] * tr;
              ag[c] = s * w;
            }
        }
      for (unsigned int a = 0; a < n_dofs; ++a)
        {
          const ShapeGradient &g   = G[a];
          double              *row = &copy.matrix(a, 0);
          if (g.n == 2)
            {
              const int    c0 = g.c[0], c1 = g.c[1];
              const double v0 = g.v[0], v1 = g.v[1];
              for (unsigned int b = 0; b < n_dofs; ++b)
                {
                  const auto &ag = scratch.AG[b];
                  double      s  = 0;
                  s += v0 * ag[c0];
                  s += v1 * ag[c1];
                  row[b] += s;
                }
            }
          else if (g.n == 3)
            {
              const int    c0 = g.c[0], c1 = g.c[1], c2 = g.c[2];
              const double v0 = g.v[0], v1 = g.v[1], v2 = g.v[2];
              for (unsigned int b = 0; b < n_dofs; ++b)
                {
                  const auto &ag = scratch.AG[b];
                  double      s  = 0;
                  s += v0 * ag[c0];
                  s += v1 * ag[c1];
                  s += v2 * ag[c2];
                  row[b] += s;
                }
            }
          else
            for (unsigned int b = 0; b < n_dofs; ++b)
              {
                double s = 0;
                for (unsigned int e = 0; e < g.n; ++e)
                  s += g.v[e] * scratch.AG[b][g.c[e]];
                row[b] += s;
              }
        }
    }

    ANVIL_INSTANTIATE_CLASS(StressDivergence)
  } // namespace MechanicsAssembly
} // namespace anvil
