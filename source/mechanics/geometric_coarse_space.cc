// The multilevel (geometric coarse spaces) preconditioner of the displacement
// system, its kept spaces and its solve: geometric_coarse_space.h.
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/vector_memory.h>

#include <anvil/core/input_error.h>
#include <anvil/core/klu_factorization.h>
#include <anvil/core/instantiate.h>

#include "geometric_coarse_space.h"
#include "gmres_run.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  CoarseSpace::CoarseSpace()              = default;
  CoarseSpace::CoarseSpace(CoarseSpace &&) = default;
  CoarseSpace::~CoarseSpace()             = default;

  std::unique_ptr<Epetra_CrsMatrix> galerkin_product(const Epetra_CrsMatrix &K, const CoarseSpace &space)
  {
    auto Ac = std::make_unique<Epetra_CrsMatrix>(Copy, *space.coarse_map, 0);
    {
      Epetra_CrsMatrix KP(Copy, K.RowMap(), 0);
      AssertThrow(EpetraExt::MatrixMatrix::Multiply(K, false, *space.P, false, KP) == 0,
                  ExcMessage("geometric coarse space: K P failed"));
      AssertThrow(EpetraExt::MatrixMatrix::Multiply(*space.P, true, KP, false, *Ac) == 0,
                  ExcMessage("geometric coarse space: Pᵀ K P failed"));
      // Benchmarks: the entries of the operators (12 B each in memory).
      if (std::getenv("ANVIL_GMG_LOG") && K.Comm().MyPID() == 0)
        std::cout << "geometric coarse space: K " << K.NumGlobalRows() << " rows, " << K.NumGlobalNonzeros()
                  << " entries; P " << space.P->NumGlobalNonzeros() << "; K P " << KP.NumGlobalNonzeros()
                  << "; A_c " << Ac->NumGlobalRows() << " rows, " << Ac->NumGlobalNonzeros() << std::endl;
    }
    return Ac;
  }

  unsigned int coarsest_ml_cycles(const unsigned int rows, const unsigned int fine_rows)
  {
    // A coarsest level the mesh could not coarsen (68³ and 34³: 17 odd
    // cells, 17 496 rows): one ML V-cycle on it is far from a solve. 34³
    // (two levels) with ML once, twice, three times on it: 28.7, 26.1, 25.3
    // Krylov per solve; a cycle there is ~20 % of a GMRES iteration's
    // matvec work, and two cost the same CPU as one. Below a deeper cycle
    // (1 M DoFs: 1/56 of the fine rows) a cycle is ~3 %: three
    // (doc/linear_solver.md, session 23).
    if (rows < min_rows_to_coarsen)
      return 1;
    return fine_rows >= 32ull * rows ? 3 : 2;
  }

  bool coarsest_factored(const unsigned int)
  {
    // KLU on 17 496 rows (34³'s coarsest, through ML's Amesos-KLU): 18 CPU s
    // per factorisation against ~0.6 s for the whole cycle's set-up with ML:
    // never automatic (doc/linear_solver.md, session 23).
    return false;
  }

  std::vector<std::vector<double>> inject(const CoarseSpace &space, const std::vector<std::vector<double>> &fine,
                                          const Epetra_CrsMatrix &K)
  {
    const MPI_Comm comm = dynamic_cast<const Epetra_MpiComm &>(K.Comm()).Comm();
    std::vector<std::vector<double>> coarse;
    std::vector<double>              all(space.n_coarse_dofs);
    for (const auto &mode : fine)
      {
        std::fill(all.begin(), all.end(), 0.);
        for (const auto &[row, k] : space.injection)
          all[k] = mode[row];
        // Each coarse dof coincides with one owned fine dof on one process.
        Utilities::MPI::sum(all, comm, all);
        std::vector<double> owned(space.coarse_map->NumMyElements());
        for (unsigned int i = 0; i < owned.size(); ++i)
          owned[i] = all[space.coarse_map->GID(i)];
        coarse.push_back(std::move(owned));
      }
    return coarse;
  }

  namespace
  {
    /**
     * The spaces (P, P₂, …) and the coarsest level's injected modes kept
     * across solves while the mesh, the
     * DoF numbering and the Dirichlet set do not change (contact and
     * plasticity change K, not P): dropped when the triangulation changes or
     * goes, rebuilt when the owned constrained dofs or K's rows differ. The
     * modes are those of the configuration of the solve that injected them
     * (near-null only for the coarse ML), kept per mode set (rigid/isochoric).
     */
    struct KeptSpace
    {
      const void                        *dof_handler = nullptr;
      std::uint64_t                      constrained = 0;
      std::unique_ptr<CoarseSpace>       space;
      unsigned int                       levels   = 2;
      int                                mode_set = -1;
      std::vector<std::vector<double>>   coarse_modes;
      /// The coarsest level's factorisation (when it is solved directly).
      std::unique_ptr<KluFactorization>  direct;
      CoarsestSolve                      coarsest;
      boost::signals2::scoped_connection change, clear;
      void                               drop()
      {
        space.reset();
        direct.reset();
        coarsest = CoarsestSolve();
        coarse_modes = std::vector<std::vector<double>>();
        mode_set     = -1;
        dof_handler  = nullptr;
      }
    };

    KeptSpace &kept_space()
    {
      static KeptSpace kept;
      return kept;
    }

    /// The owned constrained dofs (a hash, the same on every process).
    std::uint64_t constrained_signature(const AffineConstraints<double> &constraints, const IndexSet &owned,
                                        const MPI_Comm comm)
    {
      std::uint64_t h = 0;
      for (const auto &line : constraints.get_lines())
        if (owned.is_element(line.index))
          {
            std::uint64_t z = line.index + 0x9e3779b97f4a7c15ull; // splitmix64
            z               = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
            z               = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
            h += z ^ (z >> 31);
          }
      return Utilities::MPI::sum(h, comm);
    }

    /// The kept P valid for this solve (all processes agree).
    template <int dim>
    bool kept_is_valid(const KeptSpace &kept, const DoFHandler<dim> &dof_handler, const std::uint64_t constrained,
                       const Epetra_Map &rows)
    {
      int same = kept.space && kept.dof_handler == &dof_handler && kept.constrained == constrained;
      if (same)
        {
          const Epetra_Map &mine = kept.space->P->RangeMap();
          same = mine.NumMyElements() == rows.NumMyElements() &&
                 std::equal(mine.MyGlobalElements(), mine.MyGlobalElements() + mine.NumMyElements(),
                            rows.MyGlobalElements());
        }
      return Utilities::MPI::min(same, dof_handler.get_communicator()) == 1;
    }

    /// The coarsest level's solve (geometric_coarse_space.h, coarsest_ml_cycles());
    /// ANVIL_GMG_COARSE_CYCLES=k (ML k times) and ANVIL_GMG_COARSE_DIRECT=1
    /// (KLU) override the rule for benchmarks. The factorisation is kept in
    /// @p direct across solves (its analysis and pivots reused).
    CoarsestSolve coarsest_solve(const CoarseSpace &first, std::unique_ptr<KluFactorization> &direct)
    {
      const CoarseSpace *last = &first;
      while (last->coarser)
        last = last->coarser.get();
      CoarsestSolve solve;
      solve.ml_cycles = coarsest_ml_cycles(last->n_coarse_dofs, first.P->NumGlobalRows());
      if (const char *s = std::getenv("ANVIL_GMG_COARSE_CYCLES"))
        solve.ml_cycles = std::max(1, std::atoi(s));
      bool factored = coarsest_factored(last->n_coarse_dofs);
      if (const char *s = std::getenv("ANVIL_GMG_COARSE_DIRECT"))
        factored = std::string(s) == "1";
      if (factored)
        {
          if (!direct)
            direct = std::make_unique<KluFactorization>();
          solve.direct = direct.get();
        }
      return solve;
    }
  } // namespace

  template <int dim>
  unsigned int solve_two_level(const TrilinosWrappers::SparseMatrix    &K,
                               TrilinosWrappers::MPI::Vector           &x,
                               const TrilinosWrappers::MPI::Vector     &b,
                               const DoFHandler<dim>                   &dof_handler,
                               const AffineConstraints<double>         &constraints,
                               const std::function<std::vector<std::vector<double>>()> &fine_modes,
                               const int                                mode_set,
                               const IterativeSolverSettings           &settings)
  {
    IterativeSolverSettings coarse = settings;
    coarse.components              = dim;
    coarse.aggregate_blocks        = false;
    LevelSmoothing smoothing;
    if (const char *s = std::getenv("ANVIL_GMG_DEGREE"))
      smoothing.fine_degree = std::max(1, std::atoi(s));
    if (const char *s = std::getenv("ANVIL_GMG_MIDDLE_DEGREE"))
      smoothing.middle_degree = std::max(1, std::atoi(s));
    if (const char *s = std::getenv("ANVIL_GMG_RATIO"))
      smoothing.ratio = std::atof(s);
    // Single-precision smoothing by nodal blocks (float_block_matrix.h);
    // ANVIL_GMG_PRECISION=double keeps Epetra's matrices (benchmarks, tests).
    const char *precision   = std::getenv("ANVIL_GMG_PRECISION");
    smoothing.single_blocks = precision && std::string(precision) == "double" ? 0 : dim;
    // Benchmarks and tests: ANVIL_GMG_LEVELS=n asks for n levels (as many as
    // the mesh allows), else the automatic rule (geometric_coarse_space.h).
    unsigned int max_levels = 16, min_rows = min_rows_to_coarsen;
    if (const char *s = std::getenv("ANVIL_GMG_LEVELS"))
      {
        max_levels = std::max(2, std::atoi(s));
        min_rows   = 0;
      }
    // Benchmarks: ANVIL_GMG_KEEP=0 builds P and the modes at every solve (session 20).
    const bool  keep  = !std::getenv("ANVIL_GMG_KEEP") || std::string(std::getenv("ANVIL_GMG_KEEP")) != "0";
    const bool  log   = std::getenv("ANVIL_GMG_LOG") && Utilities::MPI::this_mpi_process(K.get_mpi_communicator()) == 0;
    KeptSpace  &kept  = kept_space();
    Timer       timer;
    const auto  built = [&](const char *what) {
      if (log)
        std::cout << "geometric coarse space: " << what << " in " << timer.cpu_time() << " CPU s" << std::endl;
    };
    const std::uint64_t constrained =
      constrained_signature(constraints, dof_handler.locally_owned_dofs(), dof_handler.get_communicator());
    if (!keep || !kept_is_valid(kept, dof_handler, constrained, K.trilinos_matrix().RowMap()))
      {
        kept.drop();
        kept.space       = std::make_unique<CoarseSpace>(make_coarse_space(dof_handler, constraints, K));
        kept.levels      = add_coarse_levels(dof_handler, constraints, K, *kept.space, max_levels, min_rows);
        kept.coarsest    = coarsest_solve(*kept.space, kept.direct);
        kept.dof_handler = &dof_handler;
        kept.constrained = constrained;
        auto &signals    = dof_handler.get_triangulation().signals;
        kept.change      = signals.any_change.connect([] { kept_space().drop(); });
        kept.clear       = signals.clear.connect([] { kept_space().drop(); });
        if (log)
          {
            std::cout << "geometric coarse space: " << kept.levels << " levels, rows " << K.m();
            for (const CoarseSpace *s = kept.space.get(); s; s = s->coarser.get())
              std::cout << ", " << s->n_coarse_dofs;
            std::cout << "; coarsest: ";
            if (kept.coarsest.direct)
              std::cout << "KLU" << std::endl;
            else
              std::cout << "ML x" << kept.coarsest.ml_cycles << std::endl;
          }
        built("P built");
      }
    if (kept.mode_set != mode_set)
      {
        timer.restart();
        // Injected level by level down to the coarsest (its ML's near-null space).
        kept.coarse_modes = inject(*kept.space, fine_modes(), K.trilinos_matrix());
        for (const CoarseSpace *s = kept.space->coarser.get(); s; s = s->coarser.get())
          kept.coarse_modes = inject(*s, kept.coarse_modes, K.trilinos_matrix());
        kept.mode_set = mode_set;
        built("coarse modes injected");
      }
    unsigned int iterations = 0;
    {
      // Deeper cycles form their operators row by row (no A P transient);
      // ANVIL_GMG_BY_ROWS=0/1 chooses for benchmarks.
      bool by_rows = kept.levels > 2;
      if (const char *s = std::getenv("ANVIL_GMG_BY_ROWS"))
        by_rows = std::string(s) == "1";
      timer.restart();
      const MultilevelPreconditioner preconditioner(K, *kept.space, kept.coarse_modes, coarse, smoothing, by_rows,
                                                    kept.coarsest);
      built("cycle set up");
      // The same GMRES as ML's (stall stop, pool given back).
      iterations = run_gmres(K, x, b, preconditioner, settings);
    }
    if (!keep)
      kept.drop();
    return iterations;
  }

#define INSTANTIATE(dim)                                                                                   \
  template unsigned int solve_two_level(const TrilinosWrappers::SparseMatrix &, TrilinosWrappers::MPI::Vector &, \
                                        const TrilinosWrappers::MPI::Vector &, const DoFHandler<dim> &,    \
                                        const AffineConstraints<double> &,                                 \
                                        const std::function<std::vector<std::vector<double>>()> &,       \
                                        int, const IterativeSolverSettings &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
