// The prolongation P of the geometric coarse space (geometric_coarse_space.h):
// from the mesh hierarchy when the fine cells have parents (any mesh built
// with Geometry/Global refinements >= 1: two bodies, gmsh, curved or
// distorted cells), else session 20's parent arithmetic for one unrefined
// block with even subdivisions; any other mesh is refused.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>

#include "geometric_coarse_space.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  namespace
  {
    const char *const refusal =
      "Mechanics/Linear solver/Preconditioner = geometric needs a mesh with a coarser level: set "
      "Geometry/Global refinements >= 1 (the coarse space is the mesh before the last refinement), "
      "or give Geometry/Blocks as one block with even subdivisions";

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
      const char    *what = refusal;
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

    /// Session 20's parent arithmetic for one unrefined block (level 0: no parents).
    template <int dim>
    CoarseSpace make_box_space(const DoFHandler<dim>                &dof_handler,
                               const AffineConstraints<double>      &constraints,
                               const TrilinosWrappers::SparseMatrix &K)
    {
      const Box<dim>          box  = find_box(dof_handler);
      const Epetra_CrsMatrix &A    = K.trilinos_matrix();
      const Epetra_Map       &rows = A.RowMap();

      // Every owned fine dof once: its grid index and component.
      std::vector<coarse_space_internal::GridDof<dim>> fine;
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
                coarse_space_internal::GridDof<dim> f{row, c, {}, constraints.is_constrained(dof)};
                for (unsigned int d = 0; d < dim; ++d)
                  f.index[d] = box.index(cell->vertex(v), d);
                fine.push_back(f);
              }
      return coarse_space_internal::coarsen_box<dim>(fine, box.cells, rows, A.RangeMap());
    }

    /// The child number of @p cell in its parent.
    template <int dim>
    unsigned int child_number(const typename DoFHandler<dim>::active_cell_iterator &cell)
    {
      const auto parent = cell->parent();
      for (unsigned int k = 0; k < parent->n_children(); ++k)
        if (parent->child(k) == cell)
          return k;
      AssertThrow(false, ExcInternalError());
      return 0;
    }

    /// Every active cell on one level >= 1 (one global refinement of the level above, no hanging nodes).
    template <int dim>
    bool has_parent_level(const DoFHandler<dim> &dof_handler)
    {
      unsigned int lowest = std::numeric_limits<unsigned int>::max(), highest = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            lowest  = std::min(lowest, static_cast<unsigned int>(cell->level()));
            highest = std::max(highest, static_cast<unsigned int>(cell->level()));
          }
      const MPI_Comm comm = dof_handler.get_communicator();
      lowest              = Utilities::MPI::min(lowest, comm);
      highest             = Utilities::MPI::max(highest, comm);
      return lowest >= 1 && lowest == highest;
    }

    /**
     * P from the hierarchy: the coarse space is Q1^dim on the parent level, a
     * coarse dof is the fine dof at the parent's vertex (vertex k of child k:
     * its owner and its Dirichlet status are the fine dof's), and a fine row
     * is the FE's prolongation matrix of its cell's child number — exact in
     * reference coordinates, for any parent shape and any manifold. Coarse
     * dofs numbered contiguously per process in the order of their fine dofs
     * (a node's components stay consecutive, as the coarse ML needs). The
     * parent's vertices are its children's: all siblings of an owned cell
     * share its parent's centre, so they are owned or ghosts.
     */
    template <int dim>
    CoarseSpace make_hierarchy_space(const DoFHandler<dim>                &dof_handler,
                                     const AffineConstraints<double>      &constraints,
                                     const TrilinosWrappers::SparseMatrix &K)
    {
      const MPI_Comm            comm  = dof_handler.get_communicator();
      const Epetra_CrsMatrix   &A     = K.trilinos_matrix();
      const Epetra_Map         &rows  = A.RowMap();
      const FiniteElement<dim> &fe    = dof_handler.get_fe();
      const IndexSet           &owned = dof_handler.locally_owned_dofs();

      std::vector<types::global_dof_index> nodes; // owned fine dofs at parent vertices
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const unsigned int k = child_number<dim>(cell);
            for (unsigned int c = 0; c < dim; ++c)
              if (owned.is_element(cell->vertex_dof_index(k, c)))
                nodes.push_back(cell->vertex_dof_index(k, c));
          }
      CoarseSpace        space;
      const unsigned int first  = coarse_space_internal::number_coarse_nodes(nodes, comm, rows, space);
      const unsigned int n_mine = nodes.size();

      // Each fine dof's coarse dof k where it sits on a parent vertex: k free,
      // −k − 2 constrained, −1 elsewhere (exact in double); ghosts included.
      TrilinosWrappers::MPI::Vector coarse_id(owned, DoFTools::extract_locally_relevant_dofs(dof_handler), comm);
      {
        TrilinosWrappers::MPI::Vector id(owned, comm);
        id = -1.;
        for (unsigned int i = 0; i < n_mine; ++i)
          id[nodes[i]] = constraints.is_constrained(nodes[i]) ? -double(first + i) - 2 : double(first + i);
        id.compress(VectorOperation::insert);
        coarse_id = id;
      }
      nodes = std::vector<types::global_dof_index>();

      const unsigned int                   n = fe.n_dofs_per_cell();
      std::vector<types::global_dof_index> dofs(n);
      std::vector<long long>               parent_ids(n);
      std::vector<bool>                    seen(rows.NumMyElements(), false);
      std::vector<int>                     columns;
      std::vector<double>                  values;
      space.P = std::make_unique<Epetra_CrsMatrix>(Copy, rows, 1 << dim);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const unsigned int k      = child_number<dim>(cell);
            const auto         parent = cell->parent();
            cell->get_dof_indices(dofs);
            for (unsigned int j = 0; j < n; ++j)
              {
                const auto [c, v] = fe.system_to_component_index(j);
                const auto sibling = parent->child(v);
                AssertThrow(!sibling->is_artificial(), ExcMessage("geometric coarse space: a sibling not present"));
                parent_ids[j] = std::llround(coarse_id(sibling->vertex_dof_index(v, c)));
                AssertThrow(parent_ids[j] != -1, ExcMessage("geometric coarse space: a parent vertex without a coarse dof"));
              }
            const FullMatrix<double> &R = fe.get_prolongation_matrix(k);
            for (unsigned int i = 0; i < n; ++i)
              {
                const int row = rows.LID(static_cast<int>(dofs[i]));
                if (row < 0 || seen[row])
                  continue;
                seen[row]          = true;
                const long long me = std::llround(coarse_id(dofs[i]));
                if (me != -1)
                  space.injection.emplace_back(row, static_cast<int>(me >= 0 ? me : -me - 2));
                columns.clear();
                values.clear();
                // As session 20: a constrained fine dof keeps 1 at its own
                // coarse dof (if on a parent vertex), a free one drops the
                // constrained coarse dofs.
                if (constraints.is_constrained(dofs[i]))
                  {
                    if (me != -1)
                      {
                        columns.push_back(static_cast<int>(me >= 0 ? me : -me - 2));
                        values.push_back(1.);
                      }
                  }
                else
                  for (unsigned int j = 0; j < n; ++j)
                    if (R(i, j) != 0 && parent_ids[j] >= 0)
                      {
                        columns.push_back(static_cast<int>(parent_ids[j]));
                        values.push_back(R(i, j));
                      }
                if (!columns.empty())
                  AssertThrow(space.P->InsertGlobalValues(rows.GID(row), columns.size(), values.data(),
                                                          columns.data()) == 0,
                              ExcMessage("geometric coarse space: P's insertion failed"));
              }
          }
      AssertThrow(space.P->FillComplete(*space.coarse_map, A.RangeMap()) == 0,
                  ExcMessage("geometric coarse space: P's FillComplete failed"));
      return space;
    }
  } // namespace

  namespace coarse_space_internal
  {
    template <int dim>
    CoarseSpace coarsen_box(const std::vector<GridDof<dim>> &fine, const std::array<unsigned int, dim> &cells,
                            const Epetra_Map &rows, const Epetra_Map &range)
    {
      const MPI_Comm comm = dynamic_cast<const Epetra_MpiComm &>(rows.Comm()).Comm();
      // Coarse node (I_1, …, I_dim), lexicographic.
      std::array<unsigned int, dim> stride;
      unsigned int                  nodes = 1;
      CoarseSpace                   space;
      for (unsigned int d = 0; d < dim; ++d)
        {
          stride[d] = nodes;
          nodes *= cells[d] / 2 + 1;
          space.box_cells[d] = cells[d] / 2;
        }
      space.n_coarse_dofs = dim * nodes;
      const unsigned int p = Utilities::MPI::this_mpi_process(comm), np = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int first = dim * (std::size_t(nodes) * p / np), last = dim * (std::size_t(nodes) * (p + 1) / np);
      std::vector<int>   gids(last - first);
      for (unsigned int k = 0; k < gids.size(); ++k)
        gids[k] = first + k;
      space.coarse_map = std::make_unique<Epetra_Map>(static_cast<int>(space.n_coarse_dofs), static_cast<int>(gids.size()),
                                                      gids.data(), 0, rows.Comm());

      const auto on_coarse_node = [](const GridDof<dim> &f) {
        return std::all_of(f.index.begin(), f.index.end(), [](const unsigned int i) { return i % 2 == 0; });
      };
      const auto coarse_dof = [&](const std::array<unsigned int, dim> &I, const unsigned int c) {
        unsigned int node = 0;
        for (unsigned int d = 0; d < dim; ++d)
          node += I[d] * stride[d];
        return static_cast<int>(dim * node + c);
      };
      // A coarse dof is constrained where the fine dof at its node is (all processes).
      std::vector<int> &constrained = space.box_constrained;
      constrained.assign(space.n_coarse_dofs, 0);
      for (const GridDof<dim> &f : fine)
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
      for (const GridDof<dim> &f : fine)
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
      AssertThrow(space.P->FillComplete(*space.coarse_map, range) == 0,
                  ExcMessage("geometric coarse space: P's FillComplete failed"));
      return space;
    }
  } // namespace coarse_space_internal

  unsigned int coarse_space_internal::number_coarse_nodes(std::vector<types::global_dof_index> &nodes,
                                                          const MPI_Comm comm, const Epetra_Map &rows,
                                                          CoarseSpace &space)
  {
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    const unsigned int n_mine = nodes.size();
    unsigned int       first  = 0;
    const int          ierr   = MPI_Exscan(&n_mine, &first, 1, MPI_UNSIGNED, MPI_SUM, comm);
    AssertThrowMPI(ierr);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0; // MPI_Exscan leaves rank 0's undefined
    space.n_coarse_dofs = Utilities::MPI::sum(n_mine, comm);
    std::vector<int> gids(n_mine);
    for (unsigned int i = 0; i < n_mine; ++i)
      gids[i] = first + i;
    space.coarse_map = std::make_unique<Epetra_Map>(static_cast<int>(space.n_coarse_dofs), static_cast<int>(n_mine),
                                                    gids.data(), 0, rows.Comm());
    return first;
  }

  template <int dim>
  void check_geometric_coarse_space(const DoFHandler<dim> &dof_handler)
  {
    if (dof_handler.get_fe().degree != 1 || dof_handler.get_fe().n_components() != dim)
      throw InputError("Mechanics/Linear solver/Preconditioner = geometric: Q1 elements only (Polynomial degree = 1)");
    if (!has_parent_level(dof_handler))
      find_box(dof_handler);
  }

  template <int dim>
  CoarseSpace make_coarse_space(const DoFHandler<dim>                &dof_handler,
                                const AffineConstraints<double>      &constraints,
                                const TrilinosWrappers::SparseMatrix &K)
  {
    check_geometric_coarse_space(dof_handler);
    if (has_parent_level(dof_handler))
      return make_hierarchy_space(dof_handler, constraints, K);
    return make_box_space(dof_handler, constraints, K);
  }

#define INSTANTIATE(dim)                                                                              \
  template CoarseSpace coarse_space_internal::coarsen_box<dim>(                                          \
    const std::vector<coarse_space_internal::GridDof<dim>> &, const std::array<unsigned int, dim> &,  \
    const Epetra_Map &, const Epetra_Map &);                                                          \
  template void        check_geometric_coarse_space(const DoFHandler<dim> &);                         \
  template CoarseSpace make_coarse_space(const DoFHandler<dim> &, const AffineConstraints<double> &,  \
                                         const TrilinosWrappers::SparseMatrix &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
