#pragma once

// A two-level preconditioner for the displacement system (private to
// linear_solver.cc and the tests): Chebyshev on D⁻¹K on the fine mesh and a
// coarse correction on the Q1 space of the mesh one refinement coarser,
// A_c = Pᵀ K P solved by one ML V-cycle. Its memory is P (~3.4 entries per
// fine row) and A_c (1/8 of the rows, 27-node stencil), ~1/7 of K, against
// ML's smoothed aggregation on 11 modes whose Galerkin product K·P alone
// peaks at ~3 KB/DoF (doc/memory.md, issue 15).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/linear_solver.h>

#include <functional>
#include <memory>
#include <vector>

class Epetra_CrsMatrix;
class Epetra_Map;
class Epetra_MultiVector;
class Ifpack_Chebyshev;

namespace anvil
{
  /**
   * The prolongation from the coarse Q1^dim space into the fine one
   * (coarse_space_prolongation.cc). When every active cell has a parent (a
   * mesh built with Geometry/Global refinements >= 1: any bodies, gmsh,
   * curved or distorted cells), the coarse space is Q1^dim on the parent
   * level and P's rows are the FE's prolongation matrices, a coarse dof
   * being the fine dof at its parent vertex (same owner). Otherwise the
   * fine mesh must be one axis-parallel box of n_1 × … × n_dim equal cells,
   * n_d even (Geometry/Blocks, one block): the coarse mesh is the same box
   * with n_d / 2 cells, and a fine vertex of grid index i interpolates the
   * coarse nodes i/2 (i even) or (i ± 1)/2 with 1/2 each (i odd), the
   * tensor product of these in dim directions (exact parent arithmetic, in
   * the reference configuration: the nested interpolation is the same for
   * every isoparametric deformation of the two meshes, so P need not follow
   * the current one). Coarse dofs: dim (node) + component, node
   * lexicographic; owned in contiguous ranges of nodes per process.
   *
   * Dirichlet: a constrained fine dof keeps one entry, 1 in the column of
   * the coarse dof at its own position if it sits on a coarse node (0 rows
   * otherwise); no other fine dof interpolates a constrained coarse dof.
   * K's constrained rows and columns are zero but for the diagonal, so the
   * constrained coarse dof gets A_c's diagonal K_ff and no coupling.
   */
  struct CoarseSpace
  {
    std::unique_ptr<Epetra_Map>       coarse_map;
    std::unique_ptr<Epetra_CrsMatrix> P;
    /// (owned fine row, coarse dof) where the fine dof sits on a coarse node.
    std::vector<std::pair<int, int>> injection;
    unsigned int                     n_coarse_dofs = 0;
    CoarseSpace();
    CoarseSpace(CoarseSpace &&);
    ~CoarseSpace();
  };

  /// InputError naming the parameters unless the cells have parents or the
  /// mesh is one block of equal cells with even subdivisions (collective).
  template <int dim>
  void check_geometric_coarse_space(const dealii::DoFHandler<dim> &dof_handler);

  /// P for K's rows (throws InputError as check_geometric_coarse_space()).
  template <int dim>
  CoarseSpace make_coarse_space(const dealii::DoFHandler<dim>           &dof_handler,
                                const dealii::AffineConstraints<double> &constraints,
                                const dealii::TrilinosWrappers::SparseMatrix &K);

  /// A_c = Pᵀ K P (EpetraExt, K P transient).
  std::unique_ptr<Epetra_CrsMatrix> galerkin_product(const Epetra_CrsMatrix &K, const CoarseSpace &space);

  /// Fine-dof vectors injected at the coarse nodes (owned coarse rows).
  std::vector<std::vector<double>> inject(const CoarseSpace &space, const std::vector<std::vector<double>> &fine,
                                          const Epetra_CrsMatrix &K);

  /**
   * One V-cycle per vmult: y = S b; y += P M_c Pᵀ (b − K y); y += S (b − K y),
   * S: Chebyshev of @p degree on D⁻¹K over [λ_max/ratio, λ_max] (λ_max by
   * the power method), M_c: one ML V-cycle on A_c.
   */
  class TwoLevelPreconditioner
  {
  public:
    /// @p space outlives the preconditioner (kept across solves); @p coarse_modes: inject()'s.
    TwoLevelPreconditioner(const dealii::TrilinosWrappers::SparseMatrix &K,
                           const CoarseSpace                            &space,
                           const std::vector<std::vector<double>>       &coarse_modes,
                           const IterativeSolverSettings                &coarse_settings,
                           unsigned int                                  degree,
                           double                                        ratio);
    ~TwoLevelPreconditioner();
    void vmult(dealii::TrilinosWrappers::MPI::Vector &dst, const dealii::TrilinosWrappers::MPI::Vector &src) const;

    const CoarseSpace                                         &space;
    dealii::TrilinosWrappers::SparseMatrix                     coarse_matrix;

  private:
    const Epetra_CrsMatrix                                    &K;
    std::unique_ptr<Ifpack_Chebyshev>                          smoother;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> coarse_amg;
    mutable std::unique_ptr<Epetra_MultiVector>                r, t;
    mutable dealii::TrilinosWrappers::MPI::Vector              rc, ec;
  };

  /// GMRES right-preconditioned by the two-level cycle (as solve_gmres()).
  /// P and the coarse modes are kept across solves while the mesh and the
  /// Dirichlet set stay (@p fine_modes is called only when @p mode_set, a
  /// tag of the mode set, differs from the kept modes'; ANVIL_GMG_KEEP=0: never kept).
  template <int dim>
  unsigned int solve_two_level(const dealii::TrilinosWrappers::SparseMatrix &K,
                               dealii::TrilinosWrappers::MPI::Vector        &x,
                               const dealii::TrilinosWrappers::MPI::Vector  &b,
                               const dealii::DoFHandler<dim>                &dof_handler,
                               const dealii::AffineConstraints<double>      &constraints,
                               const std::function<std::vector<std::vector<double>>()> &fine_modes,
                               int                                           mode_set,
                               const IterativeSolverSettings                &settings);
} // namespace anvil
