// The tapered end segment beyond a free end of a 2D master surface, and the
// tapered facet beyond a free edge of a 3D one (free_end.h; doc/contact.md,
// "Free ends").
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <anvil/contact/free_end.h>

#include <array>
#include <algorithm>
#include <cmath>

namespace anvil
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      /// The linear map x' = T x of the element's coordinates (slave first)
      /// that moves master node moved[k] to (1 + s) x_moved − s x_opposite.
      template <int dim>
      FullMatrix<double> extension_map(const unsigned int n_master, const std::vector<unsigned int> &moved,
                                       const std::vector<unsigned int> &opposite, const double s)
      {
        const unsigned int n = dim * (1 + n_master);
        FullMatrix<double> T(n, n);
        for (unsigned int i = 0; i < n; ++i)
          T(i, i) = 1;
        for (unsigned int k = 0; k < moved.size(); ++k)
          for (unsigned int c = 0; c < dim; ++c)
            {
              T(dim * (1 + moved[k]) + c, dim * (1 + moved[k]) + c)    = 1 + s;
              T(dim * (1 + moved[k]) + c, dim * (1 + opposite[k]) + c) = -s;
            }
        return T;
      }

      /**
       * The extended element's result @p r back on the original coordinates
       * (r = Tᵀ r', K = Tᵀ K' T) and times the taper w: the residual, forces
       * and work times w, the tangent d(w r)/dx = w K + r ⊗ ∇w.
       */
      template <int dim>
      void taper_result(ContactResult<dim> &r, const FullMatrix<double> &T, const double w,
                        const std::vector<double> &grad_w, const bool with_matrix)
      {
        const unsigned int n = T.m();
        Vector<double>     residual(n);
        T.Tvmult(residual, r.residual);
        if (with_matrix)
          {
            FullMatrix<double> KT(n, n), K(n, n);
            r.tangent.mmult(KT, T);
            T.Tmmult(K, KT);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                K(i, j) = w * K(i, j) + residual(i) * grad_w[j];
            r.tangent = K;
          }
        residual *= w;
        r.residual = residual;
        r.normal_force *= w;
        r.tangential_force *= w;
        r.frictional_work *= w;
        r.new_state.tangential_force *= w;
      }
    } // namespace

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

      // d(w r)/dx = w K + r ⊗ (dw/dξ ∇ξ): ∇ξ on (x_s, x_0, x_1).
      std::vector<double> grad_w(6);
      if (with_matrix)
        {
          const Tensor<1, 2> d_slave = e / L2, d_x1 = (a - 2 * xi * e) / L2;
          const Tensor<1, 2> d_x0 = -d_slave - d_x1;
          for (unsigned int c = 0; c < 2; ++c)
            {
              grad_w[c]     = dw_dxi * d_slave[c];
              grad_w[2 + c] = dw_dxi * d_x0[c];
              grad_w[4 + c] = dw_dxi * d_x1[c];
            }
        }
      taper_result<2>(r, extension_map<2>(2, {end}, {other}, s), w, grad_w, with_matrix);
      r.xi = {xi};
      return r;
    }

    namespace
    {
      /// ∂N_a/∂ξ_α of the bilinear facet (lexicographic vertices) at (ξ, η).
      std::array<std::array<double, 4>, 2> facet_shape_gradients(const double xi, const double eta)
      {
        return {{{{-(1 - eta), 1 - eta, -eta, eta}}, {{-(1 - xi), -xi, 1 - xi, xi}}}};
      }

      /**
       * ∇ξ_α of the closest point (ξ, η) of @p xs on the bilinear facet @p xm
       * (extended beyond [0, 1]²) with respect to the 15 coordinates (x_s, x_0..x_3),
       * by the implicit function theorem on f_α = (x_s − x_m) · x_m,α = 0:
       * J dξ = −∂f/∂x dx, J_αβ = −x_m,α · x_m,β + (x_s − x_m) · x_m,αβ,
       * ∂f_α/∂x_s = x_m,α, ∂f_α/∂x_a = −N_a x_m,α + (x_s − x_m) N_a,α.
       */
      std::array<std::array<double, 15>, 2> closest_point_gradient(const Point<3> &xs,
                                                                   const std::vector<Point<3>> &xm,
                                                                   const double xi, const double eta)
      {
        const double       N[4] = {(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta, xi * eta};
        const auto         dN   = facet_shape_gradients(xi, eta);
        Tensor<1, 3>       a[2], distance = xs;
        for (unsigned int v = 0; v < 4; ++v)
          {
            distance -= N[v] * xm[v];
            for (unsigned int k = 0; k < 2; ++k)
              a[k] += dN[k][v] * xm[v];
          }
        const Tensor<1, 3> twist = xm[0] - xm[1] - xm[2] + xm[3];
        const double       J11 = -(a[0] * a[0]), J22 = -(a[1] * a[1]);
        const double       J12 = -(a[0] * a[1]) + distance * twist;
        const double       det = J11 * J22 - J12 * J12;
        std::array<std::array<double, 15>, 2> df{}, dxi{};
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int c = 0; c < 3; ++c)
            {
              df[k][c] = a[k][c];
              for (unsigned int v = 0; v < 4; ++v)
                df[k][3 + 3 * v + c] = -N[v] * a[k][c] + distance[c] * dN[k][v];
            }
        for (unsigned int j = 0; j < 15; ++j)
          {
            dxi[0][j] = -(J22 * df[0][j] - J12 * df[1][j]) / det;
            dxi[1][j] = -(J11 * df[1][j] - J12 * df[0][j]) / det;
          }
        return dxi;
      }
    } // namespace

    ContactResult<3> free_edge_contact(const Point<3> &xs, const Point<3> &xs_old,
                                       const std::vector<Point<3>> &xm,
                                       const std::vector<Point<3>> &xm_old, const unsigned int edge,
                                       const NodeState<3> &state, const FrictionLaw &law,
                                       const bool with_matrix, const double end_taper)
    {
      if (!(end_taper > 0) || edge > 3)
        return ContactResult<3>();
      // The closest point on the facet's surface continued beyond its edges.
      const ContactResult<3> probe = node_to_segment(xs, xs_old, xm, xm_old, state, law, false);
      if (probe.xi.size() != 2 || !std::isfinite(probe.xi[0]) || !std::isfinite(probe.xi[1]))
        return ContactResult<3>();
      // Edge 2k + e is ξ_k = e (deal.II's face numbering of a quadrilateral):
      // α = k the coordinate across it, the other one along it.
      const unsigned int across = edge / 2, along = 1 - across, side = edge % 2;
      const double       xi_across = probe.xi[across], xi_along = probe.xi[along];
      const double       d         = side == 0 ? -xi_across : xi_across - 1;
      const double       t         = (d - end_tolerance) / end_taper;
      if (!(t > 0 && t < 1) || xi_along < -end_tolerance || xi_along > 1 + end_tolerance)
        return ContactResult<3>(); // not beyond this edge alone (a corner is not tapered)
      const double w     = 1 - t * t * (3 - 2 * t);
      const double dw_dd = -6 * t * (1 - t) / end_taper;

      // The facet extended across the edge by twice the taper: the edge's two
      // vertices x'_a = (1 + s) x_a − s x_b, b the vertex opposite a across
      // the facet. Along every line of the other coordinate the bilinear facet
      // is linear, so the extended facet is the same surface, ξ' = ξ/(1 + s)
      // (edge ξ = 1) or (ξ + s)/(1 + s) (edge ξ = 0).
      const double                 s = 2 * end_taper;
      const unsigned int           stride = across == 0 ? 1 : 2; // lexicographic: ξ fastest
      std::array<unsigned int, 2>  moved, opposite;
      for (unsigned int k = 0, v = 0; v < 4; ++v)
        if (((v / stride) % 2) == side)
          {
            moved[k]    = v;
            opposite[k] = side == 0 ? v + stride : v - stride;
            ++k;
          }
      std::vector<Point<3>> ext = xm, ext_old = xm_old;
      for (unsigned int k = 0; k < 2; ++k)
        {
          ext[moved[k]]     = xm[moved[k]] + s * (xm[moved[k]] - xm[opposite[k]]);
          ext_old[moved[k]] = xm_old[moved[k]] + s * (xm_old[moved[k]] - xm_old[opposite[k]]);
        }
      ContactResult<3> r = node_to_segment(xs, xs_old, ext, ext_old, state, law, with_matrix);
      if (!r.in_contact)
        return ContactResult<3>();

      // d(w r)/dx = w K + r ⊗ (dw/dd ∇d), d = −ξ_α or ξ_α − 1 on the facet itself.
      std::vector<double> grad_w(15);
      if (with_matrix)
        {
          const auto   grad_xi = closest_point_gradient(xs, xm, probe.xi[0], probe.xi[1]);
          const double sign    = side == 0 ? -1. : 1.;
          for (unsigned int j = 0; j < 15; ++j)
            grad_w[j] = dw_dd * sign * grad_xi[across][j];
        }
      taper_result<3>(r, extension_map<3>(4, {moved[0], moved[1]}, {opposite[0], opposite[1]}, s), w,
                      grad_w, with_matrix);
      // The point projected onto the edge (the heat goes to the edge's nodes).
      r.xi = {std::clamp(probe.xi[0], 0., 1.), std::clamp(probe.xi[1], 0., 1.)};
      return r;
    }
  } // namespace contact
} // namespace anvil
