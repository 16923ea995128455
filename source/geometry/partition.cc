// Geometry/Partition = per body: every body cut into as many slabs as there
// are processes (include/anvil/geometry/partition.h says why).
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/geometry/partition.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
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
  PerBodyCut cut_per_body(const std::vector<CellData<dim>> &cells, const std::vector<Point<dim>> &centers,
                          const unsigned int n_vertices, const unsigned int n_parts)
  {
    // Union-find over the cells: cells of one material that share a vertex
    // are one body. Blocks that touch may share vertices too (merged meshes),
    // so a vertex joins only cells of one material; the few vertices shared
    // by several materials are looked up by (vertex, material).
    const unsigned int        n = cells.size();
    std::vector<unsigned int> parent(n), first(n_vertices, numbers::invalid_unsigned_int);
    std::iota(parent.begin(), parent.end(), 0u);
    std::map<std::pair<unsigned int, types::material_id>, unsigned int> shared;
    const auto join = [&](const unsigned int a, const unsigned int b) {
      const unsigned int ra = find_root(parent, a), rb = find_root(parent, b);
      if (ra != rb)
        parent[std::max(ra, rb)] = std::min(ra, rb);
    };
    for (unsigned int c = 0; c < n; ++c)
      for (const unsigned int v : cells[c].vertices)
        {
          unsigned int &f = first[v];
          if (f == numbers::invalid_unsigned_int)
            f = c;
          else if (cells[f].material_id == cells[c].material_id)
            join(f, c);
          else
            join(shared.emplace(std::make_pair(v, cells[c].material_id), c).first->second, c);
        }

    PerBodyCut                             cut;
    std::vector<std::vector<unsigned int>> members; // cells per component, in order
    std::vector<unsigned int> root_to_component(n, numbers::invalid_unsigned_int);
    cut.component.resize(n);
    for (unsigned int c = 0; c < n; ++c)
      {
        unsigned int &k = root_to_component[find_root(parent, c)];
        if (k == numbers::invalid_unsigned_int)
          {
            k = members.size();
            members.emplace_back();
          }
        cut.component[c] = k;
        members[k].push_back(c);
      }

    cut.owner.resize(n);
    for (const auto &body : members)
      {
        // Slabs across the longest axis of the body's bounding box: the cut
        // is then as short as the body is thin (a strip is cut across).
        Point<dim> lower = centers[body[0]], upper = centers[body[0]];
        for (const unsigned int c : body)
          for (unsigned int d = 0; d < dim; ++d)
            lower[d] = std::min(lower[d], centers[c][d]), upper[d] = std::max(upper[d], centers[c][d]);
        unsigned int axis = 0;
        for (unsigned int d = 1; d < dim; ++d)
          if (upper[d] - lower[d] > upper[axis] - lower[axis])
            axis = d;
        std::vector<unsigned int> order(body);
        // Ties (cells in one layer) by the other coordinates, so the slabs are
        // the same whatever the cell numbering.
        std::stable_sort(order.begin(), order.end(), [&](const unsigned int a, const unsigned int b) {
          const Point<dim> &p = centers[a], &q = centers[b];
          if (p[axis] != q[axis])
            return p[axis] < q[axis];
          for (unsigned int d = 0; d < dim; ++d)
            if (p[d] != q[d])
              return p[d] < q[d];
          return false;
        });
        const std::size_t m = order.size();
        for (std::size_t k = 0; k < m; ++k)
          cut.owner[order[k]] = static_cast<types::subdomain_id>(k * n_parts / m);
      }
    return cut;
  }

  template <int dim>
  std::vector<unsigned int> partition_per_body(Triangulation<dim> &serial, const unsigned int n_parts)
  {
    std::vector<CellData<dim>> cells(serial.n_active_cells());
    std::vector<Point<dim>>    centers(serial.n_active_cells());
    for (const auto &cell : serial.active_cell_iterators())
      {
        auto &data = cells[cell->active_cell_index()];
        for (const unsigned int v : cell->vertex_indices())
          data.vertices[v] = cell->vertex_index(v);
        data.material_id                      = cell->material_id();
        centers[cell->active_cell_index()]    = cell->center();
      }
    const PerBodyCut cut = cut_per_body(cells, centers, serial.n_vertices(), n_parts);
    for (const auto &cell : serial.active_cell_iterators())
      cell->set_subdomain_id(cut.owner[cell->active_cell_index()]);
    return cut.component;
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

  namespace
  {
    // The version of deal.II 9.4's cell-data files (the first number of the
    // info file its save() writes; its load() refuses any other).
    constexpr unsigned int cell_data_version = 4;

    /// This process's first cell in the cell-data files. deal.II 9.4's own
    /// save() passes 4 times it (the count scaled by sizeof(unsigned int)),
    /// so that process r's cells sat 4 times further on than the cells
    /// before them take: the file was 2.5 times its data on two processes
    /// (69 MB for 28 MB on the contact strip), all of it hashed.
    template <int dim>
    unsigned int first_cell_offset(const parallel::fullydistributed::Triangulation<dim> &tria)
    {
      const unsigned int n_local = tria.n_locally_owned_active_cells();
      unsigned int       first   = 0;
      const int ierr = MPI_Exscan(&n_local, &first, 1, MPI_UNSIGNED, MPI_SUM, tria.get_communicator());
      AssertThrowMPI(ierr);
      if (Utilities::MPI::this_mpi_process(tria.get_communicator()) == 0)
        first = 0; // MPI_Exscan leaves rank 0's result undefined
      return first;
    }

    /// FNV-1a over the bits of the owned cells' vertices, summed over the
    /// processes: the same mesh cut the same way gives the same number.
    template <int dim>
    std::uint64_t vertex_print(const parallel::fullydistributed::Triangulation<dim> &tria)
    {
      std::uint64_t hash = 1469598103934665603ull;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < dim; ++d)
              {
                std::uint64_t bits;
                std::memcpy(&bits, &cell->vertex(v)[d], sizeof bits);
                hash = (hash ^ bits) * 1099511628211ull;
              }
      std::uint64_t sum = 0;
      const int ierr = MPI_Allreduce(&hash, &sum, 1, MPI_UINT64_T, MPI_SUM, tria.get_communicator());
      AssertThrowMPI(ierr);
      return sum;
    }
  } // namespace

  template <int dim>
  void PerBodyTriangulation<dim>::save(const std::string &filename) const
  {
    const std::uint64_t print = vertex_print(*this);
    if (Utilities::MPI::this_mpi_process(this->get_communicator()) == 0)
      {
        // deal.II 9.4's info file, read by load() (and by deal.II's).
        std::ofstream info(filename + ".info");
        info << "version nproc n_attached_fixed_size_objs n_attached_variable_size_objs "
                "n_global_active_cells\n"
             << cell_data_version << ' ' << Utilities::MPI::n_mpi_processes(this->get_communicator())
             << ' ' << this->cell_attached_data.pack_callbacks_fixed.size() << ' '
             << this->cell_attached_data.pack_callbacks_variable.size() << ' '
             << this->n_global_active_cells() << '\n'
             << "anvil-mesh " << std::hex << print << '\n';
        AssertThrow(info, ExcIO());
      }
    this->save_attached_data(first_cell_offset(*this), this->n_global_active_cells(), filename);
  }

  template <int dim>
  void PerBodyTriangulation<dim>::load(const std::string &filename)
  {
    AssertThrow(this->n_global_active_cells() > 0,
                ExcMessage("per body: load() reads cell data into the mesh created from the scene"));
    unsigned int version = 0, n_processes = 0, n_fixed = 0, n_variable = 0, n_cells = 0;
    std::string  mesh_key;
    std::uint64_t print = 0;
    {
      std::ifstream info(filename + ".info");
      std::string   header;
      std::getline(info, header);
      info >> version >> n_processes >> n_fixed >> n_variable >> n_cells;
      AssertThrow(info && version == cell_data_version, ExcIO());
      info >> mesh_key >> std::hex >> print; // absent before session 18
      if (mesh_key != "anvil-mesh")
        print = 0;
    }
    if (n_cells != this->n_global_active_cells() || (print != 0 && print != vertex_print(*this)))
      throw InputError("Output/Restart from: the checkpoint's mesh (" + std::to_string(n_cells) +
                       " cells) is not the one this scene creates (" +
                       std::to_string(this->n_global_active_cells()) +
                       (n_cells == this->n_global_active_cells() ? " cells, other vertices" : " cells") +
                       "): was Geometry changed?");
    if (n_fixed + n_variable == 0)
      return;
    this->cell_attached_data.n_attached_data_sets   = 0;
    this->cell_attached_data.n_attached_deserialize = n_fixed + n_variable;
    this->load_attached_data(first_cell_offset(*this), this->n_global_active_cells(),
                             this->n_locally_owned_active_cells(), filename, n_fixed, n_variable);
  }

#define INSTANTIATE(dim)                                                                           \
  template std::vector<unsigned int> partition_per_body(Triangulation<dim> &, unsigned int);     \
  template PerBodyCut cut_per_body(const std::vector<CellData<dim>> &,                           \
                                   const std::vector<Point<dim>> &, unsigned int, unsigned int); \
  template void create_per_body(Triangulation<dim> &,                                            \
                                parallel::fullydistributed::Triangulation<dim> &);        \
  template class PerBodyTriangulation<dim>;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
