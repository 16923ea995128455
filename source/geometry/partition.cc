// Geometry/Partition = per body: every body cut into as many slabs as there
// are processes (include/anvil/geometry/partition.h says why).
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/core/instantiate.h>
#include <anvil/geometry/partition.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <numeric>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    unsigned int find_root(std::vector<unsigned int> &parent, unsigned int v)
    {
      while (parent[v] != v)
        v = parent[v] = parent[parent[v]];
      return v;
    }
  } // namespace

  template <int dim>
  std::vector<unsigned int> partition_per_body(Triangulation<dim> &serial, const unsigned int n_parts)
  {
    // Union-find over (body, vertex): the cells of one body share vertices.
    // Blocks that touch may share vertices too (merged meshes), so a body is
    // also one material id.
    std::map<std::pair<types::material_id, unsigned int>, unsigned int> node_of;
    const auto node = [&](const auto &cell, const unsigned int v) {
      return node_of.emplace(std::make_pair(cell->material_id(), cell->vertex_index(v)), node_of.size())
        .first->second;
    };
    for (const auto &cell : serial.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        node(cell, v);
    std::vector<unsigned int> parent(node_of.size());
    std::iota(parent.begin(), parent.end(), 0u);
    for (const auto &cell : serial.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const unsigned int a = find_root(parent, node(cell, 0));
          const unsigned int b = find_root(parent, node(cell, v));
          if (a != b)
            parent[std::max(a, b)] = std::min(a, b);
        }

    std::vector<unsigned int>              component(serial.n_active_cells());
    std::vector<std::vector<Point<dim>>>   centers; // per component, by cell
    std::vector<std::vector<unsigned int>> cells;   // active indices per component
    std::vector<unsigned int> root_to_component(parent.size(), numbers::invalid_unsigned_int);
    for (const auto &cell : serial.active_cell_iterators())
      {
        unsigned int &c = root_to_component[find_root(parent, node(cell, 0))];
        if (c == numbers::invalid_unsigned_int)
          {
            c = cells.size();
            cells.emplace_back();
            centers.emplace_back();
          }
        component[cell->active_cell_index()] = c;
        cells[c].push_back(cell->active_cell_index());
        centers[c].push_back(cell->center());
      }

    std::vector<types::subdomain_id> owner(serial.n_active_cells());
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        // Slabs across the longest axis of the body's bounding box: the cut
        // is then as short as the body is thin (a strip is cut across).
        Point<dim> lower = centers[c][0], upper = centers[c][0];
        for (const auto &p : centers[c])
          for (unsigned int d = 0; d < dim; ++d)
            lower[d] = std::min(lower[d], p[d]), upper[d] = std::max(upper[d], p[d]);
        unsigned int axis = 0;
        for (unsigned int d = 1; d < dim; ++d)
          if (upper[d] - lower[d] > upper[axis] - lower[axis])
            axis = d;
        std::vector<unsigned int> order(cells[c].size());
        std::iota(order.begin(), order.end(), 0u);
        // Ties (cells in one layer) by the other coordinates, so the slabs are
        // the same whatever the cell numbering.
        std::stable_sort(order.begin(), order.end(), [&](const unsigned int a, const unsigned int b) {
          const Point<dim> &p = centers[c][a], &q = centers[c][b];
          if (p[axis] != q[axis])
            return p[axis] < q[axis];
          for (unsigned int d = 0; d < dim; ++d)
            if (p[d] != q[d])
              return p[d] < q[d];
          return false;
        });
        const std::size_t n = order.size();
        for (std::size_t k = 0; k < n; ++k)
          owner[cells[c][order[k]]] = static_cast<types::subdomain_id>(k * n_parts / n);
      }
    for (const auto &cell : serial.active_cell_iterators())
      cell->set_subdomain_id(owner[cell->active_cell_index()]);
    return component;
  }

  template <int dim>
  void create_per_body(Triangulation<dim>                          &serial,
                       parallel::fullydistributed::Triangulation<dim> &triangulation)
  {
    const MPI_Comm comm = triangulation.get_communicator();
    partition_per_body(serial, Utilities::MPI::n_mpi_processes(comm));
    // The description takes the cells of the refined levels by their level
    // subdomain ids: those of the parents follow from their children.
    if (serial.n_levels() > 1)
      GridTools::partition_multigrid_levels(serial);
    const auto description =
      TriangulationDescription::Utilities::create_description_from_triangulation(serial, comm);
    triangulation.create_triangulation(description);
  }

  template <int dim>
  void PerBodyTriangulation<dim>::load(const std::string &filename)
  {
    parallel::fullydistributed::Triangulation<dim>::load(filename);
    // Read the attached data again, from save()'s offset (the header says why).
    unsigned int version = 0, n_processes = 0, n_fixed = 0, n_variable = 0, n_cells = 0;
    {
      std::ifstream info(filename + ".info");
      std::string   header;
      std::getline(info, header);
      info >> version >> n_processes >> n_fixed >> n_variable >> n_cells;
      AssertThrow(info, ExcIO());
    }
    if (n_fixed + n_variable == 0)
      return;
    const MPI_Comm     comm    = this->get_communicator();
    const unsigned int n_local = this->n_locally_owned_active_cells();
    unsigned int       first   = 0;
    const int          ierr    = MPI_Exscan(&n_local, &first, 1, MPI_UNSIGNED, MPI_SUM, comm);
    AssertThrowMPI(ierr);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0; // MPI_Exscan leaves rank 0's result undefined
    this->data_transfer.clear();
    this->load_attached_data(first * sizeof(unsigned int), this->n_global_active_cells(), n_local,
                             filename, n_fixed, n_variable);
  }

#define INSTANTIATE(dim)                                                                           \
  template std::vector<unsigned int> partition_per_body(Triangulation<dim> &, unsigned int);     \
  template void create_per_body(Triangulation<dim> &,                                            \
                                parallel::fullydistributed::Triangulation<dim> &);        \
  template class PerBodyTriangulation<dim>;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
