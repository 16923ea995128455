#pragma once

// A multilevel preconditioner for the displacement system (private to
// linear_solver.cc and the tests): Chebyshev on D⁻¹K on the fine mesh, a
// coarse correction on the Q1 space of the mesh one refinement coarser,
// A_1 = Pᵀ K P, and so on: Chebyshev on D_ℓ⁻¹A_ℓ on each middle level ℓ,
// ML V-cycles (one, or 2–3 on a large one) on the coarsest A_{L−1}; one
// V-cycle per GMRES iteration. The smoothed levels' products (Chebyshev, the
// residuals) run on single-precision copies by nodal blocks
// (float_block_matrix.h, session 26); GMRES's own product stays in double.
// Two levels (session 20) cost P (~3.4 entries per fine row) and A_1 (1/8
// of the rows, 27-node stencil), ~1/7 of K, against ML's smoothed
// aggregation on 11 modes whose Galerkin product K·P alone peaks at
// ~3 KB/DoF (doc/memory.md, issue 15); at 1 M DoFs ML's set-up on A_1 set
// the run's peak, so large meshes get more levels (session 22).
//
// The number of levels is automatic: level ℓ ≥ 1 is coarsened once more
// while the mesh allows it (one more generation of parents, or an unrefined
// block's subdivisions still even) and A_ℓ has at least
// min_rows_to_coarsen rows, so that 20³ and 30³ keep two levels (A_1: 3 993
// and 12 288 rows) and 32³ … 68³ (1 M DoFs) get three (68³: 128 625 → 17 496
// rows, 17 cells: no fourth);
// ANVIL_GMG_LEVELS=n asks for n (as many as the mesh allows).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/linear_solver.h>

#include <array>
#include <functional>
#include <memory>
#include <vector>

class Epetra_CrsMatrix;
class Epetra_Map;
class Epetra_MultiVector;
class Epetra_Operator;
class Ifpack_Chebyshev;

namespace anvil
{
  class FloatBlockMatrix;
  class KluFactorization;

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
    /// Rows: the finer level's (K's for the first coarse space).
    std::unique_ptr<Epetra_CrsMatrix> P;
    /// (owned finer row, coarse dof) where the finer dof sits on a coarse node.
    std::vector<std::pair<int, int>> injection;
    unsigned int                     n_coarse_dofs = 0;
    /// Refinements between K's mesh and this space (1: the first coarse space).
    unsigned int                     depth = 1;
    /// Box path: this space's cells per direction (0: the hierarchy path),
    /// and every coarse dof's Dirichlet flag (all processes).
    std::array<unsigned int, 3> box_cells{};
    std::vector<int>            box_constrained;
    /// Hierarchy path, depth >= 2: (K's owned row, coarse dof) of the fine
    /// dofs at this space's nodes (depth 1: the injection).
    std::vector<std::pair<int, int>> fine_nodes;
    /// The next coarser space (its P's rows are this space's dofs), or none.
    std::unique_ptr<CoarseSpace> coarser;
    CoarseSpace();
    CoarseSpace(CoarseSpace &&);
    ~CoarseSpace();
  };

  /// Levels ℓ >= 1 with at least this many rows are coarsened again when
  /// the mesh allows: at 32³ cells (A_1 14 739 rows) three levels cost −4 %
  /// CPU, −10 % memory and −1.8 Krylov per solve against two, at 24³ (6 591)
  /// +4 % CPU; 30³ (12 288) keeps two (doc/linear_solver.md, session 22).
  constexpr unsigned int min_rows_to_coarsen = 14000;

  /// The automatic coarsest solve (geometric_coarse_space.cc): ML V-cycles
  /// per visit of a coarsest level of @p rows rows below @p fine_rows fine
  /// ones, or KLU.
  unsigned int coarsest_ml_cycles(unsigned int rows, unsigned int fine_rows);
  bool         coarsest_factored(unsigned int rows);

  namespace coarse_space_internal
  {
    /// An owned dof of a box level: its row, component, grid index (vertex), Dirichlet flag.
    template <int dim>
    struct GridDof
    {
      int                           row;
      unsigned int                  component;
      std::array<unsigned int, dim> index;
      bool                          constrained;
    };

    /// The box of @p cells (even) halved: its space, P for the rows of @p
    /// fine (one entry per owned row of @p rows; coarse_space_prolongation.cc).
    template <int dim>
    CoarseSpace coarsen_box(const std::vector<GridDof<dim>> &fine, const std::array<unsigned int, dim> &cells,
                            const Epetra_Map &rows, const Epetra_Map &range);

    /// Sorts and deduplicates @p nodes (owned fine dofs at the coarse
    /// nodes) and numbers them after the lower processes' (collective): the
    /// first coarse dof of this process; @p space gets n_coarse_dofs and the
    /// coarse map (coarse dof first + i for nodes[i]). Both hierarchy paths'.
    unsigned int number_coarse_nodes(std::vector<dealii::types::global_dof_index> &nodes, MPI_Comm comm,
                                     const Epetra_Map &rows, CoarseSpace &space);
  } // namespace coarse_space_internal

  /// InputError naming the parameters unless the cells have parents or the
  /// mesh is one block of equal cells with even subdivisions (collective).
  template <int dim>
  void check_geometric_coarse_space(const dealii::DoFHandler<dim> &dof_handler);

  /// P for K's rows (throws InputError as check_geometric_coarse_space()).
  template <int dim>
  CoarseSpace make_coarse_space(const dealii::DoFHandler<dim>           &dof_handler,
                                const dealii::AffineConstraints<double> &constraints,
                                const dealii::TrilinosWrappers::SparseMatrix &K);

  /**
   * Appends coarser spaces to @p first (coarse_space_levels.cc) while the
   * hierarchy has one more generation of parents (every active cell on one
   * level >= depth + 1) or the box's cells stay even, the last space has at
   * least @p min_rows dofs and there are fewer than @p max_levels levels
   * (the fine one counted). The levels it made (2: none added).
   */
  template <int dim>
  unsigned int add_coarse_levels(const dealii::DoFHandler<dim>           &dof_handler,
                                 const dealii::AffineConstraints<double> &constraints,
                                 const dealii::TrilinosWrappers::SparseMatrix &K,
                                 CoarseSpace                             &first,
                                 unsigned int                             max_levels,
                                 unsigned int                             min_rows);

  /// A_c = Pᵀ K P (EpetraExt, K P transient): the two-level cycle's.
  std::unique_ptr<Epetra_CrsMatrix> galerkin_product(const Epetra_CrsMatrix &K, const CoarseSpace &space);

  /// A_c = Pᵀ A P row by row of A_c (galerkin_product.cc): no A P, transients
  /// of P's size; twice EpetraExt's multiplications. The deeper cycles'.
  std::unique_ptr<Epetra_CrsMatrix> galerkin_product_by_rows(const Epetra_CrsMatrix &A, const Epetra_CrsMatrix &P);

  /// Finer-level vectors (owned rows) injected at the coarse nodes (owned coarse rows).
  std::vector<std::vector<double>> inject(const CoarseSpace &space, const std::vector<std::vector<double>> &fine,
                                          const Epetra_CrsMatrix &K);

  /// Chebyshev settings of the smoothed levels.
  struct LevelSmoothing
  {
    unsigned int fine_degree   = 4;
    /// Degree 8 on A_1 keeps Krylov at two levels' count (24³, 32³ with
    /// three levels: 4 → 28.7 / –, 6 → 26.6 / –, 8 → 25.8 / 27.3 per solve
    /// against 26.0 / 29.1 with two; doc/linear_solver.md, session 22).
    unsigned int middle_degree = 8;
    double       ratio         = 30;
    /// The smoothed levels' products in single precision by nodal blocks of
    /// this size (float_block_matrix.h; dim, or 0: Epetra's doubles).
    unsigned int single_blocks = 0;
  };

  /// How the coarsest level is solved: @p ml_cycles ML V-cycles (a fixed
  /// linear iteration on A_{L−1}), or the factorisation @p direct (kept by
  /// the caller across solves: KLU's analysis and pivots are reused).
  struct CoarsestSolve
  {
    unsigned int      ml_cycles = 1;
    KluFactorization *direct    = nullptr;
  };

  /**
   * One V-cycle per vmult (multilevel_cycle.cc); on level ℓ < L − 1:
   * y = S_ℓ b; y += P_ℓ cycle_{ℓ+1}(P_ℓᵀ (b − A_ℓ y)); y += S_ℓ (b − A_ℓ y),
   * S_ℓ: Chebyshev on D_ℓ⁻¹A_ℓ over [λ_max/ratio, λ_max] (λ_max by the power
   * method), the coarsest: CoarsestSolve (ML k times, or KLU). Two levels: session
   * 20's cycle, A_1 by galerkin_product(); more: galerkin_product_by_rows().
   */
  class MultilevelPreconditioner
  {
  public:
    /// @p space (and its coarser ones) outlives the preconditioner; @p coarse_modes: the coarsest level's.
    MultilevelPreconditioner(const dealii::TrilinosWrappers::SparseMatrix &K,
                             const CoarseSpace                            &space,
                             const std::vector<std::vector<double>>       &coarse_modes,
                             const IterativeSolverSettings                &coarse_settings,
                             const LevelSmoothing                         &smoothing,
                             bool                                          by_rows,
                             const CoarsestSolve                          &coarsest = CoarsestSolve());
    ~MultilevelPreconditioner();
    void vmult(dealii::TrilinosWrappers::MPI::Vector &dst, const dealii::TrilinosWrappers::MPI::Vector &src) const;
    unsigned int n_levels() const { return levels.size() + 1; }

    /// The coarsest level's matrix.
    dealii::TrilinosWrappers::SparseMatrix coarse_matrix;

  private:
    struct Level
    {
      const Epetra_CrsMatrix                     *A = nullptr;
      std::unique_ptr<Epetra_CrsMatrix>           kept_A; // middle levels
      /// A in single precision (float_block_matrix.h): the smoother's and
      /// the cycle's products; a middle level's kept_A is then freed.
      std::unique_ptr<FloatBlockMatrix>           single;
      /// What the smoother and the cycle's residuals multiply by.
      const Epetra_Operator                      *op = nullptr;
      const Epetra_CrsMatrix                     *P = nullptr;
      std::unique_ptr<Ifpack_Chebyshev>           smoother;
      mutable std::unique_ptr<Epetra_MultiVector> b, y, r, t;
      Level();
      Level(Level &&);
      ~Level();
    };
    void cycle(unsigned int level, const Epetra_MultiVector &b, Epetra_MultiVector &y) const;

    /// The smoothed levels 0 … L − 2.
    std::vector<Level>                                         levels;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> coarse_amg;
    CoarsestSolve                                              coarsest;
    /// The coarsest level's right-hand side and correction.
    mutable dealii::TrilinosWrappers::MPI::Vector              rc, ec;
    /// Its residual and the next cycle's correction, made only for
    /// ml_cycles > 1 (an empty deal.II vector allocates: the heap's layout,
    /// and so the BLAS kernels' rounding, stays that of one cycle).
    std::unique_ptr<dealii::TrilinosWrappers::MPI::Vector>     rk, ck;
  };

  /// GMRES right-preconditioned by the multilevel cycle (as solve_gmres()).
  /// The spaces and the coarse modes are kept across solves while the mesh and the
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
