// F-bar (de Souza Neto et al. 1996; seed sec. 3.1, constant pressure
// elements): the cell centre's dilatation replaces the point's on the active
// block of F, and the linearisation that goes with it.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <cmath>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void FBar<dim>::evaluate_centre(ScratchData<dim> &scratch, const bool with_old) const
    {
      // Cell centre: J₀ and ∂J₀ for F-bar.
      const ReferenceCellValues &ref = scratch.cell;
      const unsigned int   n_q = scratch.points.size();
      const double         R0  = formulation.radius(ref, n_q);
      const Tensor<2, 3>   F0 =
        formulation.deformation_gradient(ref.centre_grad, ref.centre_value, scratch.local_u, R0);
      if (with_old)
        scratch.J0_old = formulation.active_det(formulation.deformation_gradient(
          ref.centre_grad, ref.centre_value, scratch.local_u_old, R0));
      scratch.J0     = formulation.active_det(F0);
      scratch.F0_inv = invert(F0);
      const Tensor<2, 3> &F0_inv = scratch.F0_inv;
      for (unsigned int b = 0; b < formulation.n_dofs; ++b)
        {
          const unsigned int cb = formulation.component[b];
          const double      *g  = ref.centre_grad + b * dim;
          double             tr = 0;
          for (unsigned int L = 0; L < dim; ++L)
            tr += F0_inv[L][cb] * g[L];
          if (formulation.axisymmetric && cb == 0)
            tr += F0_inv[2][2] * ref.centre_value[b] / R0;
          scratch.center_trace[b] = tr;
        }
    }

    namespace
    {
      /// x^α with α = 1/2 (plane strain) or 1/3: sqrt or cbrt, not pow().
      inline double f_bar_power(const bool plane_strain, const double x)
      {
        return plane_strain ? std::sqrt(x) : std::cbrt(x);
      }
    } // namespace

    template <int dim>
    Tensor<2, 3> FBar<dim>::material_gradient(const ScratchData<dim> &scratch,
                                              const Tensor<2, 3>     &F,
                                              double                 &beta) const
    {
      // F̄ = (J₀/J)^α F on the active block.
      beta = f_bar_power(formulation.plane_strain, scratch.J0 / formulation.active_det(F));
      return formulation.bar(F, beta);
    }

    template <int dim>
    double FBar<dim>::old_root(const ScratchData<dim> &scratch, const Tensor<2, 3> &F_old) const
    {
      return f_bar_power(formulation.plane_strain, scratch.J0_old / formulation.active_det(F_old));
    }

    template <int dim>
    Tensor<2, 3> FBar<dim>::old_material_gradient(const ScratchData<dim> &scratch,
                                                  const Tensor<2, 3>     &F_old) const
    {
      return formulation.bar(F_old, old_root(scratch, F_old));
    }

    template <int dim>
    Tensor<2, 3> FBar<dim>::material_gradient(const ScratchData<dim> &scratch,
                                              const Tensor<2, 3>     &F,
                                              const Tensor<2, 3>     &F_old,
                                              double                 &beta,
                                              Tensor<2, 3>           &F_mat_old) const
    {
      F_mat_old = old_material_gradient(scratch, F_old);
      return material_gradient(scratch, F, beta);
    }

    template <int dim>
    SymmetricTensor<2, 3>
    FBar<dim>::stress_along(const Tensor<2, 3>                         &F_mat,
                            const std::array<SymmetricTensor<2, 3>, 9> &dsigma) const
    {
      SymmetricTensor<2, 3> dsigma_Fbar; // δσ in the direction F̄
      const auto           &directions = formulation.directions;
      for (unsigned int d = 0; d < directions.n; ++d)
        dsigma_Fbar += F_mat[directions.kl[d].first][directions.kl[d].second] * dsigma[d];
      return dsigma_Fbar;
    }

    template <int dim>
    void FBar<dim>::centre_coupling(const double J, const Tensor<2, 3> &F_inv_T,
                                    const SymmetricTensor<2, 3> &dsigma_Fbar,
                                    std::array<double, 9>       &T0) const
    {
      const auto &directions = formulation.directions;
      for (unsigned int c = 0; c < directions.n; ++c)
        {
          const unsigned int i = directions.kl[c].first, J_ = directions.kl[c].second;
          double             v = 0;
          for (unsigned int m = 0; m < 3; ++m)
            v += dsigma_Fbar[i][m] * F_inv_T[m][J_];
          T0[c] = J * formulation.alpha * v;
        }
    }

    ANVIL_INSTANTIATE_CLASS(FBar)
  } // namespace MechanicsAssembly
} // namespace anvil
