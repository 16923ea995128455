// The element formulation shared by the mechanical kernels: plane strain,
// axisymmetric (the hoop term) or 3D, standard or F-bar.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/element_formulation.h>

#include <algorithm>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    Formulation<dim>::Formulation(const FiniteElement<dim> &fe, const bool axisymmetric,
                                  const bool f_bar, const ObjectiveRate objective_rate)
      : axisymmetric(axisymmetric)
      , f_bar(f_bar)
      , objective_rate(objective_rate)
      , plane_strain(dim == 2 && !axisymmetric)
      , alpha((dim == 2 && !axisymmetric) ? 0.5 : 1. / 3.)
      // The directions of δF this formulation needs and where each lives.
      , directions(dim == 3 ? TangentDirections::in_plane(3, false) :
                              TangentDirections::in_plane(2, axisymmetric))
      , n_dofs(fe.n_dofs_per_cell())
      , component(fe.n_dofs_per_cell())
      , node(fe.n_dofs_per_cell())
    {
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          component[i] = fe.system_to_component_index(i).first;
          node[i]      = fe.system_to_component_index(i).second;
          n_nodes      = std::max(n_nodes, node[i] + 1);
        }
      for (auto &row : where)
        for (int &x : row)
          x = -1;
      for (unsigned int k = 0; k < directions.n; ++k)
        where[directions.kl[k].first][directions.kl[k].second] = k;
      bool interleaved = dim == 2;
      for (unsigned int a = 0; a < n_dofs; ++a)
        interleaved = interleaved && component[a] == a % 2;
      if (interleaved && (n_dofs == 8 || n_dofs == 18))
        planar_dofs = n_dofs;
    }

    namespace
    {
      /**
       * Formulation::deformation_gradient's sums for dim = 2 with the dofs
       * interleaved (component a mod 2) and N_DOFS known: each g_cd over the
       * shape functions of component c in their order, as the general loop
       * adds them (the same bits), without its run-time component look-up.
       */
      template <unsigned int N_DOFS>
      void planar_displacement_gradient(const double *__restrict grad,
                                        const double *__restrict value,
                                        const double *__restrict u, const bool hoop,
                                        double (&g)[2][2], double &u_r)
      {
        // (g00, g01) and (g10, g11) as pairs: each lane the scalar sum.
        typedef double v2 __attribute__((vector_size(16)));
        typedef double v2u __attribute__((vector_size(16), aligned(8)));
        v2     g0 = {0, 0}, g1 = {0, 0};
        double r  = 0;
        for (unsigned int a = 0; a < N_DOFS; a += 2)
          {
            g0 += u[a] * *reinterpret_cast<const v2u *>(grad + 2 * a);
            g1 += u[a + 1] * *reinterpret_cast<const v2u *>(grad + 2 * a + 2);
            if (hoop)
              r += u[a] * value[a];
          }
        g[0][0] = g0[0], g[0][1] = g0[1], g[1][0] = g1[0], g[1][1] = g1[1];
        u_r = r;
      }
    } // namespace

    template <int dim>
    Tensor<2, 3> Formulation<dim>::deformation_gradient(const Tensor<2, dim> &grad_u,
                                                        const double          radial_displacement,
                                                        const double          radius) const
    {
      // Plane strain: F₃₃ = 1. Axisymmetric: the hoop stretch F₃₃ = 1 + u_r/R.
      const double hoop = axisymmetric ? 1 + radial_displacement / radius : 1.;
      return embed<dim>(unit_symmetric_tensor<dim>() + grad_u, hoop);
    }

    template <int dim>
    Tensor<2, 3> Formulation<dim>::deformation_gradient(const double              *grad,
                                                        const double              *value,
                                                        const std::vector<double> &values,
                                                        const double               R) const
    {
      // On plain arrays (the Tensor and embed() calls were most of the cost):
      // each sum over the shape functions in their order, 1 + g and 0 + g
      // as unit_symmetric_tensor() + g gave them: the same bits.
      double             g[dim][dim] = {};
      double             u_r         = 0;
      const unsigned int *const c_of = component.data();
      const double *const       u    = values.data();
      if constexpr (dim == 2)
        {
          if (planar_dofs == 8)
            planar_displacement_gradient<8>(grad, value, u, axisymmetric, g, u_r);
          else if (planar_dofs == 18)
            planar_displacement_gradient<18>(grad, value, u, axisymmetric, g, u_r);
        }
      if (planar_dofs == 0)
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const unsigned int c = c_of[i];
            for (unsigned int d = 0; d < dim; ++d)
              g[c][d] += u[i] * grad[i * dim + d];
            if (axisymmetric && c == 0)
              u_r += u[i] * value[i];
          }
      Tensor<2, 3> F;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F[i][j] = (i == j ? 1. : 0.) + g[i][j];
      // Plane strain: F₃₃ = 1. Axisymmetric: the hoop stretch F₃₃ = 1 + u_r/R.
      const double hoop = axisymmetric ? 1 + u_r / R : 1.;
      for (unsigned int i = dim; i < 3; ++i)
        F[i][i] = hoop;
      return F;
    }

    template <int dim>
    void Formulation<dim>::shape_gradient(const ReferenceCellValues &cell, const unsigned int a,
                                          const unsigned int q, const double R,
                                          ShapeGradient &g) const
    {
      const unsigned int ca = component[a];
      const double      *gr = cell.grad + (q * n_dofs + a) * dim;
      g.n                   = 0;
      for (unsigned int J_ = 0; J_ < dim; ++J_)
        {
          g.c[g.n]   = where[ca][J_];
          g.v[g.n++] = gr[J_];
        }
      // The hoop term: δF₃₃ = δu_r/R.
      if (axisymmetric && ca == 0)
        {
          g.c[g.n]   = where[2][2];
          g.v[g.n++] = cell.value[q * n_dofs + a] / R;
        }
    }

    ANVIL_INSTANTIATE_CLASS(Formulation)
  } // namespace MechanicsAssembly
} // namespace anvil
