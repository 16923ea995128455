#include <deal.II/base/exceptions.h>
#include <deal.II/differentiation/ad.h>

#include <anvil/contact/ad_helpers.h>
#include <anvil/contact/contact_element.h>
#include <anvil/core/instantiate.h>

#include <array>
#include <cmath>
#include <type_traits>

namespace anvil
{
  namespace contact
  {
    using namespace dealii;

    namespace
    {
      using internal::ADNumber;
      using internal::dot;
      using internal::value_of;

      template <int dim, typename Number>
      Tensor<1, dim> values(const Tensor<1, dim, Number> &v)
      {
        Tensor<1, dim> w;
        for (unsigned int d = 0; d < dim; ++d)
          w[d] = value_of(v[d]);
        return w;
      }

      /// Node @p node (0: the slave, 1...: the master nodes) of the flat coordinate vector.
      template <int dim, typename Number>
      Tensor<1, dim, Number> node(const Number *coordinates, const unsigned int node)
      {
        Tensor<1, dim, Number> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = coordinates[dim * node + d];
        return x;
      }

      /// Tolerance on the master parameter domain [0, 1]^(dim-1): a slave just
      /// beyond the end of a master surface (by 0.1 % of a segment, e.g. when
      /// both bodies expand laterally alike) stays in contact with the end
      /// segment extended, instead of flipping in and out between iterations.
      constexpr double parameter_tolerance = 1e-3;

      /**
       * What the geometry of a pair gives the contact law: the gap, the
       * master normal, the relative displacement increment of the step
       * (x_s − x_s,old) − (x_m(ξ) − x_m,old(ξ)) before its projection on the
       * tangent plane, and the master shape functions at ξ (empty for a tool).
       */
      template <int dim, typename Number>
      struct PairGeometry
      {
        Number                 gap = 0;
        Tensor<1, dim, Number> normal, relative_increment;
        // Fixed-size storage: an evaluation allocates nothing on the heap
        // (the tube evaluates ~400 nodes per Newton iteration, most apart).
        std::array<Number, 4>  shape;
        unsigned int           n_shape = 0;
        std::array<double, 2>  xi       = {{0, 0}};
        unsigned int           n_xi     = 0;
        bool                   inside   = true;
      };

      /// 2D: the straight segment x_m(ξ) = (1 − ξ) x₀ + ξ x₁; n its left normal.
      template <typename Number>
      PairGeometry<2, Number> segment_geometry(const Number       *coordinates,
                                               const Tensor<1, 2> &slave_old,
                                               const Point<2>     *master_old)
      {
        using std::sqrt;
        PairGeometry<2, Number>      g;
        const Tensor<1, 2, Number> xs = node<2>(coordinates, 0), x0 = node<2>(coordinates, 1),
                                   x1 = node<2>(coordinates, 2);
        const Tensor<1, 2, Number> edge   = x1 - x0;
        const Number               length = sqrt(dot(edge, edge));
        // Closest point: the orthogonal projection on the segment's line.
        const Number xi = dot(xs - x0, edge) / (length * length);
        g.normal[0]     = -edge[1] / length;
        g.normal[1]     = edge[0] / length;
        g.gap           = dot(xs - x0, g.normal); // = (x_s − x_m(ξ)) · n
        g.shape[0]      = 1 - xi;
        g.shape[1]      = xi;
        g.n_shape       = 2;
        g.xi[0]         = value_of(xi);
        g.n_xi          = 1;
        g.inside        = g.xi[0] >= -parameter_tolerance && g.xi[0] <= 1 + parameter_tolerance;
        for (unsigned int d = 0; d < 2; ++d)
          {
            const Number master_increment = g.shape[0] * (x0[d] - master_old[0][d]) +
                                            g.shape[1] * (x1[d] - master_old[1][d]);
            g.relative_increment[d] = xs[d] - slave_old[d] - master_increment;
          }
        return g;
      }

      /**
       * The bilinear facet x_m(ξ, η) = Σ N_a x_a, (ξ, η) ∈ [0, 1]², vertices in
       * lexicographic order, and its first derivatives.
       */
      template <typename Number>
      struct BilinearFacet
      {
        std::array<Tensor<1, 3, Number>, 4> x;

        std::array<Number, 4> shape(const Number &s, const Number &t) const
        {
          return {{(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t}};
        }
        Tensor<1, 3, Number> position(const Number &s, const Number &t) const
        {
          const auto             N = shape(s, t);
          Tensor<1, 3, Number> p;
          for (unsigned int a = 0; a < 4; ++a)
            for (unsigned int d = 0; d < 3; ++d)
              p[d] += N[a] * x[a][d];
          return p;
        }
        Tensor<1, 3, Number> d_xi(const Number &t) const
        {
          Tensor<1, 3, Number> v;
          for (unsigned int d = 0; d < 3; ++d)
            v[d] = (1 - t) * (x[1][d] - x[0][d]) + t * (x[3][d] - x[2][d]);
          return v;
        }
        Tensor<1, 3, Number> d_eta(const Number &s) const
        {
          Tensor<1, 3, Number> v;
          for (unsigned int d = 0; d < 3; ++d)
            v[d] = (1 - s) * (x[2][d] - x[0][d]) + s * (x[3][d] - x[1][d]);
          return v;
        }
        /// x_m,ξη (x_m,ξξ = x_m,ηη = 0).
        Tensor<1, 3, Number> twist() const { return x[0] - x[1] - x[2] + x[3]; }

        /**
         * One Newton step for the closest point of @p xs, from (s, t): the
         * stationarity conditions f_α = (x_s − x_m) · x_m,α = 0 and their
         * Jacobian J_αβ = −x_m,α · x_m,β + (x_s − x_m) · x_m,αβ.
         */
        std::array<Number, 2> newton_step(const Tensor<1, 3, Number> &xs, const Number &s, const Number &t) const
        {
          const Tensor<1, 3, Number> distance = xs - position(s, t);
          const Tensor<1, 3, Number> a1 = d_xi(t), a2 = d_eta(s);
          const Number               f1 = dot(distance, a1), f2 = dot(distance, a2);
          const Number               J11 = -dot(a1, a1), J22 = -dot(a2, a2);
          const Number               J12 = -dot(a1, a2) + dot(distance, twist());
          const Number               det = J11 * J22 - J12 * J12;
          return {{-(J22 * f1 - J12 * f2) / det, -(J11 * f2 - J12 * f1) / det}};
        }
      };

      /// 3D: the bilinear facet; closest point by Newton in (ξ, η).
      template <typename Number>
      PairGeometry<3, Number> facet_geometry(const Number       *coordinates,
                                             const Tensor<1, 3> &slave_old,
                                             const Point<3>     *master_old)
      {
        using std::sqrt;
        PairGeometry<3, Number>    g;
        const Tensor<1, 3, Number> xs = node<3>(coordinates, 0);
        BilinearFacet<Number>      facet;
        BilinearFacet<double>      facet_values;
        for (unsigned int a = 0; a < 4; ++a)
          {
            facet.x[a]        = node<3>(coordinates, a + 1);
            facet_values.x[a] = values(facet.x[a]);
          }

        // Newton on the values from the facet's center ...
        const Tensor<1, 3> xs_value = values(xs);
        double             s = 0.5, t = 0.5;
        bool               converged = false;
        for (unsigned int it = 0; it < 30 && !converged; ++it)
          {
            const auto step = facet_values.newton_step(xs_value, s, t);
            if (!std::isfinite(step[0]) || !std::isfinite(step[1]))
              break;
            s += step[0];
            t += step[1];
            converged = std::abs(step[0]) + std::abs(step[1]) < 1e-14 * (1 + std::abs(s) + std::abs(t));
          }
        // ... then one more step with the full number type from the converged
        // (constant) point: its value does not move, and its derivatives are
        // those of the implicit function ξ(x), dξ/dx = −J⁻¹ ∂f/∂x.
        const auto   step = facet.newton_step(xs, Number(s), Number(t));
        const Number xi   = s + step[0];
        const Number eta  = t + step[1];

        const Tensor<1, 3, Number> a1 = facet.d_xi(eta), a2 = facet.d_eta(xi);
        Tensor<1, 3, Number>       n;
        n[0]                = a1[1] * a2[2] - a1[2] * a2[1];
        n[1]                = a1[2] * a2[0] - a1[0] * a2[2];
        n[2]                = a1[0] * a2[1] - a1[1] * a2[0];
        const Number length = sqrt(dot(n, n));
        for (unsigned int d = 0; d < 3; ++d)
          g.normal[d] = n[d] / length;
        g.gap = dot(xs - facet.position(xi, eta), g.normal);

        const auto N = facet.shape(xi, eta);
        g.shape   = N;
        g.n_shape = 4;
        g.xi      = {{value_of(xi), value_of(eta)}};
        g.n_xi    = 2;
        g.inside  = converged;
        for (const double c : g.xi)
          g.inside = g.inside && c >= -parameter_tolerance && c <= 1 + parameter_tolerance;
        for (unsigned int d = 0; d < 3; ++d)
          {
            Number master_increment = 0;
            for (unsigned int a = 0; a < 4; ++a)
              master_increment += N[a] * (facet.x[a][d] - master_old[a][d]);
            g.relative_increment[d] = xs[d] - slave_old[d] - master_increment;
          }
        return g;
      }

      /**
       * A slave behind a concave corner of the master, below the shared vertex
       * x_v where it projects into neither face: the closest master point is the
       * vertex, so n = (x_v − x_s)/|x_v − x_s| and g_N = −|x_v − x_s|. On the
       * edges of that region x_s − x_v is along −n of the face there, so gap,
       * normal and force continue those of node_to_segment() (no jump for
       * Newton to chase; doc/contact.md, "Concave corners").
       */
      template <int dim, typename Number>
      PairGeometry<dim, Number> vertex_geometry(const Number              *coordinates,
                                                const Tensor<1, dim>      &slave_old,
                                                const Tensor<1, dim>      &vertex_old)
      {
        using std::sqrt;
        PairGeometry<dim, Number>    g;
        const Tensor<1, dim, Number> xs = node<dim>(coordinates, 0), xv = node<dim>(coordinates, 1);
        const Tensor<1, dim, Number> d      = xv - xs;
        const Number                 length = sqrt(dot(d, d));
        for (unsigned int i = 0; i < dim; ++i)
          g.normal[i] = d[i] / length;
        g.gap   = -length;
        g.shape[0] = Number(1.);
        g.n_shape  = 1;
        for (unsigned int i = 0; i < dim; ++i)
          g.relative_increment[i] = xs[i] - slave_old[i] - (xv[i] - vertex_old[i]);
        return g;
      }

      /// The rigid tool: gap and normal from its projection, relative to its translation.
      template <int dim, typename Number>
      PairGeometry<dim, Number> tool_geometry(const Number         *coordinates,
                                              const Tensor<1, dim> &slave_old,
                                              const RigidTool<dim> &tool,
                                              const Tensor<1, dim> &u,
                                              const Tensor<1, dim> &u_old)
      {
        PairGeometry<dim, Number>    g;
        const Tensor<1, dim, Number> xs = node<dim>(coordinates, 0);
        tool.project_displaced(xs, u, g.gap, g.normal);
        const Tensor<1, dim> tool_increment = u - u_old;
        for (unsigned int d = 0; d < dim; ++d)
          g.relative_increment[d] = xs[d] - slave_old[d] - tool_increment[d];
        return g;
      }

      template <int dim, typename Number>
      struct ContactForces
      {
        bool                   sliding = false;
        Number                 normal_force = 0;
        Tensor<1, dim, Number> tangential_force, slip;
      };

      /// Penalty normal force (eq. 27) and Coulomb friction by elastic predictor
      /// and radial return (eq. 28–29); see the conventions in the header.
      template <int dim, typename Number>
      ContactForces<dim, Number> contact_forces(const PairGeometry<dim, Number> &g,
                                                const NodeState<dim>            &state,
                                                const FrictionLaw               &law)
      {
        using std::sqrt;
        ContactForces<dim, Number> f;
        f.normal_force             = -law.penalty_normal * g.gap;
        const Tensor<1, dim, Number> &n = g.normal;

        // Δg_T = (I − n⊗n) (relative increment)
        const Number           normal_part = dot(g.relative_increment, n);
        Tensor<1, dim, Number> tangential_increment;
        for (unsigned int d = 0; d < dim; ++d)
          tangential_increment[d] = g.relative_increment[d] - normal_part * n[d];

        if (law.penalty_tangent == 0)
          {
            // Frictionless: no tangential stiffness, all tangential motion is slip.
            f.sliding = true;
            f.slip    = tangential_increment;
            return f;
          }

        // The old force on the current tangent plane, its magnitude kept.
        Tensor<1, dim, Number> trial;
        const double           old_magnitude = state.in_contact ? state.tangential_force.norm() : 0.;
        if (old_magnitude > 0)
          {
            const Number           old_normal_part = dot(n, state.tangential_force);
            Tensor<1, dim, Number> rotated;
            for (unsigned int d = 0; d < dim; ++d)
              rotated[d] = state.tangential_force[d] - old_normal_part * n[d];
            const Number rotated_magnitude = sqrt(dot(rotated, rotated));
            if (value_of(rotated_magnitude) > 0)
              for (unsigned int d = 0; d < dim; ++d)
                trial[d] = rotated[d] * (old_magnitude / rotated_magnitude);
          }
        for (unsigned int d = 0; d < dim; ++d)
          trial[d] += law.penalty_tangent * tangential_increment[d];

        // Stick or slide, decided by value (eq. 28–29).
        const double trial_magnitude_value = std::sqrt(values(trial).norm_square());
        if (trial_magnitude_value <= law.mu_static * value_of(f.normal_force))
          {
            f.tangential_force = trial;
            return f;
          }
        f.sliding                     = true;
        const Number trial_magnitude  = sqrt(dot(trial, trial)); // > 0 here
        const Number sliding_force    = law.mu_dynamic * f.normal_force;
        const Number slip_magnitude   = (trial_magnitude - sliding_force) / law.penalty_tangent;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const Number direction = trial[d] / trial_magnitude;
            f.tangential_force[d]  = sliding_force * direction;
            f.slip[d]              = slip_magnitude * direction;
          }
        return f;
      }

      /// d r_i / d x_j into @p tangent (nothing to do for plain numbers).
      template <std::size_t N>
      void copy_derivatives(const std::array<double, N> &, unsigned int, FullMatrix<double> &)
      {}
      template <std::size_t N>
      void copy_derivatives(const std::array<ADNumber, N> &r, const unsigned int n,
                            FullMatrix<double> &tangent)
      {
        for (unsigned int i = 0; i < n; ++i)
          if (r[i].size() > 0)
            for (unsigned int j = 0; j < tangent.n(); ++j)
              tangent(i, j) = r[i].dx(j);
      }

      /// Fill @p result from the pair geometry @p g (values, and derivatives if Number is AD).
      template <int dim, typename Number>
      void evaluate_pair(const PairGeometry<dim, Number> &g,
                         const NodeState<dim>            &state,
                         const FrictionLaw               &law,
                         ContactResult<dim>              &result)
      {
        result.gap               = value_of(g.gap);
        result.normal            = values(g.normal);
        result.xi.assign(g.xi.begin(), g.xi.begin() + g.n_xi); // capacity kept: no allocation
        result.projection_inside = g.inside;
        if (!g.inside || result.gap > 0)
          return; // no contact: zero forces, residual and tangent; empty new state

        const ContactForces<dim, Number> f = contact_forces(g, state, law);

        // r_s = −t_N n + t_T, r_a = N_a (t_N n − t_T)
        const unsigned int         n = result.residual.size();
        std::array<Number, 5 * dim> r;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const Number on_slave = -f.normal_force * g.normal[d] + f.tangential_force[d];
            r[d]                  = on_slave;
            for (unsigned int a = 0; a < g.n_shape; ++a)
              r[dim * (a + 1) + d] = -g.shape[a] * on_slave;
          }
        for (unsigned int i = 0; i < n; ++i)
          result.residual[i] = value_of(r[i]);
        copy_derivatives(r, n, result.tangent);

        result.in_contact       = true;
        result.sliding          = f.sliding;
        result.normal_force     = value_of(f.normal_force);
        result.tangential_force = values(f.tangential_force);
        result.slip_increment   = values(f.slip);
        result.frictional_work  = result.tangential_force * result.slip_increment;
        result.new_state.in_contact       = true;
        result.new_state.sliding          = f.sliding;
        result.new_state.tangential_force = result.tangential_force;
      }

      /// @p result as a fresh one of @p n coordinates, its storage reused.
      template <int dim>
      void reset(ContactResult<dim> &result, const unsigned int n, const bool tangent)
      {
        result.in_contact = result.sliding = false;
        result.projection_inside = true;
        result.gap = result.normal_force = result.frictional_work = 0;
        result.normal = result.tangential_force = result.slip_increment = Tensor<1, dim>();
        result.xi.clear();
        result.new_state = NodeState<dim>();
        if (result.residual.size() != n)
          result.residual.reinit(n);
        else
          std::fill(result.residual.begin(), result.residual.end(), 0.);
        if (tangent)
          {
            if (result.tangent.m() != n || result.tangent.n() != n)
              result.tangent.reinit(n, n);
            else
              std::fill(&result.tangent(0, 0), &result.tangent(0, 0) + n * n, 0.);
          }
      }

      /**
       * Evaluate a pair whose current coordinates are @p coordinates (slave,
       * then master nodes; @p n of them) into @p result: with doubles for the
       * residual only, or with one forward-AD derivative per coordinate for
       * the tangent as well. @p geometry(coordinates) returns the
       * PairGeometry for either number type.
       */
      template <int dim, typename GeometryFunction>
      void evaluate(ContactResult<dim>        &result,
                    const double              *coordinates,
                    const unsigned int         n,
                    const GeometryFunction    &geometry,
                    const NodeState<dim>      &state,
                    const FrictionLaw         &law,
                    const bool                 tangent)
      {
        AssertThrow(law.mu_dynamic <= law.mu_static,
                    ExcMessage("contact: the dynamic friction coefficient must not exceed the static one"));
        reset(result, n, tangent);
        if (tangent)
          {
            // Most nodes a tool or a face is asked about are not touching it:
            // the geometry in doubles decides that (its values are the AD
            // values, operation for operation), and the derivatives are only
            // taken for a pair in contact.
            const PairGeometry<dim, double> g = geometry(coordinates);
            if (!g.inside || g.gap > 0)
              {
                evaluate_pair(g, state, law, result);
                return;
              }
            std::array<ADNumber, 5 * dim> x;
            for (unsigned int i = 0; i < n; ++i)
              x[i] = ADNumber(n, i, coordinates[i]);
            evaluate_pair(geometry(x.data()), state, law, result);
          }
        else
          evaluate_pair(geometry(coordinates), state, law, result);
      }
    } // namespace

    template <int dim>
    bool face_order_gives_outward_normal(const unsigned int face)
    {
      // 2D: face f runs from cell vertex face_to_cell_vertices(f, 0) to (f, 1):
      // upwards on faces 0 and 1, rightwards on 2 and 3; the left normal is
      // outward on faces 0 (x = 0) and 3 (y = 1). 3D: x_ξ × x_η is +e_k on
      // faces 2k and 2k + 1, outward on the odd ones.
      return dim == 2 ? (face == 0 || face == 3) : (face % 2 == 1);
    }

    template <int dim>
    void node_to_segment(ContactResult<dim> &result,
                         const Point<dim>   &slave,
                         const Point<dim>   &slave_old,
                         const Point<dim>   *master,
                         const Point<dim>   *master_old,
                         const NodeState<dim> &state,
                         const FrictionLaw    &law,
                         const bool            tangent)
    {
      constexpr unsigned int n_master = dim == 2 ? 2 : 4;
      std::array<double, dim * (1 + n_master)> coordinates;
      for (unsigned int d = 0; d < dim; ++d)
        coordinates[d] = slave[d];
      for (unsigned int a = 0; a < n_master; ++a)
        for (unsigned int d = 0; d < dim; ++d)
          coordinates[dim * (a + 1) + d] = master[a][d];

      const auto geometry = [&](const auto *x) {
        if constexpr (dim == 2)
          return segment_geometry(x, slave_old, master_old);
        else
          return facet_geometry(x, slave_old, master_old);
      };
      evaluate<dim>(result, coordinates.data(), coordinates.size(), geometry, state, law, tangent);
    }

    template <int dim>
    void node_to_vertex(ContactResult<dim>   &result,
                        const Point<dim>     &slave,
                        const Point<dim>     &slave_old,
                        const Point<dim>     &vertex,
                        const Point<dim>     &vertex_old,
                        const NodeState<dim> &state,
                        const FrictionLaw    &law,
                        const bool            tangent)
    {
      if (slave.distance(vertex) == 0)
        {
          result = ContactResult<dim>(); // on the vertex: no direction, no penetration
          return;
        }
      std::array<double, 2 * dim> coordinates;
      for (unsigned int d = 0; d < dim; ++d)
        {
          coordinates[d]       = slave[d];
          coordinates[dim + d] = vertex[d];
        }
      const auto geometry = [&](const auto *x) {
        using Number = std::decay_t<decltype(*x)>;
        return vertex_geometry<dim, Number>(x, slave_old, vertex_old);
      };
      evaluate<dim>(result, coordinates.data(), coordinates.size(), geometry, state, law, tangent);
    }

    template <int dim>
    void node_to_tool(ContactResult<dim>   &result,
                      const Point<dim>     &slave,
                      const Point<dim>     &slave_old,
                      const RigidTool<dim> &tool,
                      const Tensor<1, dim> &u,
                      const Tensor<1, dim> &u_old,
                      const NodeState<dim> &state,
                      const FrictionLaw    &law,
                      const bool            tangent)
    {
      std::array<double, dim> coordinates;
      for (unsigned int d = 0; d < dim; ++d)
        coordinates[d] = slave[d];
      const auto geometry = [&](const auto *x) {
        using Number = std::decay_t<decltype(*x)>;
        return tool_geometry<dim, Number>(x, slave_old, tool, u, u_old);
      };
      evaluate<dim>(result, coordinates.data(), dim, geometry, state, law, tangent);
    }

#define INSTANTIATE(dim)                                                                           \
  template bool              face_order_gives_outward_normal<dim>(unsigned int);                  \
  template void node_to_segment(ContactResult<dim> &, const Point<dim> &, const Point<dim> &,      \
                                const Point<dim> *, const Point<dim> *, const NodeState<dim> &,   \
                                const FrictionLaw &, bool);                                       \
  template void node_to_vertex(ContactResult<dim> &, const Point<dim> &, const Point<dim> &,       \
                               const Point<dim> &, const Point<dim> &, const NodeState<dim> &,    \
                               const FrictionLaw &, bool);                                        \
  template void node_to_tool(ContactResult<dim> &, const Point<dim> &, const Point<dim> &,         \
                             const RigidTool<dim> &, const Tensor<1, dim> &,                      \
                             const Tensor<1, dim> &, const NodeState<dim> &, const FrictionLaw &, \
                             bool);
    ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
  } // namespace contact
} // namespace anvil
