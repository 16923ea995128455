#pragma once

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/geometry/mesh_arrays.h>

#include <string>
#include <vector>

namespace anvil
{
  /// The cut of a mesh's cells into bodies and slabs (cut_per_body()).
  struct PerBodyCut
  {
    std::vector<dealii::types::subdomain_id> owner;     // process of every cell
    std::vector<unsigned int>                component; // body (connected component) of every cell
  };

  /**
   * The partition of partition_per_body() for cells given by their vertex
   * indices (into @p n_vertices vertices), material ids and centres.
   */
  template <int dim>
  PerBodyCut cut_per_body(const std::vector<dealii::CellData<dim>> &cells,
                          const std::vector<dealii::Point<dim>>    &centers,
                          unsigned int                              n_vertices,
                          unsigned int                              n_parts);

  /**
   * This process's part of the one-level mesh @p mesh cut per body over the
   * processes of @p comm: the cells it owns and every cell that shares a
   * vertex with them, numbered as deal.II's
   * TriangulationDescription::Utilities::create_description_from_triangulation()
   * numbers them from the whole Triangulation (the same description, entry for
   * entry: tests/mesh_arrays.cc), without a Triangulation of the whole mesh.
   */
  template <int dim>
  dealii::TriangulationDescription::Description<dim, dim>
  describe_per_body(const MeshArrays<dim> &mesh, MPI_Comm comm);

  /// Build @p triangulation from describe_per_body() (the boundary ids set
  /// after creation: per_body_description.cc says why).
  template <int dim>
  void create_per_body(const MeshArrays<dim>                                  &mesh,
                       dealii::parallel::fullydistributed::Triangulation<dim> &triangulation);

  /**
   * Geometry/Partition = per body (issue 15). p4est numbers the coarse cells of
   * each connected component consecutively, so with two bodies on two processes
   * each process gets one body and the contact surface is the partition
   * boundary. Here every body is cut into @p n_parts slabs of equal cell count
   * along its own longest axis, so that every process holds a share of every
   * body and of every contact surface.
   *
   * A body is a connected component, through shared vertices, of the active
   * cells of one material id (blocks that touch may share vertices).
   * Sets the subdomain id of every active cell of @p serial; returns the
   * component of every active cell (by active_cell_index()).
   */
  template <int dim>
  std::vector<unsigned int> partition_per_body(dealii::Triangulation<dim> &serial,
                                               unsigned int                n_parts);

  /// Build @p triangulation from the whole refined mesh @p serial, partitioned
  /// per body over the triangulation's processes.
  template <int dim>
  void create_per_body(dealii::Triangulation<dim>                         &serial,
                       dealii::parallel::fullydistributed::Triangulation<dim> &triangulation);

  /**
   * The fully distributed triangulation of Geometry/Partition = per body, with
   * its own save() and load() of the checkpoint's cell-attached data (vectors,
   * material points, temperatures).
   *
   * save() writes deal.II 9.4's info and cell-data files as its
   * fullydistributed::Triangulation::save() does, but not the triangulation
   * description: deal.II rebuilt it from the mesh and serialised it through
   * boost at every checkpoint (~340 M instructions on one process of the
   * contact strip, ~245 M per process on two, whatever the share). The mesh
   * never changes in a run and a per-body checkpoint restarts only on as many
   * processes as wrote it, so load() takes the mesh the scene creates (the
   * same cells on the same processes) and checks it against the saved one's
   * cell count and vertex print (an "anvil-mesh" line after deal.II's in the
   * info file) before reading the cell data.
   *
   * Process r's cell data sit right after those of processes < r (deal.II
   * 9.4's save() wrote them 4 times further on, at 4 * (cells of processes
   * < r), the cell count scaled by sizeof(unsigned int), and its load() read
   * every process's from offset 0: on two processes, process 1 got process
   * 0's states; plastic_block's reaction 17.10 against 11.58 after a
   * restart, tests/partition_per_body.py).
   */
  template <int dim>
  class PerBodyTriangulation : public dealii::parallel::fullydistributed::Triangulation<dim>
  {
  public:
    using dealii::parallel::fullydistributed::Triangulation<dim>::Triangulation;
    using dealii::parallel::fullydistributed::Triangulation<dim>::load;
    void save(const std::string &filename) const override;
    /// Read the cell data of a checkpoint into this (created) mesh.
    void load(const std::string &filename) override;
  };
} // namespace anvil
