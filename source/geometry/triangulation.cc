// The distributed triangulation of either kind (Geometry/Partition): p4est's
// from the coarse mesh, refined in parallel; or per body, a fully distributed
// one cut from the whole refined mesh (partition.cc), or for unrefined blocks
// described from the generator's arrays (per_body_description.cc) — created
// and reloaded.
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/geometry/geometry.h>
#include <anvil/geometry/mesh_arrays.h>
#include <anvil/geometry/partition.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  std::unique_ptr<parallel::DistributedTriangulationBase<dim>>
  Geometry<dim>::make_triangulation(const MPI_Comm communicator) const
  {
    if (partition == "per body")
      return std::make_unique<PerBodyTriangulation<dim>>(communicator);
    return std::make_unique<parallel::distributed::Triangulation<dim>>(communicator);
  }

  template <int dim>
  void Geometry<dim>::create_serial_coarse(Triangulation<dim> &serial) const
  {
    if (type == "blocks")
      create_blocks(serial);
    else if (type == "annulus" || type == "tube")
      create_ring(serial);
    else if (type == "bar")
      create_bar(serial);
    else
      create_gmsh(serial);
    if (random_distortion > 0)
      GridTools::distort_random(random_distortion, serial, true, 42);
  }

  template <int dim>
  void Geometry<dim>::copy_manifolds(const Triangulation<dim> &serial,
                                     Triangulation<dim>       &triangulation) const
  {
    // Manifold ids of cells and faces are copied with the mesh; the manifold
    // objects are set again explicitly (ours are Spherical/Cylindrical, which
    // hold no reference to the serial triangulation).
    for (const types::manifold_id id : serial.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        triangulation.set_manifold(id, serial.get_manifold(id));
  }

  template <int dim>
  void Geometry<dim>::create_coarse(parallel::DistributedTriangulationBase<dim> &triangulation) const
  {
    // p4est needs the coarse mesh as a whole: build it serially, then copy.
    // Same smoothing as the target, since copy_triangulation copies it.
    Triangulation<dim> serial(triangulation.get_mesh_smoothing());
    create_serial_coarse(serial);
    triangulation.copy_triangulation(serial);
    copy_manifolds(serial, triangulation);
  }

  template <int dim>
  void Geometry<dim>::create(parallel::DistributedTriangulationBase<dim> &triangulation) const
  {
    if (auto *p4est = dynamic_cast<parallel::distributed::Triangulation<dim> *>(&triangulation))
      {
        create_coarse(*p4est);
        check_size(triangulation.n_global_active_cells());
        triangulation.refine_global(global_refinements);
        transform(triangulation);
      }
    else if (type == "blocks" && global_refinements == 0 && random_distortion == 0)
      {
        // Per body, one level of flat blocks: each process describes its
        // part from the generator's arrays (per_body_description.cc).
        MeshArrays<dim> mesh;
        for (unsigned int b = 0; b < blocks.size(); ++b) // as create_blocks() numbers them
          append_box(mesh, blocks[b].lower, blocks[b].upper, blocks[b].subdivisions, b, 2 * dim * b);
        check_size(mesh.cells.size());
        if (!transformation.empty()) // as transform() maps every vertex
          for (auto &p : mesh.vertices)
            {
              const Point<dim> x = p;
              for (unsigned int d = 0; d < dim; ++d)
                p[d] = transformation[d]->value(x);
            }
        create_per_body(mesh, dynamic_cast<parallel::fullydistributed::Triangulation<dim> &>(triangulation));
      }
    else
      {
        // Per body: the whole refined (and transformed) mesh on every
        // process, cut by partition_per_body, each process keeping its share.
        Triangulation<dim> serial;
        create_serial_coarse(serial);
        check_size(serial.n_active_cells());
        serial.refine_global(global_refinements);
        transform(serial);
        create_per_body(serial, dynamic_cast<parallel::fullydistributed::Triangulation<dim> &>(
                                  triangulation));
        copy_manifolds(serial, triangulation);
      }
    throw_recorded_input_error(triangulation.get_communicator());
    check_cells(triangulation);
  }

  template <int dim>
  void Geometry<dim>::load(parallel::DistributedTriangulationBase<dim> &triangulation,
                           const std::string                           &file) const
  {
    if (auto *p4est = dynamic_cast<parallel::distributed::Triangulation<dim> *>(&triangulation))
      {
        // p4est saves the refinement of the coarse mesh, not the vertices.
        create_coarse(*p4est);
        triangulation.load(file);
        transform(triangulation);
      }
    else
      {
        // Per body: the mesh as the scene creates it (a per-body checkpoint
        // holds no mesh: include/anvil/geometry/partition.h), then the cells'
        // data.
        create(triangulation);
        triangulation.load(file);
        return;
      }
    throw_recorded_input_error(triangulation.get_communicator());
    check_cells(triangulation);
  }

  ANVIL_INSTANTIATE_CLASS(Geometry)
} // namespace anvil
