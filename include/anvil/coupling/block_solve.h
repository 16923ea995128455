#pragma once
// The linear solve of a two-field Newton step (coupling/monolithic.cc):
//   [ K_uu  K_uT ] [x_u]   [b_u]
//   [ K_Tu  K_TT ] [x_T] = [b_T],
// the fields numbered one after the other (u first, T shifted by n_u).
#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/linear_solver.h>

namespace anvil
{
  struct TwoFieldSystem
  {
    const dealii::TrilinosWrappers::SparseMatrix &matrix; // both fields, numbered u then T
    const dealii::TrilinosWrappers::SparseMatrix &K_uu;   // the diagonal blocks, for the AMG
    const dealii::TrilinosWrappers::SparseMatrix &K_TT;
    const dealii::IndexSet                       &owned_u, &owned_T, &owned;
    dealii::types::global_dof_index               n_u;
    /// Near-null space of K_uu for its AMG (rigid_body_modes()); null: the
    /// constant modes only, dof by dof.
    const RigidBodyModes *u_modes = nullptr;
  };

  /**
   * Solve directly (Amesos KLU on the whole matrix) or by GMRES(50) to 10⁻¹⁰
   * of |b|, left-preconditioned by one AMG per diagonal block (K_uu's on
   * system.u_modes, node by node, as the mechanics' own solve). @p x_u, @p x_T
   * take the field layouts of @p b_u, @p b_T. Returns the linear iterations
   * (1 for the direct solve); throws if the solver fails.
   */
  unsigned int solve_two_field(const TwoFieldSystem                       &system,
                               const dealii::TrilinosWrappers::MPI::Vector &b_u,
                               const dealii::TrilinosWrappers::MPI::Vector &b_T,
                               dealii::TrilinosWrappers::MPI::Vector       &x_u,
                               dealii::TrilinosWrappers::MPI::Vector       &x_T,
                               bool                                         direct);
} // namespace anvil
