// The V-cycle of the geometric coarse spaces (geometric_coarse_space.h).
// Two levels do what session 20's TwoLevelPreconditioner did, operation for
// operation (A_1 by EpetraExt, the same Chebyshev, the same ML), so their
// answers stay bit-identical; deeper cycles smooth each middle level with
// Chebyshev on D_ℓ⁻¹A_ℓ and form A_{ℓ+1} row by row (galerkin_product.cc).
// The coarsest level: ML once (bit-identical to session 22), k times on the
// residual, or KLU (CoarsestSolve; the rule in geometric_coarse_space.cc).
#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>

#include <anvil/core/klu_factorization.h>

#include "float_block_matrix.h"
#include "geometric_coarse_space.h"


DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <Ifpack_Chebyshev.h>
#include <Teuchos_ParameterList.hpp>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// Chebyshev of @p degree on D⁻¹A over [λ_max/ratio, λ_max], its
    /// products by @p op (A, or A in single precision).
    std::unique_ptr<Ifpack_Chebyshev> chebyshev(const Epetra_CrsMatrix &A, const Epetra_Operator &op,
                                                const unsigned int degree, const double ratio)
    {
      Epetra_Vector inverse_diagonal(A.RowMap());
      A.ExtractDiagonalCopy(inverse_diagonal);
      inverse_diagonal.Reciprocal(inverse_diagonal);
      double lambda_max = 0;
      Ifpack_Chebyshev::PowerMethod(op, inverse_diagonal, 10, lambda_max);
      const bool             own = &op == static_cast<const Epetra_Operator *>(&A);
      auto                   smoother = own ? std::make_unique<Ifpack_Chebyshev>(&A) : std::make_unique<Ifpack_Chebyshev>(&op);
      Teuchos::ParameterList list;
      // An operator that is not Epetra's matrix has no diagonal of its own.
      if (!own)
        list.set("chebyshev: operator inv diagonal", &inverse_diagonal);
      list.set("chebyshev: degree", static_cast<int>(degree));
      list.set("chebyshev: ratio eigenvalue", ratio);
      // The power method's estimate from below, raised as ML does.
      list.set("chebyshev: max eigenvalue", 1.1 * lambda_max);
      list.set("chebyshev: zero starting solution", true);
      smoother->SetParameters(list);
      AssertThrow(smoother->Initialize() == 0 && smoother->Compute() == 0,
                  ExcMessage("geometric coarse space: Chebyshev set-up failed"));
      return smoother;
    }
  } // namespace

  MultilevelPreconditioner::Level::Level()              = default;
  MultilevelPreconditioner::Level::Level(Level &&)      = default;
  MultilevelPreconditioner::Level::~Level()             = default;

  MultilevelPreconditioner::MultilevelPreconditioner(const TrilinosWrappers::SparseMatrix   &K,
                                                     const CoarseSpace                      &space,
                                                     const std::vector<std::vector<double>> &coarse_modes,
                                                     const IterativeSolverSettings          &coarse_settings,
                                                     const LevelSmoothing                   &smoothing,
                                                     const bool                              by_rows,
                                                     const CoarsestSolve                    &coarsest)
    : coarsest(coarsest)
  {
    std::vector<const CoarseSpace *> spaces;
    for (const CoarseSpace *s = &space; s; s = s->coarser.get())
      spaces.push_back(s);
    levels.resize(spaces.size());
    levels[0].A = &K.trilinos_matrix();
    // The operators finest first; each middle one is kept, the coarsest
    // copied into deal.II's matrix for ML and dropped.
    for (unsigned int l = 0; l < spaces.size(); ++l)
      {
        levels[l].P = spaces[l]->P.get();
        std::unique_ptr<Epetra_CrsMatrix> coarser =
          by_rows ? galerkin_product_by_rows(*levels[l].A, *spaces[l]->P) : galerkin_product(*levels[l].A, *spaces[l]);
        if (l + 1 < spaces.size())
          {
            levels[l + 1].kept_A = std::move(coarser);
            levels[l + 1].A      = levels[l + 1].kept_A.get();
          }
        else
          coarse_matrix.reinit(*coarser, true);
      }
    if (coarsest.direct)
      {
        // A new matrix object at every solve, which may reuse the freed
        // one's address on every process (KluFactorization then agrees,
        // session 24, but Amesos would keep the old object's maps): clear()
        // sends all to a new analysis (one process: KLU's analysis and
        // pivots are still reused while the pattern fits).
        coarsest.direct->clear();
        coarsest.direct->factorize(coarse_matrix);
      }
    else
      coarse_amg = build_amg(coarse_matrix, coarse_modes, coarse_settings);

    for (unsigned int l = 0; l < levels.size(); ++l)
      {
        Level &level = levels[l];
        if (smoothing.single_blocks > 0)
          level.single = FloatBlockMatrix::make(*level.A, smoothing.single_blocks);
        level.op       = level.single ? static_cast<const Epetra_Operator *>(level.single.get()) : level.A;
        level.smoother = chebyshev(*level.A, *level.op, l == 0 ? smoothing.fine_degree : smoothing.middle_degree,
                                   smoothing.ratio);
        // A middle level's double matrix served its coarser level's
        // Galerkin product and the diagonal: the float copy does the rest.
        if (level.single && level.kept_A)
          {
            level.kept_A.reset();
            level.A = nullptr;
          }
        const Epetra_Map &rows = level.op->OperatorRangeMap();
        level.r                = std::make_unique<Epetra_MultiVector>(rows, 1);
        level.t                = std::make_unique<Epetra_MultiVector>(rows, 1);
        if (l > 0)
          {
            level.b = std::make_unique<Epetra_MultiVector>(rows, 1);
            level.y = std::make_unique<Epetra_MultiVector>(rows, 1);
          }
      }
    const IndexSet coarse_owned = coarse_matrix.locally_owned_range_indices();
    rc.reinit(coarse_owned, K.get_mpi_communicator());
    ec.reinit(coarse_owned, K.get_mpi_communicator());
    if (!coarsest.direct && coarsest.ml_cycles > 1)
      {
        rk = std::make_unique<TrilinosWrappers::MPI::Vector>(coarse_owned, K.get_mpi_communicator());
        ck = std::make_unique<TrilinosWrappers::MPI::Vector>(coarse_owned, K.get_mpi_communicator());
      }
  }

  MultilevelPreconditioner::~MultilevelPreconditioner() = default;

  void MultilevelPreconditioner::vmult(TrilinosWrappers::MPI::Vector       &dst,
                                       const TrilinosWrappers::MPI::Vector &src) const
  {
    cycle(0, src.trilinos_vector(), dst.trilinos_vector());
  }

  void MultilevelPreconditioner::cycle(const unsigned int l, const Epetra_MultiVector &b, Epetra_MultiVector &y) const
  {
    const Level &level = levels[l];
    level.smoother->ApplyInverse(b, y);
    level.op->Apply(y, *level.r);
    level.r->Update(1., b, -1.);
    if (l + 1 == levels.size())
      {
        level.P->Multiply(true, *level.r, rc.trilinos_vector());
        if (coarsest.direct)
          coarsest.direct->solve(ec, rc);
        else
          {
            coarse_amg->vmult(ec, rc);
            // ML again on the residual: a fixed linear iteration, so GMRES
            // keeps a constant preconditioner.
            for (unsigned int k = 1; k < coarsest.ml_cycles; ++k)
              {
                coarse_matrix.vmult(*rk, ec);
                rk->sadd(-1., 1., rc);
                coarse_amg->vmult(*ck, *rk);
                ec += *ck;
              }
          }
        level.P->Multiply(false, ec.trilinos_vector(), *level.t);
      }
    else
      {
        const Level &next = levels[l + 1];
        level.P->Multiply(true, *level.r, *next.b);
        cycle(l + 1, *next.b, *next.y);
        level.P->Multiply(false, *next.y, *level.t);
      }
    y.Update(1., *level.t, 1.);
    level.op->Apply(y, *level.r);
    level.r->Update(1., b, -1.);
    level.smoother->ApplyInverse(*level.r, *level.t);
    y.Update(1., *level.t, 1.);
  }
} // namespace anvil
