// Self-contact at the level of the library (issue 12): which faces of its own
// surface a slave node may touch (contact::SelfContactNeighbourhood), and the
// node-to-segment element between a node and a face of its own boundary.
// Independent answers:
//  1. a hairpin (the inner skin of a strip bent into a U, as a polyline run
//     with the body on its right): a node may touch the other leg straight
//     across the gap, never its own faces and their neighbours, nor the faces
//     of its own leg a few elements on (same facing); at a tight tip (gap below
//     an element) the faces across the U, 3-4 faces away along the skin, are
//     allowed (opposite facing);
//  2. a node pushed by d into the other leg: g_N = -d, n the other leg's outward
//     normal, t_N = c_N d, the force on the node +t_N n; sliding: |t_T| = mu t_N;
//     the AD tangent against central differences of the residual (2D, and a
//     3D plate folded onto itself);
//  3. a flat and a gently curved surface (2D line and arc, 3D plane and
//     cylinder patch) compressed by 30 % along itself: no node is in contact
//     with any face it may touch (brute force over all pairs, no search);
//  4. the outward normals of faces (face_normal) against closed forms.
// Prints the numbers; returns nonzero on failure.
#include "check.h"

#include <anvil/contact/contact_element.h>
#include <anvil/contact/self_contact.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

using namespace dealii;
using namespace anvil::contact;

namespace
{
  anvil::testing::Checks check;

  /// A polyline surface: nodes and faces (i, i+1), the body on its right.
  struct Polyline
  {
    std::vector<Point<2>>                  x;
    std::vector<std::vector<unsigned int>> faces;
    void close_faces()
    {
      faces.clear();
      for (unsigned int i = 0; i + 1 < x.size(); ++i)
        faces.push_back({i, i + 1});
    }
  };

  /// The inner skin of a U: upper leg y = g from x = L to 0, a half circle of
  /// diameter g on the left, lower leg y = 0 from 0 to L; element size h.
  Polyline hairpin(const double L, const double g, const double h)
  {
    Polyline     p;
    const auto   n_leg = static_cast<unsigned int>(std::round(L / h));
    const auto   n_arc = std::max(2u, static_cast<unsigned int>(std::round(M_PI * g / 2 / h)));
    for (unsigned int i = 0; i < n_leg; ++i)
      p.x.emplace_back(L - i * h, g);
    for (unsigned int i = 0; i < n_arc; ++i)
      {
        const double phi = M_PI / 2 + M_PI * i / n_arc;
        p.x.emplace_back(g / 2 * std::cos(phi), g / 2 + g / 2 * std::sin(phi));
      }
    for (unsigned int i = 0; i <= n_leg; ++i)
      p.x.emplace_back(i * h, 0);
    p.close_faces();
    return p;
  }

  template <int dim>
  std::vector<Point<dim>> face_points(const std::vector<Point<dim>> &x, const std::vector<unsigned int> &f)
  {
    std::vector<Point<dim>> out;
    for (const auto n : f)
      out.push_back(x[n]);
    return out;
  }

  /// Largest |AD tangent - central differences| relative to the largest entry.
  template <int dim>
  double tangent_error(Point<dim> slave, const Point<dim> &slave_old, std::vector<Point<dim>> master,
                       const std::vector<Point<dim>> &master_old, const NodeState<dim> &state,
                       const FrictionLaw &law)
  {
    const auto   exact = node_to_segment(slave, slave_old, master, master_old, state, law, true);
    const double eps   = 1e-7;
    double       error = 0, scale = 0;
    for (unsigned int j = 0; j < exact.tangent.n(); ++j)
      {
        auto coordinate = [&](int) -> double & {
          return j < dim ? slave[j] : master[j / dim - 1][j % dim];
        };
        coordinate(0) += eps;
        const auto plus = node_to_segment(slave, slave_old, master, master_old, state, law, false);
        coordinate(0) -= 2 * eps;
        const auto minus = node_to_segment(slave, slave_old, master, master_old, state, law, false);
        coordinate(0) += eps;
        for (unsigned int i = 0; i < exact.tangent.m(); ++i)
          {
            const double fd = (plus.residual[i] - minus.residual[i]) / (2 * eps);
            error           = std::max(error, std::abs(fd - exact.tangent(i, j)));
            scale           = std::max(scale, std::abs(exact.tangent(i, j)));
          }
      }
    return error / scale;
  }

  /// Brute force: the (node, face) pairs allowed by the neighbourhood that are in contact.
  template <int dim>
  unsigned int self_contacts(const std::vector<Point<dim>> &x, const std::vector<std::vector<unsigned int>> &faces,
                             unsigned int &allowed)
  {
    SelfContactNeighbourhood near;
    near.build(faces, x.size());
    FrictionLaw law;
    law.penalty_normal = 1e5;
    unsigned int found = 0;
    allowed            = 0;
    for (unsigned int n = 0; n < x.size(); ++n)
      for (unsigned int f = 0; f < faces.size(); ++f)
        if (near.may_touch(n, f, x))
          {
            ++allowed;
            const auto m = face_points(x, faces[f]);
            if (node_to_segment(x[n], x[n], m, m, NodeState<dim>(), law, false).in_contact)
              ++found;
          }
    return found;
  }

  void hairpin_neighbourhood()
  {
    std::cout << "1. hairpin: which faces of its own skin a node may touch" << std::endl;
    const double h = 0.5, L = 8;
    Polyline     p = hairpin(L, 2.0, h);
    SelfContactNeighbourhood near;
    near.build(p.faces, p.x.size());
    // The lower-leg node at x = 3 and the upper-leg face above it.
    unsigned int node = 0, above = 0;
    for (unsigned int i = 0; i < p.x.size(); ++i)
      if (std::abs(p.x[i][0] - 3) < 1e-12 && std::abs(p.x[i][1]) < 1e-12)
        node = i;
    for (unsigned int f = 0; f < p.faces.size(); ++f)
      if (std::abs(p.x[p.faces[f][0]][1] - 2) < 1e-12 && std::abs(p.x[p.faces[f][0]][0] - 3.5) < 1e-12)
        above = f;
    const unsigned int own = node - 1; // face (node-1, node)
    std::cout << "  node " << node << " at (3, 0); face " << above << " above it: ring "
              << near.ring(node, above) << "; own face " << own << ": ring " << near.ring(node, own)
              << std::endl;
    check(near.may_touch(node, above, p.x), "the other leg straight across the gap may be touched");
    check(!near.may_touch(node, own, p.x) && !near.may_touch(node, own + 1, p.x), "its own faces may not");
    check(near.ring(node, own + 2) == 2 && !near.may_touch(node, own + 2, p.x),
          "their neighbours (ring 2) may not");
    check(near.ring(node, own + 3) == 3 && !near.may_touch(node, own + 3, p.x) &&
            near.ring(node, own + 4) == 4 && !near.may_touch(node, own + 4, p.x),
          "its own leg 3 and 4 faces on (same facing) may not");
    check(near.ring(node, own + 5) == 0, "beyond 4 rings nothing is excluded");

    // A tight tip: gap 0.4 mm with 0.5 mm elements, the half circle of 2 faces.
    Polyline tight = hairpin(L, 0.4, h);
    near.build(tight.faces, tight.x.size());
    unsigned int tip_lower = 0; // the lower leg's node at x = 0.5
    for (unsigned int i = 0; i < tight.x.size(); ++i)
      if (std::abs(tight.x[i][0] - 0.5) < 1e-12 && std::abs(tight.x[i][1]) < 1e-12)
        tip_lower = i;
    unsigned int       allowed_across = 0, excluded_along = 0;
    for (unsigned int f = 0; f < tight.faces.size(); ++f)
      {
        const unsigned int k = near.ring(tip_lower, f);
        const bool upper = tight.x[tight.faces[f][0]][1] > 0.39 && tight.x[tight.faces[f][1]][1] > 0.39;
        if (k >= 3 && upper && near.may_touch(tip_lower, f, tight.x))
          ++allowed_across;
        if (k >= 3 && !upper && !near.may_touch(tip_lower, f, tight.x))
          ++excluded_along;
      }
    std::cout << "  tight tip: node at (" << tight.x[tip_lower] << "): " << allowed_across
              << " upper-leg faces within 4 rings allowed, " << excluded_along
              << " lower-leg faces within 4 rings excluded" << std::endl;
    check(allowed_across >= 1, "tight fold: faces across the tip within a few elements are allowed");
    check(excluded_along >= 1, "tight fold: its own leg within a few elements is excluded");
  }

  void element_on_own_boundary()
  {
    std::cout << "2. a node pushed into a face of its own boundary" << std::endl;
    const double h = 0.5, g = 2.0, d = 0.01;
    Polyline     p = hairpin(5, g, h);
    // Face from (3.5, g) to (3, g): the upper leg, outward normal -y.
    const std::vector<Point<2>> master = {Point<2>(3.5, g), Point<2>(3.0, g)};
    const Point<2>              slave_old(3.2, g - 0.001), slave(3.2, g + d);
    FrictionLaw                 law;
    law.penalty_normal  = 1e5;
    law.penalty_tangent = 1e4;
    law.mu_static = law.mu_dynamic = 0.08;
    const auto r = node_to_segment(slave, slave_old, master, master, NodeState<2>(), law, true);
    std::cout << "  g_N = " << r.gap << " (expected " << -d << "), n = " << r.normal
              << " (expected 0 -1), t_N = " << r.normal_force << " (expected " << law.penalty_normal * d
              << "), force on the node " << -r.residual[0] << " " << -r.residual[1] << std::endl;
    check(std::abs(r.gap + d) < 1e-12 && std::abs(r.normal[1] + 1) < 1e-12, "gap and normal");
    check(std::abs(r.normal_force - law.penalty_normal * d) < 1e-9 * law.penalty_normal * d, "t_N = c_N d");
    check(std::abs(-r.residual[1] + r.normal_force) < 1e-9 && std::abs(r.residual[0]) < 1e-9,
          "the force on the node is +t_N n (pushed back out), no tangential motion no friction");
    double e = tangent_error(slave, slave_old, master, master, NodeState<2>(), law);
    std::cout << "  tangent vs central differences (stick): " << e << std::endl;
    check(e < 1e-6, "2D tangent, normal approach");
    // Sliding along the face by 0.05 mm in the step: |t_T| = mu t_N.
    const Point<2> slid(3.25, g + d), slid_old(3.2, g + d);
    const auto     s = node_to_segment(slid, slid_old, master, master, NodeState<2>(), law, true);
    std::cout << "  sliding: |t_T| = " << s.tangential_force.norm() << " (mu t_N = " << 0.08 * s.normal_force
              << ")" << std::endl;
    check(s.sliding && std::abs(s.tangential_force.norm() - 0.08 * s.normal_force) < 1e-9,
          "sliding on its own boundary: |t_T| = mu t_N");
    e = tangent_error(slid, slid_old, master, master, NodeState<2>(), law);
    std::cout << "  tangent vs central differences (slide): " << e << std::endl;
    check(e < 1e-6, "2D tangent, sliding");

    // 3D: a plate folded onto itself; its top skin's upper sheet faces down
    // (facet nodes lexicographic, x_xi x x_eta = -z), the lower sheet's node
    // under it pushed up by d.
    const std::vector<Point<3>> facet = {Point<3>(0, 1, g), Point<3>(1, 1, g), Point<3>(0, 0, g),
                                         Point<3>(1, 0, g)};
    check(std::abs(face_normal(facet)[2] + 1) < 1e-12, "3D folded sheet: the upper facet's normal is -z");
    const Point<3> s3_old(0.3, 0.6, g - 0.001), s3(0.35, 0.6, g + d);
    const auto     r3 = node_to_segment(s3, s3_old, facet, facet, NodeState<3>(), law, true);
    std::cout << "  3D: g_N = " << r3.gap << ", t_N = " << r3.normal_force << ", |t_T| = "
              << r3.tangential_force.norm() << std::endl;
    check(std::abs(r3.gap + d) < 1e-12 && std::abs(r3.normal_force - law.penalty_normal * d) < 1e-6,
          "3D: g_N = -d, t_N = c_N d");
    e = tangent_error(s3, s3_old, facet, facet, NodeState<3>(), law);
    std::cout << "  3D tangent vs central differences: " << e << std::endl;
    check(e < 1e-6, "3D tangent on a folded plate");
  }

  void no_contact_with_itself()
  {
    std::cout << "3. flat and gently curved surfaces compressed by 30 %: no self-contact" << std::endl;
    unsigned int allowed = 0;
    // 2D: 40 faces of 0.5 mm compressed to 0.35 mm, flat and on an arc of 60 degrees.
    for (const double angle : {0., M_PI / 3})
      {
        std::vector<Point<2>> x;
        for (unsigned int i = 0; i <= 40; ++i)
          {
            const double s = 0.7 * 0.5 * i;
            if (angle == 0)
              x.emplace_back(s, 0);
            else
              {
                const double R = 0.7 * 20 / angle, phi = s / R; // convex (body below)
                x.emplace_back(R * std::sin(phi), R * std::cos(phi) - R);
              }
          }
        Polyline p;
        p.x = x;
        p.close_faces();
        for (const bool reversed : {false, true}) // convex, then concave
          {
            auto faces = p.faces;
            if (reversed)
              for (auto &f : faces)
                std::swap(f[0], f[1]);
            const unsigned int found = self_contacts(p.x, faces, allowed);
            std::cout << "  2D " << (angle == 0 ? (reversed ? "flat, reversed" : "flat") : (reversed ? "concave" : "convex")) << ": "
                      << found << " contacts among " << allowed << " allowed (node, face) pairs" << std::endl;
            check(found == 0 && allowed > 0, "2D: no self-contact");
          }
      }
    // 3D: 12 x 12 facets, flat and on a cylinder of 60 degrees, compressed.
    for (const double angle : {0., M_PI / 3})
      {
        const unsigned int    n = 12;
        std::vector<Point<3>> x;
        for (unsigned int j = 0; j <= n; ++j)
          for (unsigned int i = 0; i <= n; ++i)
            {
              const double s = 0.7 * 0.5 * i, t = 0.7 * 0.5 * j;
              if (angle == 0)
                x.emplace_back(s, t, 0);
              else
                {
                  const double R = 0.7 * 0.5 * n / angle, phi = s / R;
                  x.emplace_back(R * std::sin(phi), t, R * std::cos(phi) - R);
                }
            }
        std::vector<std::vector<unsigned int>> faces;
        for (unsigned int j = 0; j < n; ++j)
          for (unsigned int i = 0; i < n; ++i)
            faces.push_back({j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i,
                             (j + 1) * (n + 1) + i + 1});
        for (const bool reversed : {false, true})
          {
            auto f2 = faces;
            if (reversed)
              for (auto &f : f2)
                std::swap(f[1], f[2]);
            const unsigned int found = self_contacts(x, f2, allowed);
            std::cout << "  3D " << (angle == 0 ? (reversed ? "flat, reversed" : "flat") : (reversed ? "concave" : "convex")) << ": "
                      << found << " contacts among " << allowed << " allowed (node, facet) pairs" << std::endl;
            check(found == 0 && allowed > 0, "3D: no self-contact");
          }
      }
  }

  void normals()
  {
    std::cout << "4. outward normals" << std::endl;
    const auto n2 = face_normal<2>({Point<2>(0, 0), Point<2>(2, 0)});
    check(std::abs(n2[1] - 1) < 1e-15, "2D: the left normal of x0 -> x1");
    const auto n3 = face_normal<3>({Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0, 1, 0), Point<3>(1, 1, 0)});
    check(std::abs(n3[2] - 1) < 1e-15, "3D: x_xi x x_eta of lexicographic vertices");
  }
} // namespace

int main()
{
  hairpin_neighbourhood();
  element_on_own_boundary();
  no_contact_with_itself();
  normals();
  return check.finish();
}
