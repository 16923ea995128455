// ContactProblem: the step's slave nodes and the couplings of the matrix
// pattern (issue 15: "the matrix pattern pruned when couplings disappear"
// without rebuilding it at every step). A pattern that holds only the step's
// candidates must grow whenever a slave slides onto a new master face: the
// two blocks did at 75 of 79 steps, each time a new matrix, a new KLU
// analysis and a pivoting factorisation. When it must grow, the pattern now
// takes the faces the slave nodes reach over the next look_ahead_steps steps
// if they keep moving relative to the master as in the last step, so it
// holds for several steps; it is pruned at that moment too (stale couplings
// dropped), or when stale couplings are most of it. Extra couplings are
// zero entries: no number in the matrix changes (doc/contact.md, "Pattern").
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/numerics/rtree.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>

#include <algorithm>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  bool ContactProblem<dim>::insert_sorted(std::vector<Coupling> &set, const Coupling &c)
  {
    const auto at = std::lower_bound(set.begin(), set.end(), c);
    if (at != set.end() && *at == c)
      return false;
    set.insert(at, c);
    return true;
  }

  template <int dim>
  void ContactProblem<dim>::begin_step(const double t0, const double t1, const Vector &u_old)
  {
    // A new step (not a cut-back's retry of the same start): the last step's
    // start is where the look-ahead takes the surface's motion from.
    if (x_old.size() == node_reference.size() && t0 > t_old)
      {
        x_before.swap(x_old);
        t_before = t_old;
      }
    t_old = t0;
    t_new = t1;
    gather_positions(u_old, x_old);
    slots.clear();
    step_sides.assign(2 * pairs.size(), StepSide());
    step_allowed.clear();
    for (unsigned int p = 0; p < pairs.size(); ++p)
      for (unsigned int pass = 0; pass < pairs[p].passes(); ++pass)
        {
          const Surface &slave = slave_side(p, pass);
          StepSide      &side  = step_sides[2 * p + pass];
          side.begin           = slots.size();
          for (const auto n : slave.nodes)
            if (node_mine[n])
              {
                side.mine.push_back(n);
                Slot slot;
                slot.pair        = p;
                slot.pass        = pass;
                slot.node        = n;
                slot.area        = tributary_area(n, slave, x_old);
                const auto c     = committed.find(slot.key());
                if (c != committed.end())
                  slot.state = c->second;
                slots.push_back(slot);
              }
          side.end = slots.size();
          if (pairs[p].tool >= 0)
            continue;
          // Couplings that may occur in this step: a generous search, whose
          // lists also serve assemble() while the surface moves little.
          candidate_faces(master_side(p, pass), x_old, 1.5 * largest_face, side.mine, side.candidates);
          for (unsigned int k = 0; k < side.mine.size(); ++k)
            for (unsigned int i = side.candidates.start[k]; i < side.candidates.start[k + 1]; ++i)
              {
                const unsigned int n = side.mine[k], f = side.candidates.faces[i];
                if (!pairs[p].self || !neighbourhood[p].always_excluded(n, f))
                  step_allowed.push_back({{p, pass, n, f}}); // in order: (p, pass, n) ascending, f sorted
              }
        }
    // Within a step the pattern only grows (a new coupling found in Newton
    // adds to it); between steps it is taken anew with the look-ahead when a
    // coupling of the step is missing, or when couplings no longer candidates
    // are most of it (e.g. the tube's folds sliding past each other: their
    // zero entries cost fill-in in every factorization).
    const bool covered =
      std::includes(allowed.begin(), allowed.end(), step_allowed.begin(), step_allowed.end());
    if (!covered || allowed.size() > 4 * step_allowed.size() + 64)
      {
        // Grown, the pattern keeps what it had (the couplings of a fold that
        // opened a little come back: no new pattern for them) unless stale
        // couplings are most of it; pruned, it is the look-ahead's alone.
        std::vector<Coupling> fresh = look_ahead_couplings(), merged;
        std::set_union(allowed.begin(), allowed.end(), fresh.begin(), fresh.end(),
                       std::back_inserter(merged));
        const bool stale = merged.size() > 2 * fresh.size() + 64;
        if (stale)
          {
            allowed.swap(fresh);
            grew = true;
          }
        else if (!covered)
          {
            allowed.swap(merged);
            grew = true;
          }
      }
  }

  template <int dim>
  std::vector<typename ContactProblem<dim>::Coupling> ContactProblem<dim>::look_ahead_couplings() const
  {
    namespace bgi = boost::geometry::index;
    std::vector<Coupling> wide = step_allowed;
    if (look_ahead_steps == 0)
      return wide;
    // The last step's motion of each surface node, scaled to this step's length.
    const bool     moved = x_before.size() == x_old.size() && t_old > t_before;
    const double   scale = moved ? (t_new - t_old) / (t_old - t_before) : 0.;
    const auto     drift = [&](const unsigned int n) {
      return moved ? Tensor<1, dim>(scale * (x_old[n] - x_before[n])) : Tensor<1, dim>();
    };
    for (unsigned int p = 0; p < pairs.size(); ++p)
      for (unsigned int pass = 0; pass < pairs[p].passes(); ++pass)
        {
          if (pairs[p].tool >= 0)
            continue;
          const StepSide &side = step_sides[2 * p + pass];
          std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
          for (const auto f : master_side(p, pass).faces)
            {
              std::vector<Point<dim>> corners;
              for (const auto n : faces[f].nodes)
                corners.push_back(x_old[n]);
              boxes.emplace_back(BoundingBox<dim>(corners), f);
            }
          const auto tree = pack_rtree(boxes);
          std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
          if (pairs[p].self && self_margin_faces >= 0)
            {
              self_look_ahead(p, side, tree, drift, wide);
              continue;
            }
          for (unsigned int k = 0; k < side.mine.size(); ++k)
            {
              const unsigned int n = side.mine[k];
              // Relative to the master: less the mean motion of the nodes of
              // the step's candidate faces (the master under the node).
              Tensor<1, dim> relative = drift(n), master;
              unsigned int   count    = 0;
              for (unsigned int i = side.candidates.start[k]; i < side.candidates.start[k + 1]; ++i)
                for (const auto m : faces[side.candidates.faces[i]].nodes)
                  {
                    master += drift(m);
                    ++count;
                  }
              if (count > 0)
                relative -= master / count;
              // The node's path over the look-ahead, enlarged by the step's
              // margin (1.5 faces): without relative motion the step's own
              // candidates, no more (each extra coupling is KLU fill-in).
              const Point<dim> ahead = x_old[n] + look_ahead_steps * relative;
              BoundingBox<dim> path(std::vector<Point<dim>>{x_old[n], ahead});
              path.extend(1.5 * largest_face);
              hits.clear();
              tree.query(bgi::intersects(path), std::back_inserter(hits));
              for (const auto &h : hits)
                if (!pairs[p].self || !neighbourhood[p].always_excluded(n, h.second))
                  wide.push_back({{p, pass, n, h.second}});
            }
        }
    std::sort(wide.begin(), wide.end());
    wide.erase(std::unique(wide.begin(), wide.end()), wide.end());
    return wide;
  }

  template <int dim>
  template <typename Tree, typename Drift>
  void ContactProblem<dim>::self_look_ahead(const unsigned int p, const StepSide &side, const Tree &tree,
                                            const Drift &drift, std::vector<Coupling> &wide) const
  {
    namespace bgi = boost::geometry::index;
    // Self-contact: the faces a node meets are its own surface's, across a
    // fold closing NORMAL to them, and "the master under the node" is its own
    // neighbourhood moving with it. So each (node, face) is tested with its
    // own relative motion: the node's path relative to the face (the mean
    // drift of its nodes) over the look-ahead, against the face's box
    // enlarged by the step's margin plus the normal margin. A straight skin
    // moving as a whole adds nothing beyond its step candidates. Only faces
    // turned against the node (normals more than 60° apart) can close onto
    // it: the skin beyond the rings, compressed along itself (the crush's
    // front), moves towards the node but is no fold. Within the rings
    // (3 … 4) the compressed skin itself comes within the step's margin.
    const double margin = (1.5 + self_margin_faces) * largest_face;
    std::vector<Tensor<1, dim>> face_drift(faces.size()), normal(faces.size());
    double                      fastest = 0; // largest face drift (max norm)
    for (const auto f : master_side(p, 0).faces)
      {
        std::vector<Point<dim>> xf;
        for (const auto m : faces[f].nodes)
          {
            face_drift[f] += drift(m);
            xf.push_back(x_old[m]);
          }
        normal[f] = contact::face_normal(xf);
        face_drift[f] /= faces[f].nodes.size();
        for (unsigned int d = 0; d < dim; ++d)
          fastest = std::max(fastest, std::abs(face_drift[f][d]));
      }
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
    for (const auto n : side.mine)
      {
        Tensor<1, dim> node_normal;
        for (const auto f : neighbourhood[p].own_faces(n))
          node_normal += normal[f];
        node_normal /= std::max(node_normal.norm(), 1e-300);
        // A superset first: the node's own path, enlarged by what any face
        // moves over the look-ahead.
        BoundingBox<dim> own(std::vector<Point<dim>>{x_old[n], x_old[n] + look_ahead_steps * drift(n)});
        own.extend(margin + look_ahead_steps * fastest);
        hits.clear();
        tree.query(bgi::intersects(own), std::back_inserter(hits));
        for (const auto &[face_box, f] : hits)
          {
            const unsigned int ring = neighbourhood[p].ring(n, f);
            if (ring == 1 || ring == 2)
              continue;
            // Beyond the rings, a fold's partner: turned against the node,
            // in front of it and the node in front of the face (the skin
            // across the wall's thickness is behind the node).
            Point<dim> centre;
            for (const auto m : faces[f].nodes)
              centre += x_old[m] / double(faces[f].nodes.size());
            const Tensor<1, dim> to_face = centre - x_old[n];
            if (ring == 0 && (node_normal * normal[f] > 0.9 || to_face * node_normal < -0.5 * largest_face ||
                              to_face * normal[f] > 0.5 * largest_face))
              continue;
            const Tensor<1, dim> relative = look_ahead_steps * (drift(n) - face_drift[f]);
            BoundingBox<dim>     path(std::vector<Point<dim>>{x_old[n], x_old[n] + relative});
            path.extend(margin);
            if (path.get_neighbor_type(face_box) != NeighborType::not_neighbors)
              wide.push_back({{p, 0, n, f}});
          }
      }
  }

  template <int dim>
  bool ContactProblem<dim>::couplings_changed() const
  {
    return Utilities::MPI::max(grew ? 1 : 0, mpi_communicator) > 0;
  }

  template <int dim>
  std::vector<std::vector<types::global_dof_index>> ContactProblem<dim>::couplings() const
  {
    ++pattern_rebuild_count;
    std::vector<std::vector<types::global_dof_index>> groups;
    // The rows of the slave nodes this process evaluates (possibly owned by another).
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      if (node_mine[n] && !node_owned[n])
        groups.emplace_back(node_dofs[n].begin(), node_dofs[n].end());
    for (const auto &[p, pass, n, f] : allowed)
      {
        std::vector<types::global_dof_index> dofs(node_dofs[n].begin(), node_dofs[n].end());
        for (const auto m : faces[f].nodes)
          dofs.insert(dofs.end(), node_dofs[m].begin(), node_dofs[m].end());
        groups.push_back(dofs);
      }
    grew = false;
    return groups;
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
