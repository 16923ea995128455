// The mechanical assembly's reference values (reference_values.h), computed
// once per mesh, against what FEValues gives at every assembly:
//  1. every shape gradient, value, JxW, radius and centre value equal bit for
//     bit to a fresh FEValues::reinit() on the assembly's mapping, on a
//     tube-like 2D mesh (6 x 20 cells, axisymmetric radii) and a randomly
//     distorted 3D mesh (no two cells alike);
//  2. the integrals they give against closed forms: Σ JxW = the mesh's area
//     or volume, and in 2D Σ 2πR JxW = π (R_o² − R_i²) L, the tube's volume
//     (QGauss(2) integrates the radius exactly);
//  3. translated cells share one entry (the 2D mesh: all 120 cells alike, at
//     most a handful of entries), every distorted 3D cell has its own, and
//     a budget too small for the entries gives none (the assembly then runs
//     FEValues per cell).
#include "check.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <anvil/mechanics/assembly_mapping.h>

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace dealii;
using namespace anvil::MechanicsAssembly;

namespace
{
  anvil::testing::Checks check;

  bool same(const double a, const double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

  /// Compares every cell's entry with FEValues; returns Σ JxW and Σ 2πR JxW.
  template <int dim>
  bool compare(const Triangulation<dim> &tria, const FiniteElement<dim> &fe,
               const AssemblyMapping<dim> &mapping, const ReferenceValues<dim> &values,
               const std::vector<unsigned int> &component, double &volume, double &ring_volume)
  {
    const QGauss<dim> quadrature(2);
    FEValues<dim>     v(mapping, fe, quadrature,
                    update_gradients | update_values | update_JxW_values | update_quadrature_points);
    FEValues<dim>     centre(mapping, fe, QMidpoint<dim>(),
                         update_gradients | update_values | update_quadrature_points);
    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    bool               equal = true;
    volume = ring_volume = 0;
    for (const auto &cell : tria.active_cell_iterators())
      {
        v.reinit(cell);
        centre.reinit(cell);
        const ReferenceCellValues c = values.cell(cell->active_cell_index());
        for (unsigned int q = 0; q < n_q; ++q)
          {
            for (unsigned int a = 0; a < n_dofs; ++a)
              {
                const Tensor<1, dim> g = v.shape_grad_component(a, q, component[a]);
                for (unsigned int d = 0; d < dim; ++d)
                  equal &= same(g[d], c.grad[(q * n_dofs + a) * dim + d]);
                equal &= same(v.shape_value_component(a, q, component[a]), c.value[q * n_dofs + a]);
              }
            equal &= same(v.JxW(q), c.JxW[q]);
            if (c.x)
              equal &= same(v.quadrature_point(q)[0], c.x[q]);
            volume += c.JxW[q];
            if (c.x)
              ring_volume += 2 * numbers::PI * c.x[q] * c.JxW[q];
          }
        for (unsigned int a = 0; a < n_dofs; ++a)
          {
            const Tensor<1, dim> g = centre.shape_grad_component(a, 0, component[a]);
            for (unsigned int d = 0; d < dim; ++d)
              equal &= same(g[d], c.centre_grad[a * dim + d]);
            equal &= same(centre.shape_value_component(a, 0, component[a]), c.centre_value[a]);
          }
        if (c.x)
          equal &= same(centre.quadrature_point(0)[0], c.x[n_q]);
      }
    return equal;
  }

  template <int dim>
  std::vector<unsigned int> components(const FiniteElement<dim> &fe)
  {
    std::vector<unsigned int> c(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < c.size(); ++i)
      c[i] = fe.system_to_component_index(i).first;
    return c;
  }

  /// The values of @p tria's cells (active order) on @p mapping, Q1^dim, QGauss(2).
  template <int dim>
  const ReferenceValues<dim> *build(const Triangulation<dim> &tria, const FiniteElement<dim> &fe,
                                    AssemblyMapping<dim> &mapping, const bool with_radius,
                                    const std::size_t max_bytes = 64u << 20)
  {
    std::vector<typename Triangulation<dim>::cell_iterator> cells;
    for (const auto &cell : tria.active_cell_iterators())
      cells.push_back(cell);
    mapping.reinit(cells, tria.n_active_cells());
    return mapping.reference_values(fe, QGauss<dim>(2), components(fe), with_radius, max_bytes);
  }
} // namespace

int main()
{
  {
    // The tube's section: R from 24.25 to 25.75 mm, 100 mm long.
    const double       Ri = 24.25, Ro = 25.75, L = 100;
    Triangulation<2>   tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {6, 20}, Point<2>(Ri, 0), Point<2>(Ro, L));
    const FESystem<2>  fe(FE_Q<2>(1), 2);
    const auto         component = components(fe);
    AssemblyMapping<2> mapping;
    const auto        *values = build(tria, fe, mapping, true);
    check(values != nullptr, "2D: reference values built");
    if (values)
      {
        double area, ring;
        check(compare(tria, fe, mapping, *values, component, area, ring),
              "2D: every value equal to FEValues bit for bit");
        std::printf("  area %.15g expected %.15g; ring volume %.15g expected %.15g\n", area,
                    (Ro - Ri) * L, ring, numbers::PI * (Ro * Ro - Ri * Ri) * L);
        check(std::abs(area - (Ro - Ri) * L) <= 1e-12 * (Ro - Ri) * L, "2D: sum JxW = area");
        check(std::abs(ring - numbers::PI * (Ro * Ro - Ri * Ri) * L) <=
                1e-12 * numbers::PI * (Ro * Ro - Ri * Ri) * L,
              "2D: sum 2 pi R JxW = pi (Ro^2 - Ri^2) L");
        std::printf("  %zu entries for %u cells\n", values->n_entries(), tria.n_active_cells());
        check(values->n_entries() <= 6, "2D: translated cells share their entries");
      }
    AssemblyMapping<2> small;
    check(build(tria, fe, small, true, 500) == nullptr,
          "2D: a budget below one entry (992 B) gives none");
  }
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_cube(tria, 3, 0., 2.);
    GridTools::distort_random(0.2, tria, true, 7);
    const FESystem<3>  fe(FE_Q<3>(1), 3);
    const auto         component = components(fe);
    AssemblyMapping<3> mapping;
    const auto        *values = build(tria, fe, mapping, false);
    check(values != nullptr, "3D: reference values built");
    if (values)
      {
        double volume, ring;
        check(compare(tria, fe, mapping, *values, component, volume, ring),
              "3D distorted: every value equal to FEValues bit for bit");
        std::printf("  volume %.15g expected %.15g\n", volume, GridTools::volume(tria));
        check(std::abs(volume - GridTools::volume(tria)) <= 1e-12 * volume, "3D: sum JxW = volume");
        std::printf("  %zu entries for %u cells\n", values->n_entries(), tria.n_active_cells());
        check(values->n_entries() == tria.n_active_cells(), "3D distorted: one entry per cell");
      }
  }
  return check.finish();
}
