#pragma once

// The iterative solve of the displacement system: GMRES preconditioned by
// smoothed-aggregation AMG (Trilinos ML) whose near-null space is the
// rigid-body modes of the body, aggregated node by node (doc/linear_solver.md).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/block_smoother.h>

#include <functional>
#include <string>
#include <memory>
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
   *
   * @p isochoric: append the linear isochoric fields u = G (x − c), G
   * symmetric and traceless (2D two, 3D five): not null vectors, but the
   * low-energy fields of a nearly incompressible (plastic F-bar) tangent,
   * which the rigid motions miss (doc/linear_solver.md, session 14).
   */
  struct RigidBodyModes
  {
    std::vector<std::vector<double>> modes;
    /// Every node's dim dofs are consecutive rows (k dim + c): ML may
    /// aggregate nodes ("PDE equations" = dim) on every process.
    bool node_blocks = true;
    /// dofs per node (dim).
    unsigned int components = 1;
  };
  template <int dim>
  RigidBodyModes rigid_body_modes(const dealii::Mapping<dim>                  &mapping,
                                  const dealii::DoFHandler<dim>               &dof_handler,
                                  const dealii::TrilinosWrappers::MPI::Vector *u,
                                  bool isochoric = false);

  /**
   * DoFs up to which Mechanics/Linear solver/Type = automatic factorizes
   * (KLU) rather than iterates (contrib/bench/solver_scaling.py, one core,
   * doc/linear_solver.md). 2D: on the plastic F-bar square the two cost the
   * same per solve at 33 282 DoFs and KLU is 1.7 times slower at 132 098;
   * on the thin contact strip (2 cells thick, little fill) KLU stays 1.5 to
   * 3 times faster up to 192 006: 50 000 between the two. 3D: AMG wins from
   * 2187 DoFs (0.21 against 0.29 s per solve) and by 8.7 times at 6591; below
   * ML's coarse size (2000 rows) AMG is one KLU solve anyway. The factor
   * fills in far more in 3D (nested dissection: O(N^4/3) entries and O(N^2)
   * work against O(N log N) and O(N^1.5) in 2D).
   */
  constexpr unsigned int measured_direct_solver_limit(const int dim)
  {
    return dim == 2 ? 50000 : 2000;
  }

  /// GMRES's Krylov basis before a restart: the default of Mechanics/Linear
  /// solver/GMRES restart (parameters.cc, where the choice is documented)
  /// and of the structs that carry it.
  constexpr unsigned int default_gmres_restart = 60;

  struct IterativeSolverSettings
  {
    double       tolerance      = 1e-8; // relative to |b|
    unsigned int max_iterations = 1000;
    /// GMRES's Krylov basis before a restart (8 B per DoF per vector).
    unsigned int restart        = default_gmres_restart;
    bool         higher_order   = false; // Q2
    /// Chebyshev degree of ML's smoother on every level (the fine level's
    /// unless aggregate_blocks).
    unsigned int smoother_degree = 2;
    /// Chebyshev's range: it damps the eigenvalues of D⁻¹K in
    /// [λ_max / ratio, λ_max] (ML's "smoother: Chebyshev alpha", deal.II's
    /// 10; MueLu's "chebyshev: ratio eigenvalue"). With the isochoric modes
    /// 100 reaches the low-energy isochoric fields a plastic tangent has
    /// below λ_max / 10 (doc/linear_solver.md, session 17).
    double       chebyshev_ratio = 10;
    /// ML's "aggregation: threshold" (MueLu's drop tolerance).
    double       aggregation_threshold = 0.02;
    /// Rows below which a level is solved by KLU.
    unsigned int coarse_size = 2000;
    /// Plain (unsmoothed) aggregation: the tentative prolongator, whose
    /// Galerkin products are ~30 % of the smoothed one's memory in 3D at
    /// 1.6-1.8x the Krylov iterations (doc/memory.md, session 18).
    bool         plain_aggregation = false;
    /// A W-cycle (ML's "prec type" MGW, MueLu's "cycle type" W): each coarse
    /// level is visited twice per visit of the finer one. Holds the 2D plastic
    /// count as the hierarchy deepens (doc/linear_solver.md, session 25).
    bool         w_cycle = false;
    unsigned int components     = 1;     // dofs per node, contiguous ("PDE equations")
    /// ReusedAMG: iterations allowed to a kept hierarchy, in units of its
    /// first solve's (0: a new hierarchy for every solve).
    double       rebuild_growth = 0;
    /// Fine level smoothed by AggregateBlockSmoother (block_smoother.h)
    /// instead of ML's Chebyshev; needs components > 1 or scalar rows.
    bool         aggregate_blocks = false;
    /// The AMG library: Trilinos ML (deal.II's PreconditionAMG) or MueLu
    /// (build_muelu(); ML's settings in MueLu's names).
    enum class Package { ml, muelu } package = Package::ml;
  };

  /**
   * Set ML parameters from "name=value; name:int=3; name:double=0.1;
   * sublist/name:bool=true" (a value is a string unless its name ends in
   * :int, :double or :bool). build_amg() applies the environment variable
   * ANVIL_ML_PARAMETERS after its own settings: the benchmarks' way to try
   * ML's options without a rebuild (doc/linear_solver.md).
   */
  void apply_ml_overrides(Teuchos::ParameterList &list, const std::string &overrides);

  /// The smoothed-aggregation hierarchy of K on @p near_null_space
  /// (vectors over the locally owned rows of K).
  std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG>
  build_amg(const dealii::TrilinosWrappers::SparseMatrix &K,
            const std::vector<std::vector<double>>       &near_null_space,
            const IterativeSolverSettings                &settings);

  /**
   * The same hierarchy built by MueLu (smoothed aggregation on the same
   * near-null space, node aggregation, drop tolerance 0.02, Chebyshev of
   * the same degree, KLU2 on the coarse level ≤ 2000 rows). Debian's MueLu
   * is Tpetra-only: the module libanvil-muelu.so
   * (source/mechanics/muelu_preconditioner.cc), loaded from libanvil's
   * folder on first use, so that runs on ML load none of Tpetra, Kokkos
   * kernels, MueLu, Ifpack2, Amesos2, copies K into a Tpetra matrix and
   * applies one V-cycle per vmult. ANVIL_MUELU_PARAMETERS overrides MueLu's
   * parameters as ANVIL_ML_PARAMETERS does ML's. doc/linear_solver.md,
   * session 16. Returned as a PreconditionAMG (its Epetra operator is
   * MueLu's) so that ReusedAMG keeps either.
   */
  std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG>
  build_muelu(const dealii::TrilinosWrappers::SparseMatrix &K,
              const std::vector<std::vector<double>>       &near_null_space,
              const IterativeSolverSettings                &settings);

  /**
   * GMRES + AMG whose hierarchy may outlive a solve. Building it
   * (aggregation, prolongator smoothing, Galerkin products) costs several
   * V-cycles; where the tangent changes little between Newton iterations
   * and steps (elastic bodies, contact) an older hierarchy is as good and
   * the set-up is saved (the fine-level smoother and the residual use the
   * current K, which the kept hierarchy references). With rebuild_growth
   * g > 0 the kept hierarchy gets g times the iterations of its first solve;
   * if GMRES has not converged by then, a fresh hierarchy continues from the
   * iterate reached. g = 0 builds one for every solve (the default:
   * spreading plasticity changes the tangent too much, doc/linear_solver.md).
   */
  class ReusedAMG
  {
  public:
    /// x = K⁻¹ b; @p modes is called only when a hierarchy is built.
    unsigned int solve(const dealii::TrilinosWrappers::SparseMatrix                 &K,
                       dealii::TrilinosWrappers::MPI::Vector                        &x,
                       const dealii::TrilinosWrappers::MPI::Vector                  &b,
                       const std::function<RigidBodyModes()>                       &modes,
                       const IterativeSolverSettings                                &settings);
    /// Forget the hierarchy (K was re-created: a new pattern).
    void clear()
    {
      amg.reset();
      smoother.reset();
    }
    /// Hierarchies built so far (benchmarks).
    unsigned int builds() const { return n_builds; }

  private:
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
    /// The fine-level smoother ML's hierarchy calls (aggregate_blocks).
    std::unique_ptr<AggregateBlockSmoother> smoother;
    const dealii::TrilinosWrappers::SparseMatrix              *matrix = nullptr;
    unsigned int first_iterations = 0, n_builds = 0;
  };

  /**
   * x = K⁻¹ b by GMRES(30), right-preconditioned by one V-cycle of @p amg
   * per iteration. Returns the iterations; throws SolverControl::NoConvergence.
   */
  unsigned int solve_gmres(const dealii::TrilinosWrappers::SparseMatrix      &K,
                           dealii::TrilinosWrappers::MPI::Vector             &x,
                           const dealii::TrilinosWrappers::MPI::Vector       &b,
                           const dealii::TrilinosWrappers::PreconditionAMG   &amg,
                           const IterativeSolverSettings                     &settings);
} // namespace anvil
