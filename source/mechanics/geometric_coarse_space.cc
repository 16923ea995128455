// The two-level (geometric coarse space) preconditioner of the displacement
// system: geometric_coarse_space.h.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/vector_memory.h>

#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>

#include "geometric_coarse_space.h"
#include "gmres_run.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <Ifpack_Chebyshev.h>
#include <Teuchos_ParameterList.hpp>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  CoarseSpace::CoarseSpace()              = default;
  CoarseSpace::CoarseSpace(CoarseSpace &&) = default;
  CoarseSpace::~CoarseSpace()             = default;

  namespace
  {
    /// The fine mesh as one box of equal cells: lower corner, cell size, cells per direction.
    template <int dim>
    struct Box
    {
      std::array<double, dim>       lower, h;
      std::array<unsigned int, dim> cells;
      /// The grid index of @p x in direction d.
      unsigned int index(const Point<dim> &x, const unsigned int d) const
      {
        return static_cast<unsigned int>(std::lround((x[d] - lower[d]) / h[d]));
      }
    };

    template <int dim>
    Box<dim> find_box(const DoFHandler<dim> &dof_handler)
    {
      const MPI_Comm comm = dof_handler.get_communicator();
      const char    *what = "Mechanics/Linear solver/Preconditioner = geometric needs one axis-parallel block "
                            "of equal cells with even subdivisions (Geometry/Blocks)";
      std::array<double, dim> lower, upper, h;
      lower.fill(std::numeric_limits<double>::max());
      upper.fill(-std::numeric_limits<double>::max());
      h.fill(std::numeric_limits<double>::max());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (unsigned int d = 0; d < dim; ++d)
            {
              double a = std::numeric_limits<double>::max(), b = -a;
              for (const unsigned int v : cell->vertex_indices())
                {
                  a = std::min(a, cell->vertex(v)[d]);
                  b = std::max(b, cell->vertex(v)[d]);
                }
              lower[d] = std::min(lower[d], a);
              upper[d] = std::max(upper[d], b);
              h[d]     = std::min(h[d], b - a);
            }
      Box<dim>      box;
      std::size_t   cells    = 1;
      int           off_grid = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          box.lower[d] = Utilities::MPI::min(lower[d], comm);
          box.h[d]     = Utilities::MPI::min(h[d], comm);
          const double length = Utilities::MPI::max(upper[d], comm) - box.lower[d];
          box.cells[d]        = static_cast<unsigned int>(std::lround(length / box.h[d]));
          if (box.cells[d] % 2 != 0 || std::abs(box.cells[d] * box.h[d] - length) > 1e-8 * length)
            off_grid = 1;
          cells *= box.cells[d];
        }
      if (cells != dof_handler.get_triangulation().n_global_active_cells())
        off_grid = 1;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < dim; ++d)
              if (std::abs(cell->vertex(v)[d] - box.lower[d] - box.index(cell->vertex(v), d) * box.h[d]) >
                  1e-8 * box.h[d])
                off_grid = 1;
      if (Utilities::MPI::max(off_grid, comm) != 0)
        throw InputError(what);
      return box;
    }
  } // namespace

  template <int dim>
  void check_geometric_coarse_space(const DoFHandler<dim> &dof_handler)
  {
    if (dof_handler.get_fe().degree != 1 || dof_handler.get_fe().n_components() != dim)
      throw InputError("Mechanics/Linear solver/Preconditioner = geometric: Q1 elements only (Polynomial degree = 1)");
    find_box(dof_handler);
  }

  template <int dim>
  CoarseSpace make_coarse_space(const DoFHandler<dim>                &dof_handler,
                                const AffineConstraints<double>      &constraints,
                                const TrilinosWrappers::SparseMatrix &K)
  {
    check_geometric_coarse_space(dof_handler);
    const MPI_Comm          comm = dof_handler.get_communicator();
    const Box<dim>          box  = find_box(dof_handler);
    const Epetra_CrsMatrix &A    = K.trilinos_matrix();
    const Epetra_Map       &rows = A.RowMap();

    // Coarse node (I_1, …, I_dim), lexicographic.
    std::array<unsigned int, dim> stride;
    unsigned int                  nodes = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        stride[d] = nodes;
        nodes *= box.cells[d] / 2 + 1;
      }
    CoarseSpace space;
    space.n_coarse_dofs = dim * nodes;
    const unsigned int p = Utilities::MPI::this_mpi_process(comm), np = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int first = dim * (std::size_t(nodes) * p / np), last = dim * (std::size_t(nodes) * (p + 1) / np);
    std::vector<int>   gids(last - first);
    for (unsigned int k = 0; k < gids.size(); ++k)
      gids[k] = first + k;
    space.coarse_map = std::make_unique<Epetra_Map>(static_cast<int>(space.n_coarse_dofs), static_cast<int>(gids.size()),
                                                    gids.data(), 0, A.Comm());

    // Every owned fine dof once: its grid index and component.
    struct FineDof
    {
      int                           row;
      unsigned int                  component;
      std::array<unsigned int, dim> index;
      bool                          constrained;
    };
    std::vector<FineDof> fine;
    fine.reserve(rows.NumMyElements());
    std::vector<bool> seen(rows.NumMyElements(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int c = 0; c < dim; ++c)
            {
              const types::global_dof_index dof = cell->vertex_dof_index(v, c);
              const int                     row = rows.LID(static_cast<int>(dof));
              if (row < 0 || seen[row])
                continue;
              seen[row] = true;
              FineDof f{row, c, {}, constraints.is_constrained(dof)};
              for (unsigned int d = 0; d < dim; ++d)
                f.index[d] = box.index(cell->vertex(v), d);
              fine.push_back(f);
            }
    const auto on_coarse_node = [](const FineDof &f) {
      return std::all_of(f.index.begin(), f.index.end(), [](const unsigned int i) { return i % 2 == 0; });
    };
    const auto coarse_dof = [&](const std::array<unsigned int, dim> &I, const unsigned int c) {
      unsigned int node = 0;
      for (unsigned int d = 0; d < dim; ++d)
        node += I[d] * stride[d];
      return static_cast<int>(dim * node + c);
    };
    // A coarse dof is constrained where the fine dof at its node is (all processes).
    std::vector<int> constrained(space.n_coarse_dofs, 0);
    for (const FineDof &f : fine)
      if (on_coarse_node(f))
        {
          std::array<unsigned int, dim> I;
          for (unsigned int d = 0; d < dim; ++d)
            I[d] = f.index[d] / 2;
          const int k = coarse_dof(I, f.component);
          constrained[k] = f.constrained ? 1 : 0;
          space.injection.emplace_back(f.row, k);
        }
    Utilities::MPI::max(constrained, comm, constrained);

    space.P = std::make_unique<Epetra_CrsMatrix>(Copy, rows, 1 << dim);
    std::vector<int>    columns;
    std::vector<double> values;
    for (const FineDof &f : fine)
      {
        columns.clear();
        values.clear();
        if (f.constrained)
          {
            if (on_coarse_node(f))
              {
                std::array<unsigned int, dim> I;
                for (unsigned int d = 0; d < dim; ++d)
                  I[d] = f.index[d] / 2;
                columns.push_back(coarse_dof(I, f.component));
                values.push_back(1.);
              }
          }
        else
          // The tensor product of the 1D weights: 1 at an even index, 1/2 at
          // the two coarse neighbours of an odd one.
          for (unsigned int corner = 0; corner < (1u << dim); ++corner)
            {
              std::array<unsigned int, dim> I;
              double                        w = 1;
              for (unsigned int d = 0; d < dim && w > 0; ++d)
                {
                  const unsigned int i = f.index[d], up = (corner >> d) & 1;
                  if (i % 2 == 0)
                    w *= up ? 0. : 1.;
                  else
                    w *= 0.5;
                  I[d] = i / 2 + up;
                }
              if (w == 0)
                continue;
              const int k = coarse_dof(I, f.component);
              if (constrained[k])
                continue;
              columns.push_back(k);
              values.push_back(w);
            }
        if (!columns.empty())
          AssertThrow(space.P->InsertGlobalValues(rows.GID(f.row), columns.size(), values.data(), columns.data()) == 0,
                      ExcMessage("geometric coarse space: P's insertion failed"));
      }
    AssertThrow(space.P->FillComplete(*space.coarse_map, A.RangeMap()) == 0,
                ExcMessage("geometric coarse space: P's FillComplete failed"));
    return space;
  }

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

  TwoLevelPreconditioner::TwoLevelPreconditioner(const TrilinosWrappers::SparseMatrix &K_,
                                                 CoarseSpace                         &&space_,
                                                 const std::vector<std::vector<double>> &fine_modes,
                                                 const IterativeSolverSettings        &coarse_settings,
                                                 const unsigned int                    degree,
                                                 const double                          ratio)
    : space(std::move(space_))
    , K(K_.trilinos_matrix())
  {
    {
      const std::unique_ptr<Epetra_CrsMatrix> Ac = galerkin_product(K, space);
      coarse_matrix.reinit(*Ac, true);
    }
    coarse_amg = build_amg(coarse_matrix, inject(space, fine_modes, K), coarse_settings);

    Epetra_Vector inverse_diagonal(K.RowMap());
    K.ExtractDiagonalCopy(inverse_diagonal);
    inverse_diagonal.Reciprocal(inverse_diagonal);
    double lambda_max = 0;
    Ifpack_Chebyshev::PowerMethod(K, inverse_diagonal, 10, lambda_max);
    smoother = std::make_unique<Ifpack_Chebyshev>(&K);
    Teuchos::ParameterList list;
    list.set("chebyshev: degree", static_cast<int>(degree));
    list.set("chebyshev: ratio eigenvalue", ratio);
    // The power method's estimate from below, raised as ML does.
    list.set("chebyshev: max eigenvalue", 1.1 * lambda_max);
    list.set("chebyshev: zero starting solution", true);
    smoother->SetParameters(list);
    AssertThrow(smoother->Initialize() == 0 && smoother->Compute() == 0,
                ExcMessage("geometric coarse space: Chebyshev set-up failed"));

    r = std::make_unique<Epetra_MultiVector>(K.RowMap(), 1);
    t = std::make_unique<Epetra_MultiVector>(K.RowMap(), 1);
    const IndexSet coarse_owned = coarse_matrix.locally_owned_range_indices();
    rc.reinit(coarse_owned, K_.get_mpi_communicator());
    ec.reinit(coarse_owned, K_.get_mpi_communicator());
  }

  TwoLevelPreconditioner::~TwoLevelPreconditioner() = default;

  void TwoLevelPreconditioner::vmult(TrilinosWrappers::MPI::Vector       &dst,
                                     const TrilinosWrappers::MPI::Vector &src) const
  {
    const Epetra_MultiVector &b = src.trilinos_vector();
    Epetra_MultiVector       &y = dst.trilinos_vector();
    smoother->ApplyInverse(b, y);
    K.Apply(y, *r);
    r->Update(1., b, -1.);
    space.P->Multiply(true, *r, rc.trilinos_vector());
    coarse_amg->vmult(ec, rc);
    space.P->Multiply(false, ec.trilinos_vector(), *t);
    y.Update(1., *t, 1.);
    K.Apply(y, *r);
    r->Update(1., b, -1.);
    smoother->ApplyInverse(*r, *t);
    y.Update(1., *t, 1.);
  }

  template <int dim>
  unsigned int solve_two_level(const TrilinosWrappers::SparseMatrix    &K,
                               TrilinosWrappers::MPI::Vector           &x,
                               const TrilinosWrappers::MPI::Vector     &b,
                               const DoFHandler<dim>                   &dof_handler,
                               const AffineConstraints<double>         &constraints,
                               const std::function<std::vector<std::vector<double>>()> &fine_modes,
                               const IterativeSolverSettings           &settings)
  {
    IterativeSolverSettings coarse = settings;
    coarse.components              = dim;
    coarse.aggregate_blocks        = false;
    unsigned int degree            = 4;
    double       ratio             = 30;
    if (const char *s = std::getenv("ANVIL_GMG_DEGREE"))
      degree = std::max(1, std::atoi(s));
    if (const char *s = std::getenv("ANVIL_GMG_RATIO"))
      ratio = std::atof(s);
    const TwoLevelPreconditioner preconditioner(K, make_coarse_space(dof_handler, constraints, K), fine_modes(),
                                                coarse, degree, ratio);
    // The same GMRES as ML's (stall stop, pool given back).
    return run_gmres(K, x, b, preconditioner, settings);
  }

#define INSTANTIATE(dim)                                                                                   \
  template void         check_geometric_coarse_space(const DoFHandler<dim> &);                             \
  template CoarseSpace  make_coarse_space(const DoFHandler<dim> &, const AffineConstraints<double> &,      \
                                         const TrilinosWrappers::SparseMatrix &);                          \
  template unsigned int solve_two_level(const TrilinosWrappers::SparseMatrix &, TrilinosWrappers::MPI::Vector &, \
                                        const TrilinosWrappers::MPI::Vector &, const DoFHandler<dim> &,    \
                                        const AffineConstraints<double> &,                                 \
                                        const std::function<std::vector<std::vector<double>>()> &,       \
                                        const IterativeSolverSettings &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
