// Self-contact (issue 12): the faces a slave node may not touch on its own
// surface, and the outward normal of a face; see self_contact.h.
#include <anvil/contact/self_contact.h>
#include <anvil/core/instantiate.h>

#include <algorithm>
#include <set>

namespace anvil
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    Tensor<1, dim> face_normal(const std::vector<Point<dim>> &x)
    {
      Tensor<1, dim> n;
      if constexpr (dim == 2)
        {
          const Tensor<1, dim> e = x[1] - x[0];
          n[0]                   = -e[1];
          n[1]                   = e[0];
        }
      else
        n = cross_product_3d(x[3] - x[0], x[2] - x[1]); // ∥ x_ξ × x_η at the centre
      const double length = n.norm();
      return length > 0 ? n / length : Tensor<1, dim>();
    }

    void SelfContactNeighbourhood::build(const std::vector<std::vector<unsigned int>> &face_nodes,
                                         const unsigned int n_nodes, const unsigned int rings)
    {
      n_rings          = rings;
      this->face_nodes = face_nodes;
      own.assign(n_nodes, {});
      for (unsigned int f = 0; f < face_nodes.size(); ++f)
        for (const auto n : face_nodes[f])
          own[n].push_back(f);
      near.assign(n_nodes, {});
      for (unsigned int n = 0; n < n_nodes; ++n)
        {
          if (own[n].empty())
            continue;
          // Breadth-first over faces sharing a vertex, ring by ring.
          std::set<unsigned int>    seen_faces(own[n].begin(), own[n].end());
          std::set<unsigned int>    seen_nodes{n};
          std::vector<unsigned int> front = own[n];
          for (unsigned int k = 1; k <= n_rings && !front.empty(); ++k)
            {
              std::vector<unsigned int> next;
              for (const auto f : front)
                {
                  near[n].emplace_back(f, k);
                  for (const auto m : face_nodes[f])
                    if (seen_nodes.insert(m).second)
                      for (const auto g : own[m])
                        if (seen_faces.insert(g).second)
                          next.push_back(g);
                }
              front = std::move(next);
            }
          std::sort(near[n].begin(), near[n].end());
        }
    }

    unsigned int SelfContactNeighbourhood::ring(const unsigned int node, const unsigned int face) const
    {
      if (node >= near.size())
        return 0;
      const auto &list = near[node];
      const auto  it   = std::lower_bound(list.begin(), list.end(), std::make_pair(face, 0u));
      return it != list.end() && it->first == face ? it->second : 0;
    }

    bool SelfContactNeighbourhood::always_excluded(const unsigned int node, const unsigned int face) const
    {
      const unsigned int k = ring(node, face);
      return k == 1 || k == 2;
    }

    template <int dim>
    bool SelfContactNeighbourhood::may_touch(const unsigned int node, const unsigned int face,
                                             const std::vector<Point<dim>> &x) const
    {
      const unsigned int k = ring(node, face);
      if (k == 0)
        return true;
      if (k <= 2)
        return false;
      auto normal_of = [&](const unsigned int f) {
        std::vector<Point<dim>> xf;
        for (const auto m : face_nodes[f])
          xf.push_back(x[m]);
        return face_normal(xf);
      };
      Tensor<1, dim> node_normal;
      for (const auto f : own[node])
        node_normal += normal_of(f);
      return !excluded(node, face, node_normal, normal_of(face));
    }

#define INSTANTIATE(dim)                                                                           \
  template Tensor<1, dim> face_normal(const std::vector<Point<dim>> &);                            \
  template bool SelfContactNeighbourhood::may_touch(unsigned int, unsigned int,                   \
                                                    const std::vector<Point<dim>> &) const;
    ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
  } // namespace contact
} // namespace anvil
