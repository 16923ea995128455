// A one-level mesh as arrays (include/anvil/geometry/mesh_arrays.h): the
// blocks generator's boxes, and the Triangulation made from them.
#include <deal.II/base/tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/geometry/mesh_arrays.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void append_box(MeshArrays<dim> &mesh, const Point<dim> &lower, const Point<dim> &upper,
                  const std::vector<unsigned int> &subdivisions, const types::material_id material,
                  const types::boundary_id first_face_id)
  {
    // GridGenerator::subdivided_hyper_rectangle's points, p1 + x*delta[0] +
    // y*delta[1] (+ z*delta[2]) in this order of operations: the same
    // vertices to the last bit.
    std::array<Tensor<1, dim>, dim> delta;
    for (unsigned int d = 0; d < dim; ++d)
      delta[d][d] = (upper[d] - lower[d]) / subdivisions[d];
    const unsigned int offset = mesh.vertices.size();
    const unsigned int nx = subdivisions[0], ny = subdivisions[1], nz = dim == 3 ? subdivisions[dim - 1] : 1;
    for (unsigned int z = 0; z < (dim == 3 ? nz + 1 : 1); ++z)
      for (unsigned int y = 0; y <= ny; ++y)
        for (unsigned int x = 0; x <= nx; ++x)
          {
            Point<dim> p = lower + x * delta[0] + y * delta[1];
            if constexpr (dim == 3)
              p = p + z * delta[2];
            mesh.vertices.push_back(p);
          }
    // Cells x fastest, vertices in deal.II's lexicographic order; a face lies
    // in a plane of the box where the cell is the first or last of its row.
    const unsigned int n_x = nx + 1, n_xy = (nx + 1) * (ny + 1);
    for (unsigned int z = 0; z < nz; ++z)
      for (unsigned int y = 0; y < ny; ++y)
        for (unsigned int x = 0; x < nx; ++x)
          {
            CellData<dim> cell;
            for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
              cell.vertices[v] = offset + (z + (v >> 2)) * n_xy + (y + ((v >> 1) & 1)) * n_x + x + (v & 1);
            cell.material_id = material;
            mesh.cells.push_back(cell);
            const std::array<unsigned int, 3> index{{x, y, z}}, count{{nx, ny, nz}};
            std::array<types::boundary_id, GeometryInfo<dim>::faces_per_cell> faces;
            for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
              faces[f] = index[f / 2] == (f % 2 == 0 ? 0 : count[f / 2] - 1) ?
                           first_face_id + f :
                           numbers::internal_face_boundary_id;
            mesh.face_ids.push_back(faces);
          }
  }

  template <int dim>
  void MeshArrays<dim>::create_triangulation(Triangulation<dim> &tria) const
  {
    tria.create_triangulation(vertices, cells, SubCellData());
    // Coarse cells keep the order they were given in.
    for (const auto &cell : tria.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          cell->face(f)->set_boundary_id(face_ids[cell->index()][f]);
  }

#define INSTANTIATE(dim)                                                                           \
  template struct MeshArrays<dim>;                                                                 \
  template void append_box(MeshArrays<dim> &, const Point<dim> &, const Point<dim> &,             \
                           const std::vector<unsigned int> &, types::material_id,                \
                           types::boundary_id);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
