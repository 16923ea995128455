// The tapered end segment beyond a free end of a 2D master surface
// (free_end.h; doc/contact.md, "Free ends").
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <anvil/contact/free_end.h>

namespace anvil
{
  namespace contact
  {
    using namespace dealii;

    ContactResult<2> free_end_contact(const Point<2> &xs, const Point<2> &xs_old,
                                      const std::vector<Point<2>> &xm,
                                      const std::vector<Point<2>> &xm_old, const unsigned int end,
                                      const NodeState<2> &state, const FrictionLaw &law,
                                      const bool with_matrix, const double end_taper)
    {
      if (!(end_taper > 0))
        return ContactResult<2>();
      const Tensor<1, 2> e  = xm[1] - xm[0];
      const double       L2 = e * e;
      const Tensor<1, 2> a  = xs - xm[0];
      const double       xi = (a * e) / L2;
      const double       d  = end == 0 ? -xi : xi - 1;
      const double       t  = (d - end_tolerance) / end_taper;
      if (!(t > 0 && t < 1))
        return ContactResult<2>();
      const double w      = 1 - t * t * (3 - 2 * t);
      const double dw_dxi = (end == 0 ? 1. : -1.) * 6 * t * (1 - t) / end_taper;

      // The end segment extended by twice the taper: x'_end = (1 + s) x_end − s x_other.
      const double          s     = 2 * end_taper;
      const unsigned int    other = 1 - end;
      std::vector<Point<2>> ext = xm, ext_old = xm_old;
      ext[end]     = xm[end] + s * (xm[end] - xm[other]);
      ext_old[end] = xm_old[end] + s * (xm_old[end] - xm_old[other]);
      ContactResult<2> r = node_to_segment(xs, xs_old, ext, ext_old, state, law, with_matrix);
      if (!r.in_contact)
        return ContactResult<2>();

      // x' = T x on the six coordinates: r = Tᵀ r', K = Tᵀ K' T.
      FullMatrix<double> T(6, 6);
      for (unsigned int i = 0; i < 6; ++i)
        T(i, i) = 1;
      for (unsigned int c = 0; c < 2; ++c)
        {
          T(2 + 2 * end + c, 2 + 2 * end + c)   = 1 + s;
          T(2 + 2 * end + c, 2 + 2 * other + c) = -s;
        }
      Vector<double> residual(6);
      T.Tvmult(residual, r.residual);
      if (with_matrix)
        {
          FullMatrix<double> KT(6, 6), K(6, 6);
          r.tangent.mmult(KT, T);
          T.Tmmult(K, KT);
          // d(w r)/dx = w K + r ⊗ (dw/dξ ∇ξ): ∇ξ on (x_s, x_0, x_1).
          const Tensor<1, 2> d_slave = e / L2, d_x1 = (a - 2 * xi * e) / L2;
          const Tensor<1, 2> d_x0 = -d_slave - d_x1;
          double             grad[6];
          for (unsigned int c = 0; c < 2; ++c)
            {
              grad[c]     = dw_dxi * d_slave[c];
              grad[2 + c] = dw_dxi * d_x0[c];
              grad[4 + c] = dw_dxi * d_x1[c];
            }
          for (unsigned int i = 0; i < 6; ++i)
            for (unsigned int j = 0; j < 6; ++j)
              K(i, j) = w * K(i, j) + residual(i) * grad[j];
          r.tangent = K;
        }
      residual *= w;
      r.residual = residual;
      r.normal_force *= w;
      r.tangential_force *= w;
      r.frictional_work *= w;
      r.new_state.tangential_force *= w;
      r.xi = {xi};
      return r;
    }
  } // namespace contact
} // namespace anvil
