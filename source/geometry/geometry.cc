#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/geometry/partition.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // Face k of a generated box: x-low, x-high, y-low, y-high, z-low, z-high.
    // With one block these are also the names (and ids 0..2*dim-1).
    const char *const face_names[6] = {"left", "right", "bottom", "top", "front", "back"};

    // The whole of @p text is one finite number.
    bool to_double(const std::string &text, double &value)
    {
      std::istringstream s(text);
      return (s >> value) && s.eof() && std::isfinite(value);
    }

    std::string str(const double value)
    {
      std::ostringstream s;
      s << value;
      return s.str();
    }

    bool to_positive_int(const std::string &text, unsigned int &value)
    {
      const bool digits =
        !text.empty() && text.size() < 10 && text.find_first_not_of("0123456789") == std::string::npos;
      return digits && (value = std::stoul(text)) > 0;
    }

    /*
     * Scan a .msh file (ASCII 2.2 or 4.1): the names of its physical groups
     * ($PhysicalNames), the physical tags actually used by elements (to name
     * unnamed groups boundary_<tag> / body_<tag>), and element types (anvil
     * needs first-order quadrilaterals / hexahedra). @p fail throws.
     */
    template <int dim>
    void scan_msh(std::istream &in, const std::function<void(const std::string &)> &fail,
                  std::map<std::string, types::boundary_id> &boundaries,
                  std::map<std::string, types::material_id> &bodies)
    {
      const std::string cell_kind = dim == 2 ? "quadrilaterals" : "hexahedra";
      double            version   = 0;
      std::map<std::pair<int, int>, std::string>      names;    // (dim, tag) -> name
      std::map<std::pair<int, int>, std::vector<int>> entities; // 4.1: (dim, entity) -> tags
      std::set<std::pair<int, int>>                   used;     // (dim, physical tag)
      unsigned long                                   n_cells = 0;
      std::string                                     line;
      const auto next = [&]() {
        std::getline(in, line);
        return std::istringstream(line);
      };

      const auto check_element = [&](const int type, const int edim, const std::vector<int> &tags) {
        if (type == 2 || type == 4 || type == 6 || type == 7)
          fail("contains triangles, tetrahedra, prisms or pyramids (gmsh element type " +
               std::to_string(type) + "); anvil needs " + cell_kind +
               ": use Recombine in the .geo (and Mesh.SubdivisionAlgorithm = 2 in 3D)");
        if (type != 15 && type != 1 && type != 3 && type != 5)
          fail("contains gmsh element type " + std::to_string(type) + ", which anvil cannot read: use "
               "first-order elements (Mesh.ElementOrder = 1) and Recombine in the .geo");
        if (edim > dim)
          fail("contains hexahedra, i.e. is a 3D mesh; set Dimension = 3");
        const std::string group = dim == 2 ? "Surface" : "Volume";
        if (edim == dim && ++n_cells && tags.empty())
          fail("has cells in no Physical " + group + ": name every body in the .geo, e.g. Physical " +
               group + "(\"steel\") = {1};");
        for (const int t : tags)
          used.insert({edim, t});
      };

      while (std::getline(in, line))
        {
          line = trim(line);
          if (line == "$MeshFormat")
            {
              int file_type = -1;
              next() >> version >> file_type;
              if (file_type != 0)
                fail("is not an ASCII .msh file: save it as ASCII (gmsh -format msh22, Mesh.Binary = 0)");
              if (!((version >= 2 && version < 3) || std::abs(version - 4.1) < 1e-8))
                fail("has .msh format " + str(version) +
                     "; anvil reads formats 2.2 and 4.1 (gmsh -format msh22)");
            }
          else if (line == "$PhysicalNames")
            {
              unsigned int count = 0;
              next() >> count;
              for (unsigned int i = 0; i < count; ++i)
                {
                  int d = -1, tag = -1;
                  next() >> d >> tag;
                  const auto first = line.find('"'), last = line.rfind('"');
                  if (tag < 0 || first == std::string::npos || last <= first)
                    fail("has a malformed $PhysicalNames line '" + trim(line) +
                         "' (expected: dim tag \"name\")");
                  names[{d, tag}] = line.substr(first + 1, last - first - 1);
                }
            }
          else if (line == "$Entities") // 4.1 only: physical tags live on entities
            {
              unsigned long counts[4] = {0, 0, 0, 0};
              next() >> counts[0] >> counts[1] >> counts[2] >> counts[3];
              for (int d = 0; d < 4; ++d)
                for (unsigned long i = 0; i < counts[d]; ++i)
                  {
                    // Points: tag x y z nPhys tags...; others: tag box(6) nPhys tags...
                    auto   s   = next();
                    int    tag = 0, n_phys = 0;
                    double skip;
                    s >> tag;
                    for (int k = 0; k < (d == 0 ? 3 : 6); ++k)
                      s >> skip;
                    s >> n_phys;
                    std::vector<int> &tags = entities[{d, tag}];
                    tags.resize(std::max(0, n_phys));
                    for (int &t : tags)
                      s >> t;
                  }
            }
          else if (line == "$Elements" && version < 3)
            {
              // 2.2: number type n_tags physical elementary nodes...
              unsigned long count = 0;
              next() >> count;
              for (unsigned long i = 0; i < count; ++i)
                {
                  int number = 0, type = 0, n_tags = 0, physical = 0;
                  next() >> number >> type >> n_tags >> physical;
                  const int edim = type == 15 ? 0 : type == 1 ? 1 : type == 3 ? 2 : 3;
                  check_element(type, edim, std::vector<int>(n_tags > 0 && physical > 0, physical));
                }
            }
          else if (line == "$Elements")
            {
              // 4.1: blocks "entityDim entityTag elementType count" + count lines.
              unsigned long n_blocks = 0;
              next() >> n_blocks;
              for (unsigned long b = 0; b < n_blocks; ++b)
                {
                  int           edim = 0, entity = 0, type = 0;
                  unsigned long count = 0;
                  next() >> edim >> entity >> type >> count;
                  for (unsigned long i = 0; i < count; ++i)
                    std::getline(in, line);
                  if (count > 0)
                    check_element(type, edim, entities[{edim, entity}]);
                }
            }
        }
      if (version == 0)
        fail("is not a gmsh .msh file (no $MeshFormat section)");
      if (n_cells == 0)
        fail("contains no " + cell_kind + "; is Dimension right?");

      // Named groups, then unnamed ones that elements use.
      for (const auto &[key, name] : names)
        if ((key.first == dim && !bodies.emplace(name, key.second).second) ||
            (key.first == dim - 1 && !boundaries.emplace(name, key.second).second))
          fail("has two physical groups named '" + name + "' of dimension " + std::to_string(key.first));
      for (const auto &[d, tag] : used)
        if (names.count({d, tag}) == 0 && d == dim)
          bodies.emplace("body_" + std::to_string(tag), tag);
        else if (names.count({d, tag}) == 0 && d == dim - 1)
          boundaries.emplace("boundary_" + std::to_string(tag), tag);
    }

    template <typename Id>
    Id find_id(const std::map<std::string, Id> &map, const std::string &kind, const std::string &name,
               const std::string &where, const std::string &known)
    {
      const auto it = map.find(name);
      if (it == map.end())
        throw InputError(where + ": no " + kind + " named '" + name +
                         "' in the mesh; the mesh has: " + known);
      return it->second;
    }

    template <typename Id>
    std::string list_names(const std::map<std::string, Id> &map)
    {
      // In id order (the order of declaration), which reads better than alphabetical.
      std::vector<std::pair<Id, std::string>> sorted;
      for (const auto &[name, id] : map)
        sorted.emplace_back(id, name);
      std::sort(sorted.begin(), sorted.end());
      std::string text;
      for (const auto &[id, name] : sorted)
        text += (text.empty() ? "" : ", ") + name;
      return text.empty() ? "(none)" : text;
    }
  } // namespace

  template <int dim>
  void Geometry<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Type", "blocks", Patterns::Selection("blocks|annulus|tube|bar|gmsh"),
                      "The mesh: blocks (axis-parallel boxes, see Blocks), annulus (2D ring, faces inner, "
                      "outer), tube (3D hollow cylinder along z, faces inner, outer, bottom, top; in 2D its "
                      "axisymmetric section r in [Inner radius, Outer radius], z in [0, Length]), bar (3D "
                      "solid cylinder along z, faces side, bottom, top; in 2D its axisymmetric section, "
                      "faces axis, side, bottom, top) or gmsh (a .msh file, see Mesh file).");
    prm.declare_entry("Global refinements", "0", Patterns::Integer(0),
                      "Number of times every cell of the coarse mesh is split in 2^dim.");
    prm.declare_entry("Transformation", "", Patterns::Anything(),
                      "Map every vertex of the refined mesh to new coordinates: dim "
                      "','-separated muparser expressions in x, y (, z), e.g. a bar tapered "
                      "towards y = 0: 'x*(0.982 + 0.018*y/26.667), y'. Empty: none. Boundary "
                      "and body names are kept; curved boundaries follow the formula, not "
                      "their original shape, under further refinement.");
    prm.declare_entry("Random distortion", "0", Patterns::Double(0, 0.4),
                      "Move interior vertices of the coarse mesh at random by up to this fraction of "
                      "the adjacent edge length (dimensionless, 0 to 0.4); for patch tests. The "
                      "distortion is the same on every process and every run.");
    prm.declare_entry("Body name", "body", Patterns::Anything(),
                      "Name of the single body of annulus, tube and bar (blocks name each block; gmsh "
                      "uses its physical names).");
    prm.declare_entry("Blocks", dim == 2 ? "body: 0, 0, 1, 1, 4, 4" : "body: 0, 0, 0, 1, 1, 1, 4, 4, 4",
                      Patterns::Anything(),
                      std::string("';'-separated blocks ") +
                        (dim == 2 ? "'name: x0, y0, x1, y1, nx, ny'" :
                                    "'name: x0, y0, z0, x1, y1, z1, nx, ny, nz'") +
                        ": lower and upper corner (mm) and cells per direction. One block: faces left, "
                        "right, bottom, top" + (dim == 3 ? ", front (z0), back (z1)" : "") +
                        "; several: name.left, name.right, ... Blocks that touch stay separate bodies "
                        "(for contact).");
    prm.declare_entry("Inner radius", "1", Patterns::Double(0),
                      "Inner radius of annulus and tube (mm), > 0.");
    prm.declare_entry("Outer radius", "2", Patterns::Double(0),
                      "Outer radius of annulus and tube (mm), > Inner radius.");
    prm.declare_entry("Radius", "1", Patterns::Double(0), "Radius of the bar (mm), > 0.");
    prm.declare_entry("Length", "4", Patterns::Double(0), "Length along z of tube and bar (mm), > 0.");
    prm.declare_entry("Radial cells", "2", Patterns::Integer(1),
                      "Cells through the wall of annulus and tube, and across the 2D bar (the 3D bar's "
                      "cross-section is fixed: 5 cells).");
    prm.declare_entry("Axial cells", "8", Patterns::Integer(1), "Cells along the length of tube and bar.");
    prm.declare_entry("Circumferential cells", "0", Patterns::Integer(0),
                      "Cells around annulus and 3D tube; 0 chooses cells of about square shape (a "
                      "multiple of 4), otherwise at least 3.");
    prm.declare_entry("Partition", "space-filling curve",
                      Patterns::Selection("space-filling curve|per body"),
                      "How the cells are shared among the processes: space-filling curve "
                      "(p4est's: each body's coarse cells are numbered in a row, so two bodies "
                      "on two processes give one body each, and their contact surface is the "
                      "partition boundary) or per body (every body cut into as many slabs of "
                      "equal cell count as there are processes, along its longest axis: every "
                      "process holds a share of every body and contact surface; the whole "
                      "refined mesh is built on each process once; a checkpoint restarts on "
                      "as many processes as wrote it).");
    prm.declare_entry("Mesh file", "", Patterns::Anything(),
                      "Type = gmsh: path of an ASCII .msh file (format 2.2 or 4.1, coordinates in mm, "
                      "quadrilaterals/hexahedra); relative to the scene file's directory.");
    prm.leave_subsection();
  }

  template <int dim>
  void Geometry<dim>::parse_parameters(ParameterHandler &prm, const Scene &scene)
  {
    for (const auto *entry : {"Geometry/Mesh file", "Geometry/Global refinements",
                              "Geometry/Transformation", "Geometry/Random distortion"})
      locations[entry] = scene.where(entry);
    prm.enter_subsection("Geometry");
    type                  = prm.get("Type");
    global_refinements    = prm.get_integer("Global refinements");
    random_distortion     = prm.get_double("Random distortion");
    transformation.clear();
    const std::string transformation_text = prm.get("Transformation");
    if (!trim(transformation_text).empty())
      {
        const auto parts = split_outside_parentheses(transformation_text, ',');
        if (parts.size() != dim)
          scene.fail("Geometry/Transformation", "= '" + transformation_text + "': expected " +
                                                  std::to_string(dim) + " ','-separated expressions");
        for (const auto &p : parts)
          transformation.push_back(parse_expression<dim>(p, scene, "Geometry/Transformation"));
      }
    body_name             = trim(prm.get("Body name"));
    inner_radius          = prm.get_double("Inner radius");
    outer_radius          = prm.get_double("Outer radius");
    radius                = prm.get_double("Radius");
    length                = prm.get_double("Length");
    radial_cells          = prm.get_integer("Radial cells");
    axial_cells           = prm.get_integer("Axial cells");
    circumferential_cells = prm.get_integer("Circumferential cells");
    mesh_file             = trim(prm.get("Mesh file"));
    partition             = trim(prm.get("Partition"));
    const std::string block_text = prm.get("Blocks");
    prm.leave_subsection();

    if (partition != "space-filling curve" && partition != "per body")
      scene.fail("Geometry/Partition", "= '" + partition +
                                         "': expected 'space-filling curve' or 'per body'");
    blocks.clear();
    boundaries.clear();
    bodies.clear();

    const auto positive = [&](const std::string &entry, const double value) {
      if (!(value > 0))
        scene.fail("Geometry/" + entry, "is " + str(value) + ": expected a length > 0 (mm)");
    };
    if (type != "blocks" && type != "gmsh" && body_name.empty())
      scene.fail("Geometry/Body name", "is empty: expected the name of the body");

    if (type == "blocks")
      {
        const auto bad = [&](const std::string &what) {
          scene.fail("Geometry/Blocks", what + "; expected ';'-separated blocks " +
                                          (dim == 2 ? "'name: x0, y0, x1, y1, nx, ny'" :
                                                      "'name: x0, y0, z0, x1, y1, z1, nx, ny, nz'"));
        };
        for (const std::string &item : split_outside_parentheses(block_text, ';'))
          {
            if (item.empty())
              continue; // tolerate a trailing ';'
            const auto colon = item.find(':');
            if (colon == std::string::npos || trim(item.substr(0, colon)).empty())
              bad("has '" + item + "' without a name");
            Block block{trim(item.substr(0, colon)), {}, {}, std::vector<unsigned int>(dim)};
            for (const auto &other : blocks)
              if (other.name == block.name)
                bad("names the block '" + block.name + "' twice");
            const auto numbers = split_outside_parentheses(item.substr(colon + 1), ',');
            if (numbers.size() != 3 * dim)
              bad("has " + std::to_string(numbers.size()) + " numbers for block '" + block.name +
                  "' instead of " + std::to_string(3 * dim));
            for (unsigned int d = 0; d < dim; ++d)
              {
                const std::string x(1, "xyz"[d]);
                if (!to_double(numbers[d], block.lower[d]) || !to_double(numbers[dim + d], block.upper[d]))
                  bad("has a corner coordinate of block '" + block.name + "' that is not a number");
                if (!to_positive_int(numbers[2 * dim + d], block.subdivisions[d]))
                  bad("has the subdivision '" + numbers[2 * dim + d] + "' in block '" + block.name +
                      "': subdivisions must be integers >= 1");
                if (!(block.upper[d] > block.lower[d]))
                  bad("has block '" + block.name + "' with " + x + "1 <= " + x +
                      "0: the second corner must be above the first in every direction");
              }
            blocks.push_back(block);
          }
        if (blocks.empty())
          bad("is empty");
        for (unsigned int b = 0; b < blocks.size(); ++b)
          {
            bodies[blocks[b].name] = b;
            for (unsigned int f = 0; f < 2 * dim; ++f)
              boundaries[blocks.size() == 1 ? face_names[f] : blocks[b].name + "." + face_names[f]] =
                2 * dim * b + f;
          }
      }
    else if (type == "annulus" || type == "tube")
      {
        if (type == "annulus" && dim == 3)
          scene.fail("Geometry/Type", "is annulus, a 2D ring: in 3D use tube");
        positive("Inner radius", inner_radius);
        positive("Outer radius", outer_radius);
        if (inner_radius >= outer_radius)
          scene.fail("Geometry/Inner radius", "is " + str(inner_radius) +
                                                ": expected less than Outer radius (" +
                                                str(outer_radius) + " mm)");
        if (circumferential_cells == 1 || circumferential_cells == 2)
          scene.fail("Geometry/Circumferential cells", "must be 0 (automatic) or at least 3");
        if (type == "tube")
          positive("Length", length);
        bodies[body_name] = 0;
        boundaries        = {{"inner", 0}, {"outer", 1}};
        if (type == "tube")
          boundaries.insert({{"bottom", 2}, {"top", 3}});
      }
    else if (type == "bar")
      {
        positive("Radius", radius);
        positive("Length", length);
        bodies[body_name] = 0;
        if (dim == 2)
          boundaries = {{"axis", 0}, {"side", 1}, {"bottom", 2}, {"top", 3}};
        else
          boundaries = {{"side", 0}, {"bottom", 1}, {"top", 2}};
      }
    else // gmsh
      {
        if (mesh_file.empty())
          scene.fail("Geometry/Mesh file", "is empty: Type = gmsh needs the path of a .msh file");
        // Relative to the directory of the scene file, so scenes can be run from anywhere.
        const auto slash = scene.filename().find_last_of('/');
        if (mesh_file[0] != '/' && slash != std::string::npos)
          mesh_file = scene.filename().substr(0, slash + 1) + mesh_file;
        std::ifstream in(mesh_file);
        if (!in)
          scene.fail("Geometry/Mesh file", "is '" + mesh_file + "', which does not exist or cannot be read "
                                           "(relative paths are relative to the scene file's directory)");
        const auto fail = [&](const std::string &what) {
          scene.fail("Geometry/Mesh file", "('" + mesh_file + "') " + what);
        };
        scan_msh<dim>(in, fail, boundaries, bodies);
      }
  }

  template <int dim>
  void Geometry<dim>::transform(Triangulation<dim> &triangulation) const
  {
    if (!transformation.empty())
      GridTools::transform(
        [this](const Point<dim> &p) {
          Point<dim> q;
          for (unsigned int d = 0; d < dim; ++d)
            q[d] = transformation[d]->value(p);
          return q;
        },
        triangulation);
  }

  template <int dim>
  void Geometry<dim>::create_gmsh(Triangulation<dim> &tria) const
  {
    // The stream overload: the filename overload goes through the gmsh API,
    // which ignores unnamed physical groups. Physical tags become boundary
    // ids (faces) and material ids (cells).
    std::ifstream in(mesh_file);
    if (!in)
      throw InputError(mesh_file + ": cannot read the mesh file (Geometry/Mesh file)");
    std::string version;
    std::getline(in, version) && std::getline(in, version);
    if (version.rfind("2.", 0) == 0)
      check_msh22(in);
    in.clear();
    in.seekg(0);
    GridIn<dim> grid_in;
    grid_in.attach_triangulation(tria);
    try
      {
        grid_in.read_msh(in);
      }
    catch (const std::bad_alloc &)
      {
        throw InputError(mesh_file + ": cannot read this mesh (Geometry/Mesh file): it declares "
                                     "more nodes or elements than memory holds (a wrong count?)");
      }
    catch (const ExceptionBase &e)
      {
        std::stringstream text;
        e.print_info(text);
        std::string message; // deal.II's text, on one line with single blanks
        for (std::string word; text >> word;)
          message += (message.empty() ? "" : " ") + word;
        if (message.find("internal face") != std::string::npos)
          message = "a physical group of dimension " + std::to_string(dim - 1) +
                    " lies inside the mesh (e.g. between two bodies); only boundary curves/"
                    "surfaces can be named. deal.II says: " + message;
        throw InputError(mesh_file + ": cannot read this mesh (Geometry/Mesh file): " + message);
      }
  }

  template <int dim>
  types::boundary_id Geometry<dim>::boundary_id(const std::string &name, const std::string &where) const
  {
    return find_id(boundaries, "boundary", name, where, list_boundary_names());
  }

  template <int dim>
  types::material_id Geometry<dim>::body_id(const std::string &name, const std::string &where) const
  {
    return find_id(bodies, "body", name, where, list_body_names());
  }

  template <int dim>
  std::string Geometry<dim>::list_boundary_names() const
  {
    return list_names(boundaries);
  }

  template <int dim>
  std::string Geometry<dim>::list_body_names() const
  {
    return list_names(bodies);
  }

  ANVIL_INSTANTIATE_CLASS(Geometry)
} // namespace anvil
