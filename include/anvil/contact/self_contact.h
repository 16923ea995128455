#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <utility>
#include <vector>

namespace anvil
{
  namespace contact
  {
    /**
     * Outward unit normal of a contact face from its current vertices, ordered
     * as for node_to_segment(): 2D the left normal of x₁ − x₀, 3D the normal
     * of the bilinear facet at its centre (diagonals' cross product). A
     * degenerate face gives the zero vector.
     */
    template <int dim>
    dealii::Tensor<1, dim> face_normal(const std::vector<dealii::Point<dim>> &x);

    /**
     * Which master faces a slave node may not touch in self-contact (a pair
     * whose Slave and Master are the same boundaries; issue 12).
     *
     * Every node of a surface lies on its own faces (gap 0) and, on a convex
     * surface, slightly behind the planes of the faces next to those: a plain
     * node-to-segment search would put a flat or curved surface in contact
     * with itself. The rings of a node: ring 1 its own faces, ring k + 1 the
     * faces sharing a vertex with ring k (topological distance along the
     * surface, so independent of the deformation). Excluded:
     *  - rings 1 and 2 always (own faces and their neighbours);
     *  - rings 3 … `rings` (a few element sizes along the surface) when the
     *    face's outward normal faces the same way as the node's
     *    (n_face · n_node > 0): the surface next to the node, however curved.
     * What a concertina fold needs stays: its two skins come together face to
     * face (opposite normals), and far along the surface (beyond `rings`)
     * nothing is excluded, so a skin folded onto itself over a few elements
     * (the tip of a fold: a U of opposite normals) touches itself.
     */
    class SelfContactNeighbourhood
    {
    public:
      /// @p face_nodes: the surface's faces (node numbers), @p n_nodes nodes in all.
      void build(const std::vector<std::vector<unsigned int>> &face_nodes,
                 unsigned int                                   n_nodes,
                 unsigned int                                   rings = 4);

      /// The ring (1, 2, ...) of @p face seen from @p node, or 0 if beyond `rings`.
      unsigned int ring(unsigned int node, unsigned int face) const;

      /// Never a candidate of @p node, whatever the configuration (rings 1 and 2).
      bool always_excluded(unsigned int node, unsigned int face) const;

      /// Excluded now, given the node's and the face's current outward normals.
      template <int dim>
      bool excluded(unsigned int node, unsigned int face, const dealii::Tensor<1, dim> &node_normal,
                    const dealii::Tensor<1, dim> &face_normal) const
      {
        const unsigned int k = ring(node, face);
        return k != 0 && (k <= 2 || node_normal * face_normal > 0);
      }

      /**
       * Whether @p face may be a master of @p node at the current positions
       * @p x (indexed by node): beyond the rings, or within rings 3 … `rings`
       * and turned against the node's normal (the mean of its own faces').
       */
      template <int dim>
      bool may_touch(unsigned int node, unsigned int face, const std::vector<dealii::Point<dim>> &x) const;

      /// Faces of @p node (ring 1).
      const std::vector<unsigned int> &own_faces(unsigned int node) const { return own[node]; }

    private:
      std::vector<std::vector<unsigned int>>                          face_nodes;
      unsigned int                                                   n_rings = 4;
      std::vector<std::vector<std::pair<unsigned int, unsigned int>>> near; // per node: (face, ring), sorted by face
      std::vector<std::vector<unsigned int>>                          own;
    };
  } // namespace contact
} // namespace anvil
