// The mesh a run will use is checked before any work (and by --check, which
// builds it): the gmsh file's own structure, the size the refinements would
// reach, and cells that the Transformation (or the file) turned inside out.

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>

#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/geometry/geometry.h>

#include <unistd.h>

#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    bool read_count(const std::string &line, unsigned long &count)
    {
      std::istringstream s(line);
      long               n = -1;
      std::string        rest;
      return (s >> n) && !(s >> rest) && n >= 0 && (count = n, true);
    }
  } // namespace

  template <int dim>
  void Geometry<dim>::check_msh22(std::istream &in) const
  {
    // GridIn would allocate a declared count before reading it (a huge one
    // ends in bad_alloc), skips NaN coordinates into a misleading message and
    // reads a quad with a repeated node as a collapsed cell: say what is wrong.
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);)
      lines.push_back(l.substr(0, l.find_last_not_of(" \r\t") + 1));
    const auto fail = [&](const std::string &what) {
      throw InputError(locations.at("Geometry/Mesh file") + ": 'Geometry/Mesh file' ('" + mesh_file +
                       "') " + what);
    };
    const auto section = [&](const std::string &name) {
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (lines[i] == name)
          return i;
      fail("has no " + name + " section");
      return std::size_t(0);
    };
    const std::size_t nodes = section("$Nodes"), elements = section("$Elements");
    unsigned long     n_nodes = 0, n_elements = 0;
    if (nodes + 1 >= lines.size() || !read_count(lines[nodes + 1], n_nodes) ||
        nodes + 2 + n_nodes >= lines.size() || lines[nodes + 2 + n_nodes] != "$EndNodes")
      fail("declares " + (nodes + 1 < lines.size() ? "'" + lines[nodes + 1].substr(0, 40) + "'" :
                                                    std::string("no")) +
           " nodes but does not list that many before $EndNodes (truncated or wrong count)");
    std::set<long> ids;
    for (unsigned long i = 0; i < n_nodes; ++i)
      {
        std::istringstream s(lines[nodes + 2 + i]);
        long               id = 0;
        std::string        x[3];
        s >> id >> x[0] >> x[1] >> x[2];
        for (const auto &c : x)
          {
            double v = 0;
            try
              {
                std::size_t used = 0;
                v                = std::stod(c, &used);
                if (used != c.size())
                  v = std::nan("");
              }
            catch (...)
              {
                v = std::nan("");
              }
            if (!std::isfinite(v))
              fail("node " + std::to_string(id) + " (line " + std::to_string(nodes + 3 + i) +
                   ") has the coordinate '" + c.substr(0, 40) + "': expected three finite numbers");
          }
        if (!ids.insert(id).second)
          fail("lists node " + std::to_string(id) + " twice");
      }
    if (elements + 1 >= lines.size() || !read_count(lines[elements + 1], n_elements) ||
        elements + 2 + n_elements >= lines.size() ||
        lines[elements + 2 + n_elements] != "$EndElements")
      fail("declares " +
           (elements + 1 < lines.size() ? "'" + lines[elements + 1].substr(0, 40) + "'" :
                                          std::string("no")) +
           " elements but does not list that many before $EndElements (truncated or wrong count)");
    for (unsigned long i = 0; i < n_elements; ++i)
      {
        std::istringstream s(lines[elements + 2 + i]);
        long               number = 0, type = 0, n_tags = 0, tag = 0;
        s >> number >> type >> n_tags;
        for (long k = 0; k < n_tags && s; ++k)
          s >> tag;
        const unsigned int n = type == 15 ? 1 : type == 1 ? 2 : type == 3 ? 4 : type == 5 ? 8 : 0;
        std::vector<long>  element(n, -1);
        for (auto &node : element)
          s >> node;
        std::string rest;
        if (!s || n == 0 || (s >> rest))
          fail("element " + std::to_string(number) + " (line " + std::to_string(elements + 3 + i) +
               ") is malformed: expected 'number type n_tags tags... nodes' with the nodes of "
               "a point, line, quadrilateral or hexahedron");
        std::set<long> distinct;
        for (const long node : element)
          {
            if (ids.count(node) == 0)
              fail("element " + std::to_string(number) + " refers to node " + std::to_string(node) +
                   ", which $Nodes does not list");
            if (!distinct.insert(node).second)
              fail("element " + std::to_string(number) + " repeats node " + std::to_string(node) +
                   ": a degenerate cell");
          }
      }
  }

  template <int dim>
  void Geometry<dim>::check_size(const unsigned int n_coarse_cells) const
  {
    // Each refinement multiplies the cells by 2^dim. Memory per cell measured
    // on the shipped scenes (mesh, DoFs, matrix, material points) is below
    // ~10 kB in 2D and ~60 kB in 3D; what cannot fit this machine is refused.
    const double log10_cells =
      std::log10(std::max(1u, n_coarse_cells)) + dim * global_refinements * std::log10(2.0);
    const double bytes_per_cell = dim == 2 ? 1e4 : 6e4;
    const double log10_bytes    = log10_cells + std::log10(bytes_per_cell);
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    if (log10_bytes > std::log10(memory) || log10_cells > 9)
      {
        std::ostringstream s;
        s.precision(3);
        s << "= " << global_refinements << " would make about 10^" << std::fixed
          << std::setprecision(0) << std::floor(log10_cells) << " cells (" << n_coarse_cells
          << " coarse cells x 2^(" << dim << " x " << global_refinements << ")) needing about 10^"
          << std::floor(log10_bytes - 9) << " GB (estimate: " << bytes_per_cell / 1e3 << " kB per cell), more than this "
          << "machine's " << std::setprecision(1) << memory / 1e9 << " GB: expected fewer refinements";
        throw InputError(locations.at("Geometry/Global refinements") +
                         ": 'Geometry/Global refinements' " + s.str());
      }
  }

  template <int dim>
  void Geometry<dim>::check_cells(const parallel::DistributedTriangulationBase<dim> &tria) const
  {
    // The Jacobian at every vertex of every cell must be positive: a cell a
    // Transformation (or the file's node order) turned over would otherwise be
    // found only as an "inverted element" of the first step.
    const FE_Q<dim>     fe(1);
    const QTrapezoid<dim> vertices;
    const MappingQ1<dim> mapping; // FEValues keeps a reference
    FEValues<dim>       fe_values(mapping, fe, vertices, update_jacobians);
    std::string         problem;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < vertices.size(); ++q)
            {
              const double det = fe_values.jacobian(q).determinant();
              if (!(det > 0) && problem.empty())
                {
                  std::ostringstream s;
                  s << "the cell at (" << cell->center() << ") has a "
                    << (det < 0 ? "negative" : "zero") << " Jacobian at its vertex ("
                    << cell->vertex(q) << "): the mesh has cells that are inverted or collapsed";
                  problem = s.str();
                }
            }
        }
    const std::string entry = !transformation.empty() ? "Geometry/Transformation" :
                              type == "gmsh"          ? "Geometry/Mesh file" :
                                                        "Geometry/Random distortion";
    for (const auto &p : Utilities::MPI::all_gather(tria.get_communicator(), problem))
      if (!p.empty())
        throw InputError(locations.at(entry) + ": '" + entry + "' makes a mesh where " + p);
  }

#define INSTANTIATE(dim)                                                                           \
  template void Geometry<dim>::check_msh22(std::istream &) const;                                  \
  template void Geometry<dim>::check_size(unsigned int) const;                                     \
  template void Geometry<dim>::check_cells(                                                        \
    const parallel::DistributedTriangulationBase<dim> &) const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
