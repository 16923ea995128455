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
    void FBar<dim>::evaluate_centre(ScratchData<dim> &scratch) const
    {
      // Cell centre: J₀ and ∂J₀ for F-bar.
      const ReferenceCellValues &ref = scratch.cell;
      const unsigned int   n_q = scratch.points.size();
      const double         R0  = formulation.radius(ref, n_q);
      const Tensor<2, 3>   F0 =
        formulation.deformation_gradient(ref.centre_grad, ref.centre_value, scratch.local_u, R0);
      const Tensor<2, 3> F0_old =
        formulation.deformation_gradient(ref.centre_grad, ref.centre_value, scratch.local_u_old, R0);
      scratch.J0     = formulation.active_det(F0);
      scratch.J0_old = formulation.active_det(F0_old);
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

    template <int dim>
    Tensor<2, 3> FBar<dim>::material_gradient(const ScratchData<dim> &scratch,
                                              const Tensor<2, 3>     &F,
                                              const Tensor<2, 3>     &F_old,
                                              double                 &beta,
                                              Tensor<2, 3>           &F_mat_old) const
    {
      // F̄ = (J₀/J)^α F on the active block.
      // x^α with α = 1/2 (plane strain) or 1/3: sqrt or cbrt, not pow().
      const auto power = [this](const double x) {
        return formulation.plane_strain ? std::sqrt(x) : std::cbrt(x);
      };
      beta      = power(scratch.J0 / formulation.active_det(F));
      F_mat_old = formulation.bar(F_old, power(scratch.J0_old / formulation.active_det(F_old)));
      return formulation.bar(F, beta);
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
