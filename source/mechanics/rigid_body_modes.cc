// The rigid-body modes of the displacement field: AMG's near-null space
// (deal.II 9.4 has no DoFTools::extract_rigid_body_modes).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/linear_solver.h>

#include <array>
#include <cstdlib>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// The displacement of a rotation about axis e_k, ω = e_k, at x − c:
    /// ω × (x − c) (in 2D the single rotation about z: (−y, x)).
    template <int dim>
    double rotation_component(const unsigned int k, const unsigned int c, const Tensor<1, dim> &r)
    {
      if (dim == 2)
        return c == 0 ? -r[1] : r[0];
      // (e_k × r)_c = ε_ckj r_j, j the third index; ε_ckj = +1 when
      // (c, k, j) is an even permutation of (0, 1, 2), i.e. k = c + 1 mod 3.
      if (c == k)
        return 0;
      const unsigned int j = 3 - k - c;
      return (c + 1) % 3 == k ? r[j] : -r[j];
    }
  } // namespace

  template <int dim>
  RigidBodyModes rigid_body_modes(const Mapping<dim>                       &mapping,
                                  const DoFHandler<dim>                    &dof_handler,
                                  const TrilinosWrappers::MPI::Vector      *u,
                                  const bool                                isochoric)
  {
    const auto        &fe    = dof_handler.get_fe();
    const IndexSet    &owned = dof_handler.locally_owned_dofs();
    const unsigned int n     = owned.n_elements();
    // The support point x = X + u of every owned dof, and its component.
    std::vector<Point<dim>>   x(n);
    std::vector<unsigned int> component(n, numbers::invalid_unsigned_int);
    RigidBodyModes            result;
    result.components = dim;

    FEValues<dim> fe_values(mapping, fe, Quadrature<dim>(fe.get_unit_support_points()),
                            update_quadrature_points | update_values);
    std::vector<Vector<double>>          u_at(fe.n_dofs_per_cell(), Vector<double>(dim));
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    // An owned dof always sits on a locally owned cell (its owner is the
    // lowest subdomain among the cells around it); ghost cells add nothing.
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          if (u)
            fe_values.get_function_values(*u, u_at);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              if (!owned.is_element(dofs[i]))
                continue;
              const unsigned int row = owned.index_within_set(dofs[i]);
              const unsigned int c   = fe.system_to_component_index(i).first;
              x[row]                 = fe_values.quadrature_point(i);
              if (u)
                for (unsigned int d = 0; d < dim; ++d)
                  x[row][d] += u_at[i][d];
              component[row] = c;
            }
        }
    // ML aggregates node k from rows k dim .. k dim + dim − 1: each row's
    // component must be row mod dim, and the rows of a node one point.
    for (unsigned int row = 0; row < n; ++row)
      if (component[row] != row % dim ||
          (row % dim > 0 && x[row].distance(x[row - row % dim]) > 1e-12 * (1 + x[row].norm())))
        result.node_blocks = false;
    result.node_blocks =
      Utilities::MPI::min(result.node_blocks ? 1 : 0, dof_handler.get_communicator()) == 1;

    // Rotations about the centroid: better conditioned than about the origin
    // when the body lies far from it (the same span either way).
    std::array<double, dim + 1> sums{};
    for (unsigned int row = 0; row < n; ++row)
      {
        for (unsigned int d = 0; d < dim; ++d)
          sums[d] += x[row][d];
        sums[dim] += 1;
      }
    Utilities::MPI::sum(ArrayView<const double>(sums.data(), sums.size()),
                        dof_handler.get_communicator(), ArrayView<double>(sums.data(), sums.size()));
    Tensor<1, dim> centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = sums[d] / std::max(sums[dim], 1.);

    const unsigned int n_rotations = dim == 2 ? 1 : 3;
    result.modes.assign(dim + n_rotations, std::vector<double>(n, 0.));
    for (unsigned int row = 0; row < n; ++row)
      {
        const unsigned int c = component[row];
        result.modes[c][row] = 1;
        const Tensor<1, dim> r = x[row] - Point<dim>(centre);
        for (unsigned int k = 0; k < n_rotations; ++k)
          result.modes[dim + k][row] = rotation_component<dim>(dim == 2 ? 2 : k, c, r);
      }
    // The isochoric linear fields u = G (x − c), G symmetric and traceless
    // (Mechanics/Linear solver/AMG isochoric modes; ANVIL_ISOCHORIC_MODES=1
    // for benchmarks). They are not null vectors (their energy is 2G|G|²,
    // not κ), but they are the low-energy fields of nearly incompressible
    // (plastic) flow that the rigid motions miss: with Chebyshev 5 on the
    // plastic F-bar block 3D 20^3 61.3 -> 28.5 Krylov iterations per solve,
    // at 5/3 (3D: 11/6) the prolongator's columns (doc/linear_solver.md).
    if (isochoric || std::getenv("ANVIL_ISOCHORIC_MODES"))
      {
        std::vector<std::array<double, 9>> gradients; // row-major dim × dim
        if (dim == 2)
          gradients = {{{1, 0, 0, -1}}, {{0, 1, 1, 0}}};
        else
          gradients = {{{1, 0, 0, 0, -1, 0, 0, 0, 0}}, {{0, 0, 0, 0, 1, 0, 0, 0, -1}},
                       {{0, 1, 0, 1, 0, 0, 0, 0, 0}},  {{0, 0, 1, 0, 0, 0, 1, 0, 0}},
                       {{0, 0, 0, 0, 0, 1, 0, 1, 0}}};
        for (const auto &G : gradients)
          {
            std::vector<double> mode(n);
            for (unsigned int row = 0; row < n; ++row)
              {
                const unsigned int   c = component[row];
                const Tensor<1, dim> r = x[row] - Point<dim>(centre);
                for (unsigned int d = 0; d < dim; ++d)
                  mode[row] += G[c * dim + d] * r[d];
              }
            result.modes.push_back(mode);
          }
      }
    return result;
  }

#define INSTANTIATE(dim)                                                                     \
  template RigidBodyModes rigid_body_modes(const Mapping<dim> &, const DoFHandler<dim> &,  \
                                           const TrilinosWrappers::MPI::Vector *, bool);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
