#pragma once

// The iterative solve of the displacement system: GMRES preconditioned by
// smoothed-aggregation AMG (Trilinos ML) whose near-null space is the
// rigid-body modes of the body, aggregated node by node (doc/linear_solver.md).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace anvil
{
  /**
   * The rigid-body motions of the current configuration x = X + u, as
   * vectors over the locally owned dofs (in the order of
   * dof_handler.locally_owned_dofs()): dim translations, then the
   * rotations: 2D one, (−y, x); 3D three, e_k × (x − c). c is the centroid
   * of the support points (all processes). Plane strain and 3D: all of them
   * are zero-energy modes of the unsupported body. @p u: the displacement,
   * ghosted (u = 0 if null).
   *
   * @p axisymmetric: x is the radius, y the axis. Only the axial
   * translation is a zero-energy mode (a radial translation or an in-plane
   * rotation strains the hoop direction, ε_θθ = u_r / r); the three are
   * still returned, the radial translation and the rotation being near-null
   * on aggregates far from the axis (their energy relative to the
   * aggregate's is O((h/r)²), doc/linear_solver.md).
   */
  struct RigidBodyModes
  {
    std::vector<std::vector<double>> modes;
    /// Every node's dim dofs are consecutive rows (k dim + c): ML may
    /// aggregate nodes ("PDE equations" = dim) on every process.
    bool node_blocks = true;
  };
  template <int dim>
  RigidBodyModes rigid_body_modes(const dealii::Mapping<dim>                  &mapping,
                                  const dealii::DoFHandler<dim>               &dof_handler,
                                  const dealii::TrilinosWrappers::MPI::Vector *u);

  /**
   * DoFs up to which Mechanics/Linear solver/Type = automatic factorizes
   * (KLU) rather than iterates: where the two cost the same per Newton
   * iteration on the plastic F-bar block, one core (doc/linear_solver.md).
   * 3D is lower: the factor's fill grows as N^(4/3) against N log N in 2D.
   */
  constexpr unsigned int measured_direct_solver_limit(const int dim)
  {
    return dim == 2 ? 50000 : 20000;
  }

  struct IterativeSolverSettings
  {
    double       tolerance      = 1e-8; // relative to |b|
    unsigned int max_iterations = 1000;
    bool         higher_order   = false; // Q2
    unsigned int components     = 1;     // dofs per node, contiguous ("PDE equations")
  };

  /**
   * x = K⁻¹ b by GMRES(30) and one AMG V-cycle per iteration, the hierarchy
   * built on @p near_null_space (vectors over the locally owned rows of K).
   * Returns the iterations; throws SolverControl::NoConvergence.
   */
  unsigned int solve_gmres_amg(const dealii::TrilinosWrappers::SparseMatrix     &K,
                               dealii::TrilinosWrappers::MPI::Vector            &x,
                               const dealii::TrilinosWrappers::MPI::Vector      &b,
                               const std::vector<std::vector<double>>           &near_null_space,
                               const IterativeSolverSettings                    &settings);
} // namespace anvil
