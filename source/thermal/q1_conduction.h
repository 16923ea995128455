#pragma once

// The conduction matrix of a Q1 cell, K_ij = ∫ k ∇φᵢ·∇φⱼ dv (seed eq. 26,
// k independent of T), on the current configuration from the cell's moved
// vertices, without an FEValues reinit: the shape gradients on the reference
// cell are tabulated once, and at every point J = Σ_v x_v ⊗ ∇̂N_v (a Q1
// mapping's Jacobian: its shape functions are FE_Q(1)'s, vertex v = dof v),
// ∇φᵢ = J⁻ᵀ ∇̂φᵢ, dv = det J w_q (× 2πx₀ when axisymmetric). What FEValues
// with MappingQ1Eulerian computes, in another order of the same products:
// equal to round-off (tests/heat_q1_conduction.cc: 1e-15 of the largest entry).
// two_blocks: the heat tangent loop 3.2 M → ~0.4 M instructions per configuration.

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/full_matrix.h>

#include <array>
#include <vector>

namespace anvil
{
  namespace thermal
  {
    template <int dim>
    class Q1Conduction
    {
    public:
      static constexpr unsigned int n_vertices = 1u << dim;

      /// @p fe must be FE_Q(1) (its dof v sits on vertex v).
      Q1Conduction(const dealii::FiniteElement<dim> &fe, const dealii::Quadrature<dim> &quadrature)
        : n_q(quadrature.size())
        , weights(quadrature.get_weights())
        , value(n_q)
        , gradient(n_q)
      {
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int v = 0; v < n_vertices; ++v)
            {
              value[q][v]    = fe.shape_value(v, quadrature.point(q));
              gradient[q][v] = fe.shape_grad(v, quadrature.point(q));
            }
      }

      /// @p matrix (n_vertices², zero on entry) += k ∫ ∇φᵢ·∇φⱼ dv on the cell
      /// with the (moved) vertices @p x: the upper triangle, mirrored, in the
      /// summation order of Conduction::cell_tangent.
      template <class Vertices>
      void add_cell_matrix(const Vertices &x, const double k, const bool axisymmetric,
                           dealii::FullMatrix<double> &matrix) const
      {
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const dealii::Tensor<2, dim>       J       = jacobian(x, q);
            const double                       det     = dealii::determinant(J);
            const dealii::Tensor<2, dim>       inverse = dealii::invert(J);
            std::array<dealii::Tensor<1, dim>, n_vertices> g;
            for (unsigned int i = 0; i < n_vertices; ++i)
              for (unsigned int a = 0; a < dim; ++a)
                {
                  double s = 0;
                  for (unsigned int b = 0; b < dim; ++b)
                    s += inverse[b][a] * gradient[q][i][b];
                  g[i][a] = s;
                }
            double w = det * weights[q];
            if (axisymmetric)
              {
                double r = 0;
                for (unsigned int v = 0; v < n_vertices; ++v)
                  r += value[q][v] * x[v][0];
                w *= 2 * dealii::numbers::PI * r;
              }
            for (unsigned int i = 0; i < n_vertices; ++i)
              for (unsigned int j = i; j < n_vertices; ++j)
                matrix(i, j) += (k * (g[i] * g[j])) * w;
          }
        for (unsigned int i = 0; i < n_vertices; ++i)
          for (unsigned int j = i + 1; j < n_vertices; ++j)
            matrix(j, i) = matrix(i, j);
      }

      /// What an FEValues of the Q1 mapping with JxW and quadrature points
      /// gives on the cell with the (moved) vertices @p x, to round-off, from
      /// the Jacobian and radius add_cell_matrix uses: at point q, JxW[q],
      /// the ring weight 2πx₀ (1 unless @p axisymmetric) and the point
      /// (dim doubles at points[q · dim]).
      template <class Vertices>
      void cell_weights(const Vertices &x, const bool axisymmetric, double *JxW, double *axis_weight,
                        double *points) const
      {
        for (unsigned int q = 0; q < n_q; ++q)
          {
            JxW[q] = dealii::determinant(jacobian(x, q)) * weights[q];
            for (unsigned int d = 0; d < dim; ++d)
              {
                double c = 0;
                for (unsigned int v = 0; v < n_vertices; ++v)
                  c += value[q][v] * x[v][d];
                points[q * dim + d] = c;
              }
            axis_weight[q] = axisymmetric ? 2 * dealii::numbers::PI * points[q * dim] : 1.;
          }
      }

    private:
      /// J = Σ_v x_v ⊗ ∇̂N_v at point q (the Q1 mapping's Jacobian).
      template <class Vertices>
      dealii::Tensor<2, dim> jacobian(const Vertices &x, const unsigned int q) const
      {
        dealii::Tensor<2, dim> J;
        for (unsigned int v = 0; v < n_vertices; ++v)
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              J[a][b] += x[v][a] * gradient[q][v][b];
        return J;
      }

      const unsigned int                                           n_q;
      const std::vector<double>                                    weights;
      std::vector<std::array<double, n_vertices>>                  value;
      std::vector<std::array<dealii::Tensor<1, dim>, n_vertices>> gradient;
    };
  } // namespace thermal
} // namespace anvil
