// The search for a free facet edge of a 3D master surface beyond which a
// slave node still feels the facet, tapered (free_end.h, free_edge_contact;
// doc/contact.md, "Free ends").
#include <anvil/contact/contact_problem.h>
#include <anvil/contact/free_end.h>
#include <anvil/core/instantiate.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  int ContactProblem<dim>::free_edge_face(
    const unsigned int p, const unsigned int pass, const unsigned int n,
    const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end,
    const std::vector<Point<dim>> &x, const contact::NodeState<dim> &state,
    const contact::FrictionLaw &law, const bool with_matrix, int best_face,
    contact::ContactResult<dim> &result) const
  {
    int found = -1;
    if constexpr (dim == 3)
      for (const auto &entry : beyond_end)
        {
          const unsigned int      f = entry.first;
          std::vector<Point<dim>> xm, xm_old;
          face_positions(f, x, xm, xm_old);
          // Which edge: the one coordinate of the closest point outside [0, 1]
          // (beyond two at once, a corner, is not tapered).
          const auto probe = contact::node_to_segment(x[n], x_old[n], xm, xm_old, state, law, false);
          if (probe.xi.size() != 2)
            continue;
          const double tol = contact::end_tolerance;
          unsigned int edge = 4, outside = 0;
          for (unsigned int k = 0; k < 2; ++k)
            if (probe.xi[k] < -tol || probe.xi[k] > 1 + tol)
              {
                edge = 2 * k + (probe.xi[k] > 1 ? 1 : 0);
                ++outside;
              }
          if (outside != 1)
            continue;
          // Free: no other facet of the master surface has both its vertices
          // (deal.II's line 2k + e of a quadrilateral: vertices with ξ_k = e).
          const unsigned int stride = edge / 2 == 0 ? 1 : 2;
          std::vector<unsigned int> vertices;
          for (unsigned int v = 0; v < 4; ++v)
            if ((v / stride) % 2 == edge % 2)
              vertices.push_back(faces[f].nodes[v]);
          bool free = true;
          for (const auto g : node_faces[vertices[0]])
            if (g != f && master_side(p, pass).has(faces[g]))
              for (const auto m : faces[g].nodes)
                free = free && m != vertices[1];
          if (!free)
            continue;
          auto r = contact::free_edge_contact(x[n], x_old[n], xm, xm_old, edge, state, law,
                                              with_matrix, pairs[p].end_taper);
          if (r.in_contact && (best_face < 0 || std::abs(r.gap) < std::abs(result.gap)))
            {
              result    = std::move(r);
              best_face = f;
              found     = f;
            }
        }
    return found;
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
