// ContactProblem::candidate_faces: the bounding-box search of the master faces
// near each slave node (issue 15: "the R-tree rebuilt only when the geometry
// moved enough"). Its own file because the kept tree and its validity test are
// one concern apart from the contact evaluation in contact_problem.cc.
#include <deal.II/base/bounding_box.h>
#include <deal.II/numerics/rtree.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  struct ContactProblem<dim>::SearchCache
  {
    struct Side
    {
      std::vector<Point<dim>>                               x_ref; // the nodes the tree was built at
      RTree<std::pair<BoundingBox<dim>, unsigned int>>      tree;
      std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits; // a query's, kept for its storage
    };
    std::map<std::pair<const Surface *, double>, Side> sides; // by master side and margin
  };

  namespace
  {
    /// Whether the box of the face's @p nodes at @p x, enlarged by @p margin,
    /// holds @p point, computed as BoundingBox(corners).extend(margin) is.
    template <int dim>
    bool box_holds(const std::vector<unsigned int> &nodes, const std::vector<Point<dim>> &x,
                   const double margin, const Point<dim> &point)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          double lo = std::numeric_limits<double>::max(), hi = -lo;
          for (const auto n : nodes)
            {
              lo = std::min(lo, x[n][d]);
              hi = std::max(hi, x[n][d]);
            }
          lo -= margin;
          hi += margin;
          if (!(lo <= point[d] && point[d] <= hi))
            return false;
        }
      return true;
    }
  } // namespace

  template <int dim>
  bool ContactProblem<dim>::face_box_holds(const unsigned int f, const std::vector<Point<dim>> &x,
                                           const double margin, const Point<dim> &point) const
  {
    return box_holds<dim>(faces[f].nodes, x, margin, point);
  }

  template <int dim>
  void ContactProblem<dim>::candidate_faces(
    const Surface &master, const std::vector<Point<dim>> &x, const double margin,
    const std::vector<unsigned int> &slaves, CandidateLists &candidates) const
  {
    namespace bgi = boost::geometry::index;
    // The boxes are built with a slack beyond the margin and kept until a
    // master node has moved more than half the slack in a coordinate (half:
    // clear of round-off in the comparison of boxes): a box of the
    // current faces, enlarged by the margin, is then inside the kept one, so
    // the kept tree's hits include every face the current boxes would give,
    // and the test below keeps exactly those (the same comparisons as the
    // tree's own: bit for bit the candidates of a tree built anew).
    const double slack = 0.5 * largest_face;
    if (!search_cache)
      search_cache = std::make_shared<SearchCache>();
    auto &side = search_cache->sides[{&master, margin}];
    bool  valid = side.x_ref.size() == x.size();
    for (unsigned int i = 0; valid && i < master.faces.size(); ++i)
      for (const auto n : faces[master.faces[i]].nodes)
        for (unsigned int d = 0; d < dim; ++d)
          if (!(std::abs(x[n][d] - side.x_ref[n][d]) <= 0.5 * slack))
            valid = false;
    if (!valid)
      {
        std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
        boxes.reserve(master.faces.size());
        for (const auto f : master.faces)
          {
            std::vector<Point<dim>> corners;
            for (const auto n : faces[f].nodes)
              corners.push_back(x[n]);
            BoundingBox<dim> box(corners);
            box.extend(margin + slack);
            boxes.emplace_back(box, f);
          }
        side.tree  = pack_rtree(boxes);
        side.x_ref = x;
      }
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> &hits = side.hits;
    candidates.start.assign(1, 0);
    candidates.faces.clear();
    for (const auto s : slaves)
      {
        hits.clear();
        side.tree.query(bgi::intersects(x[s]), std::back_inserter(hits));
        for (const auto &h : hits)
          if (face_box_holds(h.second, x, margin, x[s]))
            candidates.faces.push_back(h.second);
        std::sort(candidates.faces.begin() + candidates.start.back(), candidates.faces.end());
        candidates.start.push_back(candidates.faces.size());
      }
  }

  template <int dim>
  void ContactProblem<dim>::filter_candidates(const CandidateLists &superset,
                                              const std::vector<Point<dim>> &x, const double margin,
                                              const std::vector<unsigned int> &slaves,
                                              CandidateLists &candidates) const
  {
    candidates.start.assign(1, 0);
    candidates.faces.clear();
    for (unsigned int k = 0; k < slaves.size(); ++k)
      {
        // Sorted already: a sorted list filtered.
        for (unsigned int i = superset.start[k]; i < superset.start[k + 1]; ++i)
          if (face_box_holds(superset.faces[i], x, margin, x[slaves[k]]))
            candidates.faces.push_back(superset.faces[i]);
        candidates.start.push_back(candidates.faces.size());
      }
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
