#pragma once

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <array>
#include <vector>

namespace anvil
{
  /**
   * A mesh of one level (no refinement) as plain arrays: what a generator
   * makes before any Triangulation exists. Geometry/Partition = per body cuts
   * it and describes each process's part directly (per_body_description.cc),
   * so that no process builds a Triangulation of the whole mesh; one process
   * builds the whole Triangulation from it (create_triangulation()).
   */
  template <int dim>
  struct MeshArrays
  {
    std::vector<dealii::Point<dim>>    vertices;
    std::vector<dealii::CellData<dim>> cells; // vertex indices and material id
    /// The boundary id of face f of cell c at [c][f]; inner faces hold
    /// numbers::internal_face_boundary_id.
    std::vector<std::array<dealii::types::boundary_id, dealii::GeometryInfo<dim>::faces_per_cell>>
      face_ids;

    /// The Triangulation of these arrays, with the faces' boundary ids.
    void create_triangulation(dealii::Triangulation<dim> &tria) const;
  };

  /**
   * The cells and vertices of one box cut into subdivisions[d] cells per
   * direction, appended to @p mesh with material id @p material and the faces
   * in the box's planes numbered first_face_id + k (k = 2d at the lower, 2d + 1
   * at the upper end of direction d). Vertices and cells in the order, and
   * with the arithmetic, of GridGenerator::subdivided_hyper_rectangle (deal.II
   * 9.4), so the mesh and the answers are the same as by deal.II's generator
   * (checked vertex for vertex in tests/mesh_arrays.cc).
   */
  template <int dim>
  void append_box(MeshArrays<dim>                 &mesh,
                  const dealii::Point<dim>        &lower,
                  const dealii::Point<dim>        &upper,
                  const std::vector<unsigned int> &subdivisions,
                  dealii::types::material_id       material,
                  dealii::types::boundary_id       first_face_id);
} // namespace anvil
