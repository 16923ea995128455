// ContactProblem: contact pairs from the scene, the gathered surfaces, the
// search and the assembly of the node-to-segment / node-to-tool elements into
// the mechanics (seed §3.1, eq. 27–29). The heat exchange is in contact_heat.cc.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/rtree.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/contact/free_end.h>
#include <anvil/core/gather.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>

namespace anvil
{
  using namespace dealii;


  template <int dim>
  void ContactProblem<dim>::setup(const DoFHandler<dim> &dof_handler, const bool axi)
  {
    axisymmetric     = axi;
    mpi_communicator = dof_handler.get_communicator();
    n_global_dofs    = dof_handler.n_dofs();
    number_surfaces(gather_surface_faces(dof_handler), dof_handler.locally_owned_dofs());
    share_out_nodes();
    build_pair_sides();
    committed.clear();
    slots.clear();
    step_sides.clear();
    allowed.clear();
    step_allowed.clear();
    x_old.clear();
    x_before.clear();
    search_cache.reset();
    grew = true;
  }


  template <int dim>
  std::vector<std::vector<double>>
  ContactProblem<dim>::gather_surface_faces(const DoFHandler<dim> &dof_handler) const
  {
    std::set<types::boundary_id> wanted;
    for (const auto &p : pairs)
      {
        wanted.insert(p.slaves.begin(), p.slaves.end());
        wanted.insert(p.masters.begin(), p.masters.end());
      }
    // Local faces: boundary, material, then per vertex its dim dofs and
    // reference position, the vertices ordered so that the normal points out.
    const unsigned int  n_vertices = GeometryInfo<dim>::vertices_per_face;
    std::vector<double> local;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() && wanted.count(cell->face(f)->boundary_id()))
            {
              std::vector<unsigned int> order(n_vertices);
              std::iota(order.begin(), order.end(), 0);
              if (!contact::face_order_gives_outward_normal<dim>(f))
                {
                  if (dim == 2)
                    std::swap(order[0], order[1]);
                  else
                    std::swap(order[1], order[2]);
                }
              local.push_back(cell->face(f)->boundary_id());
              local.push_back(cell->material_id());
              for (const unsigned int k : order)
                {
                  const unsigned int v = GeometryInfo<dim>::face_to_cell_vertices(f, k);
                  for (unsigned int c = 0; c < dim; ++c)
                    local.push_back(cell->vertex_dof_index(v, c));
                  for (unsigned int c = 0; c < dim; ++c)
                    local.push_back(cell->vertex(v)[c]);
                }
            }
    return gather_doubles(mpi_communicator, local);
  }


  template <int dim>
  void ContactProblem<dim>::number_surfaces(const std::vector<std::vector<double>> &all,
                                            const IndexSet                         &owned)
  {
    const unsigned int n_vertices = GeometryInfo<dim>::vertices_per_face;
    // Nodes by their x dof, then numbered in the order of their reference
    // coordinates (independent of the partition). Every process numbers the
    // whole gathered surface: kept in flat arrays sorted once (a map of the
    // nodes looked up twice per comparison cost 217 M instructions per
    // process on the 48 k-DoF-per-body strip, at np 1 and at np 2 alike).
    struct RawNode
    {
      types::global_dof_index                  key = 0; // the x dof
      std::array<types::global_dof_index, dim> dofs;
      Point<dim>                               X;
      unsigned int                             body = 0;
    };
    std::vector<RawNode>                                          raw;
    std::vector<std::pair<types::boundary_id, std::vector<types::global_dof_index>>> raw_faces;
    const unsigned int stride = 2 + n_vertices * 2 * dim;
    for (const auto &part : all)
      for (std::size_t i = 0; i + stride <= part.size(); i += stride)
        {
          std::vector<types::global_dof_index> keys;
          for (unsigned int k = 0; k < n_vertices; ++k)
            {
              RawNode n;
              n.body = static_cast<unsigned int>(part[i + 1]);
              for (unsigned int c = 0; c < dim; ++c)
                {
                  n.dofs[c] = static_cast<types::global_dof_index>(part[i + 2 + k * 2 * dim + c]);
                  n.X[c]    = part[i + 2 + k * 2 * dim + dim + c];
                }
              n.key = n.dofs[0];
              raw.push_back(n);
              keys.push_back(n.key);
            }
          raw_faces.emplace_back(static_cast<types::boundary_id>(part[i]), keys);
        }
    // One entry per node, the last one met (as a map's assignment kept it).
    std::stable_sort(raw.begin(), raw.end(), [](const RawNode &a, const RawNode &b) { return a.key < b.key; });
    {
      std::size_t kept = 0;
      for (std::size_t i = 0; i < raw.size(); ++i)
        if (i + 1 == raw.size() || raw[i + 1].key != raw[i].key)
          raw[kept++] = raw[i];
      raw.resize(kept);
    }
    std::sort(raw.begin(), raw.end(), [](const RawNode &a, const RawNode &b) {
      for (unsigned int c = 0; c < dim; ++c)
        if (a.X[c] != b.X[c])
          return a.X[c] < b.X[c];
      if (a.body != b.body) // touching bodies: coincident vertices
        return a.body < b.body;
      return a.key < b.key;
    });
    // (x dof, node number), by x dof.
    std::vector<std::pair<types::global_dof_index, unsigned int>> number(raw.size());
    node_reference.clear();
    node_dofs.clear();
    node_owned.clear();
    node_mine.clear();
    node_body.clear();
    node_reference.reserve(raw.size());
    node_dofs.reserve(raw.size());
    node_body.reserve(raw.size());
    for (const auto &n : raw)
      {
        number[node_reference.size()] = {n.key, static_cast<unsigned int>(node_reference.size())};
        node_body.push_back(n.body);
        node_reference.push_back(n.X);
        node_dofs.push_back(n.dofs);
        node_owned.push_back(owned.is_element(n.key));
      }
    std::sort(number.begin(), number.end());
    const auto number_of = [&number](const types::global_dof_index key) {
      return std::lower_bound(number.begin(), number.end(), std::make_pair(key, 0u))->second;
    };
    faces.clear();
    surfaces.clear();
    largest_face = 0;
    double shortest = std::numeric_limits<double>::max();
    faces.reserve(raw_faces.size());
    {
      std::map<types::boundary_id, std::size_t> count; // each surface's arrays at their size
      for (const auto &[b, keys] : raw_faces)
        ++count[b];
      for (const auto &[b, n] : count)
        {
          surfaces[b].faces.reserve(n);
          surfaces[b].nodes.reserve(n * n_vertices);
        }
    }
    for (const auto &[b, keys] : raw_faces)
      {
        Face face;
        face.boundary = b;
        face.nodes.reserve(keys.size());
        for (const auto k : keys)
          face.nodes.push_back(number_of(k));
        surfaces[b].faces.push_back(faces.size());
        for (const auto n : face.nodes)
          surfaces[b].nodes.push_back(n);
        for (unsigned int a = 0; a < face.nodes.size(); ++a)
          for (unsigned int c = a + 1; c < face.nodes.size(); ++c)
            {
              const double d = node_reference[face.nodes[a]].distance(node_reference[face.nodes[c]]);
              largest_face   = std::max(largest_face, d);
              shortest       = std::min(shortest, d);
            }
        faces.push_back(face);
      }
    node_faces.assign(node_reference.size(), {});
    for (unsigned int f = 0; f < faces.size(); ++f)
      for (const auto n : faces[f].nodes)
        node_faces[n].push_back(f);
    for (auto &[b, s] : surfaces)
      {
        std::sort(s.nodes.begin(), s.nodes.end());
        s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
      }
    if (penetration_limit == 0)
      penetration_limit = faces.empty() ? std::numeric_limits<double>::max() : 0.5 * shortest;
  }


  template <int dim>
  void ContactProblem<dim>::build_pair_sides()
  {
    // Each pair's two sides: the union of its boundaries' faces and nodes.
    pair_sides.assign(pairs.size(), {});
    neighbourhood.assign(pairs.size(), {});
    for (unsigned int p = 0; p < pairs.size(); ++p)
      for (unsigned int k = 0; k < 2; ++k)
        {
          Surface &side = pair_sides[p][k];
          for (const auto b : k == 0 ? pairs[p].slaves : pairs[p].masters)
            {
              side.boundaries.insert(b);
              side.faces.insert(side.faces.end(), surfaces[b].faces.begin(), surfaces[b].faces.end());
              side.nodes.insert(side.nodes.end(), surfaces[b].nodes.begin(), surfaces[b].nodes.end());
            }
          std::sort(side.faces.begin(), side.faces.end());
          std::sort(side.nodes.begin(), side.nodes.end());
          side.nodes.erase(std::unique(side.nodes.begin(), side.nodes.end()), side.nodes.end());
        }
    for (unsigned int p = 0; p < pairs.size(); ++p)
      if (pairs[p].self)
        {
          // Faces indexed as in `faces`; those of other boundaries left empty.
          std::vector<std::vector<unsigned int>> side_faces(faces.size());
          for (const auto f : pair_sides[p][0].faces)
            side_faces[f] = faces[f].nodes;
          neighbourhood[p].build(side_faces, node_reference.size());
        }
  }

  template <int dim>
  IndexSet ContactProblem<dim>::surface_dofs() const
  {
    std::vector<types::global_dof_index> dofs;
    for (const auto &d : node_dofs)
      dofs.insert(dofs.end(), d.begin(), d.end());
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    IndexSet set(n_global_dofs);
    set.add_indices(dofs.begin(), dofs.end());
    set.compress();
    return set;
  }

  template <int dim>
  void ContactProblem<dim>::set_constrained(
    const std::function<bool(types::global_dof_index)> &owned_and_constrained)
  {
    std::vector<double> flags(node_dofs.size() * dim, 0.);
    for (unsigned int n = 0; n < node_dofs.size(); ++n)
      for (unsigned int c = 0; c < dim; ++c)
        if (owned_and_constrained(node_dofs[n][c]))
          flags[n * dim + c] = 1;
    Utilities::MPI::sum(flags, mpi_communicator, flags);
    constrained.clear();
    for (unsigned int n = 0; n < node_dofs.size(); ++n)
      for (unsigned int c = 0; c < dim; ++c)
        if (flags[n * dim + c] > 0)
          constrained.insert(node_dofs[n][c]);
  }

  template <int dim>
  bool ContactProblem<dim>::may_touch(const unsigned int p, const unsigned int node,
                                      const unsigned int face, const std::vector<Point<dim>> &x) const
  {
    // A node never touches a face it is a vertex of (a corner shared by the
    // Slave and the Master boundaries of one body).
    const auto &nodes = faces[face].nodes;
    if (std::find(nodes.begin(), nodes.end(), node) != nodes.end())
      return false;
    // Self-contact: not the node's own surface next to it (self_contact.h).
    return !pairs[p].self || neighbourhood[p].may_touch(node, face, x);
  }

  template <int dim>
  std::pair<int, unsigned int> ContactProblem<dim>::concave_corner(
    const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end) const
  {
    // Two faces the node is behind and beyond, ending at one vertex: the node
    // is below a concave corner, where no face's projection reaches it.
    for (unsigned int i = 0; i < beyond_end.size(); ++i)
      for (unsigned int j = i + 1; j < beyond_end.size(); ++j)
        if (faces[beyond_end[i].first].nodes[beyond_end[i].second] ==
            faces[beyond_end[j].first].nodes[beyond_end[j].second])
          return {int(beyond_end[i].first), beyond_end[i].second};
    return {-1, 0};
  }

  template <int dim>
  void ContactProblem<dim>::face_positions(const unsigned int f, const std::vector<Point<dim>> &x,
                                           std::vector<Point<dim>> &xm,
                                           std::vector<Point<dim>> &xm_old) const
  {
    for (const auto m : faces[f].nodes)
      {
        xm.push_back(x[m]);
        xm_old.push_back(x_old[m]);
      }
  }

  template <int dim>
  void ContactProblem<dim>::face_positions(const unsigned int f, const std::vector<Point<dim>> &x,
                                           std::array<Point<dim>, 4> &xm,
                                           std::array<Point<dim>, 4> &xm_old) const
  {
    const auto &nodes = faces[f].nodes;
    for (unsigned int a = 0; a < nodes.size(); ++a)
      {
        xm[a]     = x[nodes[a]];
        xm_old[a] = x_old[nodes[a]];
      }
  }

  template <int dim>
  int ContactProblem<dim>::closest_face(
    const unsigned int p, const unsigned int n, const unsigned int *candidates,
    const unsigned int n_candidates, const std::vector<Point<dim>> &x,
    const contact::NodeState<dim> &state, const contact::FrictionLaw &law,
    contact::ContactResult<dim> &result,
    std::vector<std::pair<unsigned int, unsigned int>> &beyond_end) const
  {
    const Pair &pair      = pairs[p];
    int         best_face = -1;
    for (unsigned int k = 0; k < n_candidates; ++k)
      {
        const unsigned int f = candidates[k];
        if (!may_touch(p, n, f, x))
          continue;
        std::array<Point<dim>, 4> xm, xm_old;
        face_positions(f, x, xm, xm_old);
        auto &r = probe; // evaluated in place, swapped into result when closer
        contact::node_to_segment(r, x[n], x_old[n], xm.data(), xm_old.data(), state, law, false);
        if (!r.projection_inside)
          {
            // Behind the face's line and beyond its end: a side
            // of a concave corner, if another face shares the vertex.
            // 3D: behind the facet's surface and outside it, maybe beyond a
            // free edge (free_edge_face).
            if (r.gap < 0 && !(pair.self && -r.gap > 1.5 * penetration_limit))
              beyond_end.emplace_back(f, r.xi[0] < 0 ? 0u : 1u);
            continue;
          }
        // Self-contact: a node deeper behind a face of its own
        // surface than 1.5 penetration limits is seeing it through
        // the wall (the other skin of a thin wall), not touching it;
        // a step reaching the limit is cut back before this matters.
        if (pair.self && -r.gap > 1.5 * penetration_limit)
          continue;
        if (best_face < 0 || std::abs(r.gap) < std::abs(result.gap))
          {
            std::swap(result, r);
            best_face = f;
          }
      }
    return best_face;
  }

  template <int dim>
  int ContactProblem<dim>::free_end_face(
    const unsigned int p, const unsigned int pass, const unsigned int n,
    const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end,
    const std::vector<Point<dim>> &x, const contact::NodeState<dim> &state,
    const contact::FrictionLaw &law, const bool with_matrix, int best_face,
    contact::ContactResult<dim> &result) const
  {
    // Beyond a free end of the master surface: its end segment extended,
    // tapered (free_end_contact; 3D: free_edge_face).
    int found = -1;
    if constexpr (dim == 3)
      found = free_edge_face(p, pass, n, beyond_end, x, state, law, with_matrix, best_face, result);
    else
      for (const auto &[f, end] : beyond_end)
        {
          const unsigned int v    = faces[f].nodes[end];
          bool               free = true;
          for (const auto g : node_faces[v])
            free = free && (g == f || !master_side(p, pass).has(faces[g]));
          if (!free)
            continue;
          std::vector<Point<dim>> xm, xm_old;
          face_positions(f, x, xm, xm_old);
          auto r = contact::free_end_contact(x[n], x_old[n], xm, xm_old, end, state, law,
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
