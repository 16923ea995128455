// The blocks as arrays and the per-body description made from them, against
// deal.II's own route (independent answers):
//  1. append_box() gives GridGenerator::subdivided_hyper_rectangle's mesh to
//     the last bit: the same vertices (compared bitwise), the same cells
//     (vertex indices), and with colorize = true its boundary ids (0 .. 2 dim - 1
//     at x0, x1, y0, y1, z0, z1) on every boundary face, shifted by the
//     box's first id.
//  2. describe_per_body() of several blocks (2D, 3D) equals, entry for entry,
//     create_description_from_triangulation() of the whole Triangulation
//     partitioned by partition_per_body(), on this run's processes (1, 2, 3):
//     the same cells, vertices, ids, owners, boundary and manifold ids.
//  3. The fully distributed triangulation of create_per_body() (the boundary
//     ids set on the faces after creation) and the one from deal.II's
//     description have the same cells, in the same order, with the same
//     vertices, owners and boundary ids on every face (ghosts included).
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/geometry/mesh_arrays.h>
#include <anvil/geometry/partition.h>

#include "check.h"

#include <cstring>
#include <sstream>

using namespace dealii;

namespace
{
  anvil::testing::Checks check;

  template <int dim>
  bool same_bits(const Point<dim> &a, const Point<dim> &b)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (std::memcmp(&a[d], &b[d], sizeof(double)) != 0)
        return false;
    return true;
  }

  template <int dim>
  void box_as_deal_ii(const Point<dim> &lower, const Point<dim> &upper, const std::vector<unsigned int> &n)
  {
    anvil::MeshArrays<dim> mesh;
    anvil::append_box(mesh, lower, upper, n, 3, 10);
    Triangulation<dim> piece;
    GridGenerator::subdivided_hyper_rectangle(piece, n, lower, upper, /*colorize=*/true);
    bool vertices = mesh.vertices.size() == piece.n_vertices();
    for (unsigned int v = 0; vertices && v < mesh.vertices.size(); ++v)
      vertices = same_bits(mesh.vertices[v], piece.get_vertices()[v]);
    bool cells = mesh.cells.size() == piece.n_active_cells(), faces = cells, material = true;
    unsigned int n_boundary = 0;
    for (const auto &cell : piece.active_cell_iterators())
      if (cells)
        {
          const auto &data = mesh.cells[cell->index()];
          for (const unsigned int v : cell->vertex_indices())
            cells = cells && data.vertices[v] == cell->vertex_index(v);
          material = material && data.material_id == 3;
          for (const unsigned int f : cell->face_indices())
            {
              const auto id = mesh.face_ids[cell->index()][f];
              if (cell->face(f)->at_boundary())
                ++n_boundary, faces = faces && id == 10 + cell->face(f)->boundary_id();
              else
                faces = faces && id == numbers::internal_face_boundary_id;
            }
        }
    std::ostringstream what;
    what << dim << "D box " << lower << " to " << upper << ", " << mesh.cells.size() << " cells: ";
    check(vertices, what.str() + "vertices bit for bit those of subdivided_hyper_rectangle");
    check(cells && material, what.str() + "cells (vertex indices) those of subdivided_hyper_rectangle");
    check(faces && n_boundary > 0, what.str() + std::to_string(n_boundary) +
                                     " boundary faces with colorize's ids + 10, inner faces internal");
  }

  template <int dim>
  std::string difference(const TriangulationDescription::Description<dim, dim> &a,
                         const TriangulationDescription::Description<dim, dim> &b)
  {
    if (a.coarse_cell_vertices.size() != b.coarse_cell_vertices.size())
      return "vertex counts " + std::to_string(a.coarse_cell_vertices.size()) + ", " +
             std::to_string(b.coarse_cell_vertices.size());
    for (unsigned int v = 0; v < a.coarse_cell_vertices.size(); ++v)
      if (!same_bits(a.coarse_cell_vertices[v], b.coarse_cell_vertices[v]))
        return "vertex " + std::to_string(v);
    if (a.coarse_cells.size() != b.coarse_cells.size() || a.cell_infos.size() != b.cell_infos.size())
      return "cell or level counts";
    if (a.coarse_cell_index_to_coarse_cell_id != b.coarse_cell_index_to_coarse_cell_id)
      return "coarse cell ids";
    for (unsigned int c = 0; c < a.coarse_cells.size(); ++c)
      if (a.coarse_cells[c].vertices != b.coarse_cells[c].vertices ||
          a.coarse_cells[c].material_id != b.coarse_cells[c].material_id ||
          a.coarse_cells[c].manifold_id != b.coarse_cells[c].manifold_id)
        return "coarse cell " + std::to_string(c);
    for (unsigned int l = 0; l < a.cell_infos.size(); ++l)
      {
        if (a.cell_infos[l].size() != b.cell_infos[l].size())
          return "cell info counts";
        for (unsigned int c = 0; c < a.cell_infos[l].size(); ++c)
          {
            const auto &p = a.cell_infos[l][c], &q = b.cell_infos[l][c];
            const std::string at = " of cell info " + std::to_string(c);
            if (p.id != q.id)
              return "id" + at;
            if (p.subdomain_id != q.subdomain_id)
              return "subdomain id" + at + ": " + std::to_string(p.subdomain_id) + ", " +
                     std::to_string(q.subdomain_id);
            if (p.level_subdomain_id != q.level_subdomain_id)
              return "level subdomain id" + at + ": " + std::to_string(p.level_subdomain_id) + ", " +
                     std::to_string(q.level_subdomain_id);
            if (p.manifold_id != q.manifold_id || p.manifold_line_ids != q.manifold_line_ids ||
                (dim == 3 && p.manifold_quad_ids != q.manifold_quad_ids))
              return "manifold ids" + at;
            if (p.boundary_ids != q.boundary_ids)
              return "boundary ids" + at;
          }
      }
    if (a.settings != b.settings || a.smoothing != b.smoothing)
      return "settings or smoothing";
    return "";
  }

  template <int dim>
  void description_as_deal_ii(const MPI_Comm comm)
  {
    // Three bodies: two touching blocks (separate vertices) and one apart,
    // of unequal lengths and axes.
    anvil::MeshArrays<dim> mesh;
    Point<dim>             a, b, c, d, e, f;
    for (unsigned int k = 0; k < dim; ++k)
      a[k] = 0, b[k] = 1, c[k] = 0, d[k] = 0.5, e[k] = 2, f[k] = 2.3;
    b[0] = 3.7, c[1] = 1, d[1] = 1.4, d[0] = 3.7, f[1] = 5;
    std::vector<unsigned int> n1(dim, 2), n2(dim, 1), n3(dim, 2);
    n1[0] = 37, n2[0] = 18, n3[1] = 23;
    anvil::append_box(mesh, a, b, n1, 0, 0);
    anvil::append_box(mesh, c, d, n2, 1, 2 * dim);
    anvil::append_box(mesh, e, f, n3, 2, 4 * dim);
    const auto mine = anvil::describe_per_body(mesh, comm);

    Triangulation<dim> serial;
    mesh.create_triangulation(serial);
    anvil::partition_per_body(serial, Utilities::MPI::n_mpi_processes(comm));
    const auto theirs = TriangulationDescription::Utilities::create_description_from_triangulation(serial, comm);
    const std::string diff = difference(mine, theirs);
    const unsigned int failed = Utilities::MPI::sum(diff.empty() ? 0u : 1u, comm);
    check(failed == 0, std::to_string(dim) + "D, 3 bodies, " + std::to_string(mesh.cells.size()) +
                         " cells on " + std::to_string(Utilities::MPI::n_mpi_processes(comm)) +
                         " processes: describe_per_body = deal.II's description" +
                         (diff.empty() ? std::string() : " (first difference here: " + diff + ")"));

    parallel::fullydistributed::Triangulation<dim> one(comm), other(comm);
    anvil::create_per_body(mesh, one); // boundary ids set after creation
    other.create_triangulation(theirs);
    bool same = one.n_global_active_cells() == mesh.cells.size() &&
                one.n_locally_owned_active_cells() == other.n_locally_owned_active_cells();
    auto p = one.begin_active(), q = other.begin_active();
    for (; same && p != one.end() && q != other.end(); ++p, ++q)
      {
        same = p->id() == q->id() && p->subdomain_id() == q->subdomain_id() &&
               p->material_id() == q->material_id();
        for (const unsigned int v : p->vertex_indices())
          same = same && same_bits(p->vertex(v), q->vertex(v));
        for (const unsigned int f : p->face_indices())
          same = same && p->face(f)->boundary_id() == q->face(f)->boundary_id();
      }
    same = same && p == one.end() && q == other.end();
    check(Utilities::MPI::min(same ? 1u : 0u, comm) == 1,
          std::to_string(dim) + "D: the two fully distributed triangulations have the same cells");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  check.print_on_this_process(Utilities::MPI::this_mpi_process(comm) == 0);

  box_as_deal_ii<2>(Point<2>(0.1, -0.3), Point<2>(1.7, 0.02), {7, 3});
  box_as_deal_ii<2>(Point<2>(0, 0.02), Point<2>(100, 0.04), {10000, 2});
  box_as_deal_ii<3>(Point<3>(-1.3, 0.1, 0.7), Point<3>(0.9, 2.2, 1.1), {5, 7, 3});
  description_as_deal_ii<2>(comm);
  description_as_deal_ii<3>(comm);
  return check.finish();
}
