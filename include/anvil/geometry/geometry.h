#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/distributed/tria_base.h>

#include <istream>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * The mesh of a scene and the names of its parts.
   *
   * Built-in generators (all with named faces and a named body):
   *  - `blocks`: one or several axis-parallel rectangles (2D) / boxes (3D) with
   *    subdivisions. With one block the faces are named left, right, bottom,
   *    top (and front, back in 3D: z = z0, z = z1); with several, the faces
   *    of block B are named B.left, B.right, ...
   *  - `annulus` (2D) / `tube` (3D): a ring of inner and outer radius; faces
   *    inner, outer (and bottom, top in 3D for z = 0 and z = length).
   *  - `bar`: a cylindrical bar along z (3D), faces side, bottom, top; in 2D
   *    its axisymmetric section r in [0, R], z in [0, L], faces axis, side,
   *    bottom, top.
   *  - `gmsh`: a .msh file (format 2.2 or 4.1); physical names become boundary
   *    names (dimension dim-1) and body names (dimension dim). Unnamed physical
   *    groups are called boundary_<tag> and body_<tag>.
   */
  template <int dim>
  class Geometry
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);

    /// Reads the Geometry subsection; checks ranges and that the mesh file exists.
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene);

    /// The triangulation Geometry/Partition asks for, empty: p4est's
    /// (space-filling curve) or a fully distributed one (per body).
    std::unique_ptr<dealii::parallel::DistributedTriangulationBase<dim>>
    make_triangulation(MPI_Comm communicator) const;

    /// Build the coarse mesh, name its parts, refine globally, transform
    /// (and, for a fully distributed triangulation, partition per body).
    void create(dealii::parallel::DistributedTriangulationBase<dim> &triangulation) const;

    /// Read the mesh a checkpoint saved in @p file into an empty triangulation
    /// of the kind that saved it.
    void load(dealii::parallel::DistributedTriangulationBase<dim> &triangulation,
              const std::string                                   &file) const;

    /// Geometry/Partition: "space-filling curve" or "per body".
    const std::string &partition_kind() const { return partition; }

    const std::map<std::string, dealii::types::boundary_id> &boundary_names() const
    {
      return boundaries;
    }
    const std::map<std::string, dealii::types::material_id> &body_names() const
    {
      return bodies;
    }

    /// The id of a named boundary, or an InputError listing the known names.
    dealii::types::boundary_id boundary_id(const std::string &name,
                                           const std::string &where) const;

    /// The id of a named body, or an InputError listing the known names.
    dealii::types::material_id body_id(const std::string &name, const std::string &where) const;

    /// "left, right, top" — for error messages.
    std::string list_boundary_names() const;
    std::string list_body_names() const;

  private:
    struct Block
    {
      std::string               name;
      dealii::Point<dim>        lower, upper;
      std::vector<unsigned int> subdivisions;
    };

    void create_blocks(dealii::Triangulation<dim> &tria) const;
    void create_ring(dealii::Triangulation<dim> &tria) const;
    void create_bar(dealii::Triangulation<dim> &tria) const;
    void create_gmsh(dealii::Triangulation<dim> &tria) const;
    /// The coarse mesh of any type, randomly distorted if asked.
    void create_serial_coarse(dealii::Triangulation<dim> &serial) const;
    /// Build only the coarse mesh (p4est's load() then refines it as saved).
    void create_coarse(dealii::parallel::DistributedTriangulationBase<dim> &triangulation) const;
    /// Apply the Transformation to a refined mesh (p4est: after load() too).
    void transform(dealii::Triangulation<dim> &triangulation) const;
    /// The manifolds of the coarse mesh's curved parts, set on @p triangulation.
    void copy_manifolds(const dealii::Triangulation<dim> &serial,
                        dealii::Triangulation<dim>       &triangulation) const;
    // mesh_check.cc: refuse with one line what the run could not use.
    void check_msh22(std::istream &in) const;
    void check_size(unsigned int n_coarse_cells) const;
    void check_cells(const dealii::parallel::DistributedTriangulationBase<dim> &tria) const;

    std::string        type;
    std::vector<Block> blocks;
    // ring and bar
    std::string  body_name;
    double       inner_radius = 0, outer_radius = 1, radius = 1, length = 1;
    unsigned int radial_cells = 1, axial_cells = 1, circumferential_cells = 0;
    // gmsh
    std::string  mesh_file;
    unsigned int global_refinements = 0;
    std::string  partition          = "space-filling curve";
    double       random_distortion  = 0;
    std::vector<std::shared_ptr<dealii::FunctionParser<dim>>> transformation;
    std::map<std::string, std::string> locations; // entry -> where the scene sets it

    // Filled by parse_parameters (generators) or by create (gmsh reads the file
    // once at parse to learn the names, so they are known before any work).
    std::map<std::string, dealii::types::boundary_id> boundaries;
    std::map<std::string, dealii::types::material_id> bodies;
  };
} // namespace anvil
