// The heat tangent's Q1 conduction kernel (source/thermal/q1_conduction.h),
// which computes K_ij = ∫ k ∇φᵢ·∇φⱼ dv from a cell's moved vertices, against
//  1. FEValues on MappingQ1Eulerian, the path it replaces, on a 2D mesh moved
//     by a random displacement (plane and axisymmetric) and a moved 3D mesh:
//     every entry to 1e-14 of the cell's largest;
//  2. the closed form on an a × b rectangle, k = 1:
//     K_ii = (a/b + b/a)/3, K(i, x-neighbour) = (a/b − 2b/a)/6 ... (the
//     bilinear element's stiffness), and zero row sums (constants are in the
//     kernel of K) on every distorted cell;
//  3. axisymmetric: Σ_ij K_ij r_i r_j = k ∫ 2πr |∇r|² dv = k π (R_o² − R_i²) L
//     for the radius r = x₀ (linear, so the Q1 interpolant is exact);
//  4. the cell weights of the current configuration's table (cell_weights:
//     JxW and the points) against the same FEValues (1e-14), and their
//     volume Σ JxW 2πr = π (R_o² − R_i²) L on the ring.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1_eulerian.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/vector.h>

#include "../source/thermal/q1_conduction.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace dealii;

namespace
{
  int failures = 0;

  void check(const bool ok, const char *what, const double value, const double expected)
  {
    std::printf("%-58s %.16e  expected %.16e  %s\n", what, value, expected, ok ? "ok" : "FAILED");
    if (!ok)
      ++failures;
  }

  /// Largest |K_kernel − K_FEValues| relative to the cell's largest entry,
  /// over all cells of a mesh moved by a random displacement; and the largest
  /// row sum relative to the same.
  template <int dim>
  void compare(const Triangulation<dim> &tria, const bool axisymmetric, double &entry_error,
               double &row_sum_error, double &weight_error)
  {
    FESystem<dim>   mechanics_fe(FE_Q<dim>(1), dim);
    DoFHandler<dim> mechanics(tria);
    mechanics.distribute_dofs(mechanics_fe);
    Vector<double>   u(mechanics.n_dofs());
    std::mt19937     random(7);
    std::uniform_real_distribution<double> d(-0.08, 0.08);
    for (auto &x : u)
      x = d(random);
    MappingQ1Eulerian<dim, Vector<double>> mapping(mechanics, u);

    const FE_Q<dim>   fe(1);
    const QGauss<dim> quadrature(2);
    DoFHandler<dim>   heat(tria);
    heat.distribute_dofs(fe);
    FEValues<dim> v(mapping, fe, quadrature, update_gradients | update_JxW_values | update_quadrature_points);
    const anvil::thermal::Q1Conduction<dim> kernel(fe, quadrature);
    const double                            k = 2.5;
    const unsigned int                      n = fe.n_dofs_per_cell();
    FullMatrix<double>                      a(n, n), b(n, n);
    entry_error = row_sum_error = weight_error = 0;
    std::vector<double> JxW(quadrature.size()), axis(quadrature.size()), points(quadrature.size() * dim);
    for (const auto &cell : heat.active_cell_iterators())
      {
        v.reinit(cell);
        kernel.cell_weights(mapping.get_vertices(cell), axisymmetric, JxW.data(), axis.data(), points.data());
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            weight_error = std::max(weight_error, std::abs(JxW[q] - v.JxW(q)) / v.JxW(q));
            for (unsigned int d = 0; d < dim; ++d)
              weight_error = std::max(weight_error, std::abs(points[q * dim + d] - v.quadrature_point(q)[d]) /
                                                      v.quadrature_point(q).norm());
          }
        a = 0;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            const double r = axisymmetric ? 2 * numbers::PI * v.quadrature_point(q)[0] : 1.;
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                a(i, j) += k * (v.shape_grad(i, q) * v.shape_grad(j, q)) * v.JxW(q) * r;
          }
        b = 0;
        kernel.add_cell_matrix(mapping.get_vertices(cell), k, axisymmetric, b);
        double scale = 0, diff = 0, row = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            double sum = 0;
            for (unsigned int j = 0; j < n; ++j)
              {
                scale = std::max(scale, std::abs(a(i, j)));
                diff  = std::max(diff, std::abs(a(i, j) - b(i, j)));
                sum += b(i, j);
              }
            row = std::max(row, std::abs(sum));
          }
        entry_error   = std::max(entry_error, diff / scale);
        row_sum_error = std::max(row_sum_error, row / scale);
      }
  }
} // namespace

int main()
{
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {6, 8}, Point<2>(1, 0), Point<2>(3, 4));
    double e, r, w;
    compare<2>(tria, false, e, r, w);
    check(w < 1e-14, "2D moved mesh: cell weights, max relative |JxW, x_q - FEValues'|", w, 0);
    check(e < 1e-14, "2D moved mesh: max |K - K_FEValues| / max |K|", e, 0);
    check(r < 1e-14, "2D moved mesh: max |row sum| / max |K|", r, 0);
    compare<2>(tria, true, e, r, w);
    check(e < 1e-14, "2D axisymmetric moved mesh: max |K - K_FEValues| / max |K|", e, 0);
    check(r < 1e-14, "2D axisymmetric moved mesh: max |row sum| / max |K|", r, 0);
  }
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {3, 3, 4}, Point<3>(0, 0, 0), Point<3>(2, 2, 3));
    double e, r, w;
    compare<3>(tria, false, e, r, w);
    check(w < 1e-14, "3D moved mesh: cell weights, max relative |JxW, x_q - FEValues'|", w, 0);
    check(e < 1e-14, "3D moved mesh: max |K - K_FEValues| / max |K|", e, 0);
    check(r < 1e-14, "3D moved mesh: max |row sum| / max |K|", r, 0);
  }
  {
    // One a × b rectangle, k = 1: the bilinear element's stiffness.
    const double a = 2, b = 0.5;
    const FE_Q<2> fe(1);
    const anvil::thermal::Q1Conduction<2> kernel(fe, QGauss<2>(2));
    const std::array<Point<2>, 4> x{{Point<2>(0, 0), Point<2>(a, 0), Point<2>(0, b), Point<2>(a, b)}};
    FullMatrix<double> K(4, 4);
    kernel.add_cell_matrix(x, 1., false, K);
    const double diagonal = (a / b + b / a) / 3, along_x = (a / b - 2 * b / a) / 6,
                 along_y = (b / a - 2 * a / b) / 6, across = -(a / b + b / a) / 6;
    check(std::abs(K(0, 0) - diagonal) < 1e-15 * diagonal, "rectangle 2 x 0.5: K_00", K(0, 0), diagonal);
    check(std::abs(K(0, 1) - along_x) < 1e-15 * diagonal, "rectangle: K_01 (x-neighbour)", K(0, 1), along_x);
    check(std::abs(K(0, 2) - along_y) < 1e-15 * diagonal, "rectangle: K_02 (y-neighbour)", K(0, 2), along_y);
    check(std::abs(K(0, 3) - across) < 1e-15 * diagonal, "rectangle: K_03 (opposite)", K(0, 3), across);
  }
  {
    // Axisymmetric ring R_i..R_o × L: Σ K_ij r_i r_j = k π (R_o² − R_i²) L.
    Triangulation<2> tria;
    const double     Ri = 1, Ro = 3, L = 2, k = 1.5;
    GridGenerator::subdivided_hyper_rectangle(tria, {5, 4}, Point<2>(Ri, 0), Point<2>(Ro, L));
    const FE_Q<2>                         fe(1);
    const anvil::thermal::Q1Conduction<2> kernel(fe, QGauss<2>(2));
    double                                sum = 0, volume = 0;
    FullMatrix<double>                    K(4, 4);
    std::array<double, 4>                 JxW, axis;
    std::array<double, 8>                 points;
    for (const auto &cell : tria.active_cell_iterators())
      {
        std::array<Point<2>, 4> x;
        for (unsigned int v = 0; v < 4; ++v)
          x[v] = cell->vertex(v);
        K = 0;
        kernel.add_cell_matrix(x, k, true, K);
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int j = 0; j < 4; ++j)
            sum += K(i, j) * x[i][0] * x[j][0];
        kernel.cell_weights(x, true, JxW.data(), axis.data(), points.data());
        for (unsigned int q = 0; q < 4; ++q)
          volume += JxW[q] * axis[q];
      }
    const double expected = k * numbers::PI * (Ro * Ro - Ri * Ri) * L;
    check(std::abs(sum - expected) < 1e-13 * expected, "axisymmetric ring: sum K_ij r_i r_j", sum, expected);
    const double ring = numbers::PI * (Ro * Ro - Ri * Ri) * L;
    check(std::abs(volume - ring) < 1e-13 * ring, "axisymmetric ring: volume sum JxW 2 pi r", volume, ring);
  }
  std::printf("%s\n", failures ? "FAILED" : "all ok");
  return failures ? 1 : 0;
}
