// Geometry, the built-in meshes: blocks (one or several bodies), the ring
// (annulus, tube, axisymmetric tube section) and the bar (solid cylinder, or
// its axisymmetric section), each with its named faces. geometry.cc parses the
// scene and imports gmsh meshes.
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <anvil/core/instantiate.h>
#include <anvil/geometry/geometry.h>
#include <anvil/geometry/mesh_arrays.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // True if every vertex of @p face satisfies @p predicate. Vertices are exact
    // (unlike face centres, which on a curved boundary lie on a chord).
    template <typename FaceIterator, typename Predicate>
    bool all_vertices(const FaceIterator &face, const Predicate &predicate)
    {
      for (const unsigned int v : face->vertex_indices())
        if (!predicate(face->vertex(v)))
          return false;
      return true;
    }

    // Set the boundary id of every boundary face to classify(cell, face).
    template <int dim, typename Classify>
    void label_boundary(Triangulation<dim> &tria, const Classify &classify)
    {
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            face->set_boundary_id(classify(cell, face));
    }

    /*
     * Boxes into one coarse mesh. GridGenerator::merge_triangulations would
     * merge coincident vertices and so glue touching blocks together; blocks
     * are separate bodies (possibly in contact), so their vertex and cell
     * lists are concatenated (mesh_arrays.cc), which keeps every block's
     * vertices distinct. Cell material id = box index; boundary id of face k
     * of box b = 2*dim*b + k. Box is Geometry<dim>::Block (lower, upper,
     * subdivisions).
     */
    template <int dim, typename Box>
    MeshArrays<dim> box_arrays(const std::vector<Box> &boxes)
    {
      MeshArrays<dim> mesh;
      for (unsigned int b = 0; b < boxes.size(); ++b)
        append_box(mesh, boxes[b].lower, boxes[b].upper, boxes[b].subdivisions, b, 2 * dim * b);
      return mesh;
    }

    template <int dim, typename Box>
    void build_boxes(Triangulation<dim> &tria, const std::vector<Box> &boxes)
    {
      box_arrays<dim>(boxes).create_triangulation(tria);
    }

    // The axisymmetric section r in [r0, r1] (x), z in [0, length] (y) of tube and bar.
    template <int dim, typename Box>
    void build_section(Triangulation<dim> &tria, Box box, const double r0, const double r1,
                       const double length)
    {
      box.lower[0] = r0;
      box.upper[0] = r1;
      box.upper[1] = length;
      build_boxes(tria, std::vector<Box>{box});
    }

    /*
     * A ring r in [ri, ro] (2D) or a tube, additionally z in [0, length] (3D),
     * with n_r layers through the thickness. Built directly (hyper_shell and
     * cylinder_shell have a single layer through the thickness) with evenly
     * spaced radii. Local cell axes (r, phi, z) are right-handed. All manifold
     * ids are 0: SphericalManifold about the origin in 2D, CylindricalManifold
     * about z in 3D (exact for both cylinders and the flat annular ends).
     */
    template <int dim>
    void build_ring(Triangulation<dim> &tria, const double ri, const double ro, const double length,
                    const unsigned int n_r, const unsigned int n_phi, const unsigned int n_z)
    {
      const unsigned int n_layers = dim == 3 ? n_z + 1 : 1;
      const auto index = [&](unsigned int k, unsigned int j, unsigned int l) {
        return (l * n_phi + j % n_phi) * (n_r + 1) + k;
      };
      std::vector<Point<dim>> vertices;
      for (unsigned int l = 0; l < n_layers; ++l)
        for (unsigned int j = 0; j < n_phi; ++j)
          for (unsigned int k = 0; k <= n_r; ++k)
            {
              const double r   = ri + (ro - ri) * k / n_r;
              const double phi = 2 * numbers::PI * j / n_phi;
              Point<dim>   p;
              p[0] = r * std::cos(phi);
              p[1] = r * std::sin(phi);
              if (dim == 3)
                p[dim - 1] = length * l / n_z;
              vertices.push_back(p);
            }
      std::vector<CellData<dim>> cells;
      for (unsigned int l = 0; l < std::max(1u, n_layers - 1); ++l)
        for (unsigned int j = 0; j < n_phi; ++j)
          for (unsigned int k = 0; k < n_r; ++k)
            {
              CellData<dim> data;
              for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
                data.vertices[v] = index(k + (v & 1), j + ((v >> 1) & 1), l + ((v >> 2) & 1));
              data.material_id = 0;
              cells.push_back(data);
            }
      tria.create_triangulation(vertices, cells, SubCellData());
      tria.set_all_manifold_ids(0);
      if constexpr (dim == 2)
        tria.set_manifold(0, SphericalManifold<2>(Point<2>()));
      else
        tria.set_manifold(0, CylindricalManifold<3>(2));

      // inner = 0, outer = 1, bottom = 2, top = 3.
      const double tol = 1e-10 * ro;
      label_boundary(tria, [&](const auto &, const auto &face) {
        const auto radius = [](const Point<dim> &p) { return std::hypot(p[0], p[1]); };
        if (all_vertices(face, [&](const Point<dim> &p) { return radius(p) < ri + tol; }))
          return 0u;
        if (all_vertices(face, [&](const Point<dim> &p) { return radius(p) > ro - tol; }))
          return 1u;
        return all_vertices(face, [&](const Point<dim> &p) { return p[dim - 1] < tol; }) ? 2u : 3u;
      });
    }

  } // namespace

  template <int dim>
  void Geometry<dim>::create_blocks(Triangulation<dim> &tria) const
  {
    build_boxes(tria, blocks);
  }

  template <int dim>
  void Geometry<dim>::create_ring(Triangulation<dim> &tria) const
  {
    if (dim == 2 && type == "tube") // face ids 0..3 = inner, outer, bottom, top
      return build_section(tria, Block{body_name, {}, {}, {radial_cells, axial_cells}},
                           inner_radius, outer_radius, length);
    unsigned int n_phi = circumferential_cells;
    if (n_phi == 0)
      {
        // Cells about as long around the mid radius as they are thick; a
        // multiple of 4 keeps the mesh symmetric about the x and y axes.
        const double thickness = (outer_radius - inner_radius) / radial_cells;
        n_phi = static_cast<unsigned int>(
          std::ceil(numbers::PI * (inner_radius + outer_radius) / thickness));
        n_phi = std::max(4u, 4 * ((n_phi + 3) / 4));
      }
    build_ring(tria, inner_radius, outer_radius, length, radial_cells, n_phi, axial_cells);
  }

  template <int dim>
  void Geometry<dim>::create_bar(Triangulation<dim> &tria) const
  {
    if constexpr (dim == 2) // face ids 0..3 = axis, side, bottom, top
      build_section(tria, Block{body_name, {}, {}, {radial_cells, axial_cells}}, 0., radius, length);
    else
      {
        // subdivided_cylinder runs along x in [-L/2, L/2] with a CylindricalManifold
        // (id 0) on its hull. The cyclic permutation (x, y, z) -> (y, z, x)
        // keeps cells right-handed and puts the axis on z; then shift to [0, L].
        GridGenerator::subdivided_cylinder(tria, axial_cells, radius, length / 2);
        const double half = length / 2;
        GridTools::transform([half](const Point<dim> &p) { return Point<dim>(p[1], p[2], p[0] + half); },
                             tria);
        tria.set_manifold(0, CylindricalManifold<3>(2));
        // side = 0, bottom = 1, top = 2.
        const double tol = 1e-10 * std::max(radius, length);
        label_boundary(tria, [&](const auto &, const auto &face) {
          if (all_vertices(face, [&](const Point<dim> &p) { return std::abs(p[2]) < tol; }))
            return 1u;
          const auto top = [&](const Point<dim> &p) { return std::abs(p[2] - length) < tol; };
          return all_vertices(face, top) ? 2u : 0u;
        });
        for (const auto &cell : tria.active_cell_iterators())
          cell->set_material_id(0);
      }
  }

#define INSTANTIATE(dim)                                                                           \
  template void Geometry<dim>::create_blocks(Triangulation<dim> &) const;                         \
  template void Geometry<dim>::create_ring(Triangulation<dim> &) const;                           \
  template void Geometry<dim>::create_bar(Triangulation<dim> &) const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
