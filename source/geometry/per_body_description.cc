// Geometry/Partition = per body without the whole mesh on every process: the
// generator's arrays cut per body (partition.cc), and this process's cells
// with their ghost layer described for a parallel::fullydistributed
// triangulation, as deal.II describes them from a whole Triangulation.
// Session 16 measured ~560 M instructions per process on the contact strip
// for building the whole mesh, partitioning and describing it.
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/cell_id.h>

#include <anvil/core/instantiate.h>
#include <anvil/geometry/partition.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  TriangulationDescription::Description<dim, dim> describe_per_body(const MeshArrays<dim> &mesh,
                                                                    const MPI_Comm         comm)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_vertices = mesh.vertices.size(), n_cells = mesh.cells.size();

    // Cell centres as TriaAccessor::center() forms them (the sum of the
    // vertices over their count), so the slabs are those of the Triangulation.
    std::vector<Point<dim>> centers(n_cells);
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        Point<dim> p;
        for (const unsigned int v : mesh.cells[c].vertices)
          p += mesh.vertices[v];
        centers[c] = p / static_cast<unsigned int>(mesh.cells[c].vertices.size());
      }
    const PerBodyCut cut =
      cut_per_body(mesh.cells, centers, n_vertices, Utilities::MPI::n_mpi_processes(comm));

    // Locally relevant: the owned cells and every cell that shares a vertex
    // with one; their vertices numbered in the order of the global numbers.
    std::vector<bool> near(n_vertices, false);
    for (unsigned int c = 0; c < n_cells; ++c)
      if (cut.owner[c] == rank)
        for (const unsigned int v : mesh.cells[c].vertices)
          near[v] = true;
    std::vector<unsigned int> relevant;
    std::vector<unsigned int> local(n_vertices, numbers::invalid_unsigned_int);
    for (unsigned int c = 0; c < n_cells; ++c)
      for (const unsigned int v : mesh.cells[c].vertices)
        if (near[v])
          {
            relevant.push_back(c);
            for (const unsigned int w : mesh.cells[c].vertices)
              local[w] = 0;
            break;
          }

    TriangulationDescription::Description<dim, dim> description;
    description.comm      = comm;
    description.settings  = TriangulationDescription::Settings::default_setting;
    description.smoothing = Triangulation<dim>::none;
    for (unsigned int v = 0, k = 0; v < n_vertices; ++v)
      if (local[v] == 0)
        {
          local[v] = k++;
          description.coarse_cell_vertices.push_back(mesh.vertices[v]);
        }
    description.cell_infos.resize(1);
    for (const unsigned int c : relevant)
      {
        CellData<dim> cell = mesh.cells[c];
        for (auto &v : cell.vertices)
          v = local[v];
        description.coarse_cells.push_back(cell);
        description.coarse_cell_index_to_coarse_cell_id.push_back(c);

        TriangulationDescription::CellData<dim> info;
        info.id                 = CellId(c, {}).template to_binary<dim>();
        info.subdomain_id       = cut.owner[c];
        info.level_subdomain_id = 0; // a serial Triangulation's, never partitioned
        info.manifold_id        = cell.manifold_id;
        info.manifold_line_ids.fill(numbers::flat_manifold_id);
        info.manifold_quad_ids.fill(numbers::flat_manifold_id);
        for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
          if (mesh.face_ids[c][f] != numbers::internal_face_boundary_id)
            info.boundary_ids.emplace_back(f, mesh.face_ids[c][f]);
        description.cell_infos[0].push_back(info);
      }
    return description;
  }

  template <int dim>
  void create_per_body(const MeshArrays<dim> &mesh, parallel::fullydistributed::Triangulation<dim> &tria)
  {
    // deal.II 9.4 sorts the description's cells twice (fully distributed and
    // serial create_triangulation) with a comparison that takes them by
    // value: every comparison copied two vectors of boundary ids (most cells
    // of a strip two cells thick have a boundary face). Without them the
    // copies allocate nothing; the ids are set on the faces afterwards, where
    // the description would have set them (boundary faces of the cells it
    // lists; the artificial boundary keeps deal.II's 0 either way).
    auto description = describe_per_body(mesh, tria.get_communicator());
    for (auto &info : description.cell_infos[0])
      info.boundary_ids.clear();
    tria.create_triangulation(description);
    for (const auto &cell : tria.cell_iterators_on_level(0))
      {
        const auto &faces = mesh.face_ids[cell->id().get_coarse_cell_id()];
        for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
          if (faces[f] != numbers::internal_face_boundary_id)
            cell->face(f)->set_boundary_id(faces[f]);
      }
  }

#define INSTANTIATE(dim)                                                                           \
  template TriangulationDescription::Description<dim, dim> describe_per_body(                      \
    const MeshArrays<dim> &, MPI_Comm);                                                            \
  template void create_per_body(const MeshArrays<dim> &,                                          \
                                parallel::fullydistributed::Triangulation<dim> &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
