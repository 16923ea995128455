// Parts 8 and 9 of the contact element test (contact_element.cc says what all
// parts check): node to vertex below a concave corner, and the tapered facet
// beyond a free edge.
#include "contact_element_support.h"

namespace contact_test
{
  /**
   * A slave below a concave corner of the master (two segments meeting at
   * the vertex (0, 0) at 120°, their normals pointing up and inward): in the
   * region where it projects into neither face, node_to_vertex() must (a)
   * meet node_to_segment() of each face on the region's edges (gap, normal
   * and forces equal: the Newton stall of the tube, doc/contact.md), (b) give
   * the closed-form gap −|x_s − x_v| and normal (x_v − x_s)/|x_v − x_s|, and
   * (c) have a tangent equal to finite differences, sticking and sliding.
   */
  double test_concave_corner()
  {
    std::cout << "8. Slave below a concave corner (node to vertex)" << std::endl;
    const double      angle = numbers::PI / 6; // each face rises 30° from the vertex
    const Point<2>    v(0, 0), a(-std::cos(angle), std::sin(angle)), b(std::cos(angle), std::sin(angle));
    // Master faces ordered so that the left normal points up (into the valley).
    const std::vector<Point<2>> left = {a, v}, right = {v, b};
    const FrictionLaw           law  = seed_law();
    // On the edge of the region under the right face: straight below the vertex
    // along −n of that face.
    const Tensor<1, 2> n_right({-std::sin(angle), std::cos(angle)});
    const Tensor<1, 2> n_left({std::sin(angle), std::cos(angle)});
    for (const auto &[face, normal, name] :
         {std::make_tuple(right, n_right, "right"), std::make_tuple(left, n_left, "left")})
      {
        const Point<2> slave     = v - 0.05 * normal;
        const Point<2> slave_old = slave + Tensor<1, 2>({0.002, 0.});
        const auto by_face  = node_to_segment(slave, slave_old, face, face, NodeState<2>(), law, false);
        const auto by_vertex = node_to_vertex(slave, slave_old, v, v, NodeState<2>(), law, false);
        std::cout << "  edge of the " << name << " face: xi " << by_face.xi[0] << "  gap " << by_face.gap
                  << " / " << by_vertex.gap << "  t_N " << by_face.normal_force << " / "
                  << by_vertex.normal_force << "  |t_T| " << by_face.tangential_force.norm() << " / "
                  << by_vertex.tangential_force.norm() << std::endl;
        check(by_face.in_contact && by_vertex.in_contact, std::string(name) + ": both in contact");
        check(close(by_face.gap, by_vertex.gap, 1e-12), std::string(name) + ": gap continuous");
        check(close(by_face.normal, by_vertex.normal, 1e-12), std::string(name) + ": normal continuous");
        check(close(by_face.tangential_force, by_vertex.tangential_force, 1e-9),
              std::string(name) + ": friction force continuous");
        check(close(by_face.residual[0], by_vertex.residual[0], 1e-9) &&
                close(by_face.residual[1], by_vertex.residual[1], 1e-9),
              std::string(name) + ": force on the slave continuous");
      }
    // Inside the region: the closed form.
    const Point<2> slave(0.01, -0.04);
    const auto     r = node_to_vertex(slave, slave, v, v, NodeState<2>(), law, false);
    check(close(r.gap, -slave.norm(), 1e-14), "vertex: gap = -|x_s - x_v|");
    check(close(r.normal, Tensor<1, 2>(-slave / slave.norm()), 1e-14), "vertex: normal along x_v - x_s");
    check(!node_to_segment(slave, slave, left, left, NodeState<2>(), law, false).projection_inside &&
            !node_to_segment(slave, slave, right, right, NodeState<2>(), law, false).projection_inside,
          "vertex: the slave projects into neither face");

    const auto evaluator = [](const Point<2> &slave_old, const Point<2> &vertex_old, const NodeState<2> &state,
                              const FrictionLaw &law) -> Evaluator<2> {
      return [=](const std::vector<double> &x, const bool tangent) {
        return node_to_vertex(Point<2>(x[0], x[1]), slave_old, Point<2>(x[2], x[3]), vertex_old, state, law,
                              tangent);
      };
    };
    const std::vector<double> x0 = {0.01, -0.04, 0.001, 0.0005};
    NodeState<2>              sticking;
    double                    worst = tangent_error<2>("vertex, stick", x0,
                                  evaluator(Point<2>(0.0101, -0.04), v, sticking, law), false);
    worst = std::max(worst, tangent_error<2>("vertex, slide", x0,
                                             evaluator(Point<2>(0.03, -0.04), v, sticking, law), true));
    NodeState<2> old;
    old.in_contact       = true;
    old.tangential_force = Tensor<1, 2>({3., 1.});
    worst = std::max(worst, tangent_error<2>("vertex, old force, stick", x0,
                                             evaluator(Point<2>(0.0100, -0.0401), v, old, law), false));
    return worst;
  }

  /// Part 9: the tapered facet beyond a free edge (doc/contact.md, "Free ends").
  double test_free_edge()
  {
    std::cout << "9. Beyond a free facet edge (3D taper)" << std::endl;
    const FrictionLaw law   = seed_law();
    double            worst = 0;
    const double      tol = end_tolerance, taper = default_end_taper;
    for (const bool warped : {false, true})
      for (unsigned int edge = 0; edge < 4; ++edge)
        for (const bool slide : {false, true})
          {
            const auto [master, master_old] = test_facet(warped);
            // 0.02 facet parameters beyond edge 2k + e (inside the taper), 0.6 along it.
            const unsigned int k = edge / 2;
            double             st[2];
            st[k]     = edge % 2 == 0 ? -0.02 : 1.02;
            st[1 - k] = 0.6;
            const Point<3> on_surface = facet_point(master, st[0], st[1]);
            const auto     probe = node_to_segment(on_surface, on_surface, master, master_old, NodeState<3>(), law, false);
            const Point<3> slave = on_surface - (probe.gap + 0.01) * probe.normal;
            const Point<3> slave_old =
              slave - (slide ? Tensor<1, 3>({0.02, -0.01, 0.003}) : Tensor<1, 3>({0.0003, -0.0011, 0.0002}));
            NodeState<3> state;
            state.in_contact       = true;
            state.tangential_force = Tensor<1, 3>({0.5, -0.7, 0.1});
            const Evaluator<3> f   = [=](const std::vector<double> &x, const bool tangent) {
              std::vector<Point<3>> m(4);
              for (unsigned int a = 0; a < 4; ++a)
                m[a] = Point<3>(x[3 + 3 * a], x[4 + 3 * a], x[5 + 3 * a]);
              return free_edge_contact(Point<3>(x[0], x[1], x[2]), slave_old, m, master_old, edge, state, law,
                                       tangent);
            };
            worst = std::max(worst, tangent_error<3>(std::string(warped ? "warped" : "flat") + " facet, edge " +
                                                       std::to_string(edge) + (slide ? " slide" : " stick"),
                                                     flatten(slave, master), f, slide));
          }

    // Continuity at the tolerance, nothing past the taper (flat facet, edge ξ = 1).
    const std::vector<Point<3>> flat = {Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0, 1, 0), Point<3>(1, 1, 0)};
    const auto at = [&](const double xi) { return Point<3>(xi, 0.4, -0.01); };
    const Point<3> inside = at(1 + 0.999 * tol), just_beyond = at(1 + 1.001 * tol);
    const auto by_facet = node_to_segment(inside, inside, flat, flat, NodeState<3>(), law, false);
    const auto by_taper = free_edge_contact(just_beyond, just_beyond, flat, flat, 1, NodeState<3>(), law, false);
    std::cout << "  at the tolerance: t_N " << by_facet.normal_force << " (facet) / " << by_taper.normal_force
              << " (taper)" << std::endl;
    check(by_facet.in_contact && by_taper.in_contact &&
            std::abs(by_facet.normal_force - by_taper.normal_force) < 1e-6 * by_facet.normal_force,
          "free edge: the taper continues the facet's force at the tolerance");
    check(!free_edge_contact(at(1 + tol + 1.01 * taper), at(1 + tol + 1.01 * taper), flat, flat, 1, NodeState<3>(),
                             law, false).in_contact,
          "free edge: no contact past the taper");
    check(!free_edge_contact(at(1 + tol + 0.5 * taper), at(1 + tol + 0.5 * taper), flat, flat, 0, NodeState<3>(),
                             law, false).in_contact,
          "free edge: no contact beyond the opposite edge's side");

    // The extruded facet against the 2D tapered end segment, at w ∈ (0, 1).
    const double              beyond = 1 + tol + 0.3 * taper;
    const std::vector<Point<2>> segment = {Point<2>(0, 0), Point<2>(1, 0)};
    const Point<2>            slave2(beyond, -0.01), slave2_old(beyond - 0.0004, -0.01);
    // The segment extruded along z: ξ along x, η along −z, so that
    // x_ξ × x_η = +y is the segment's left normal.
    const std::vector<Point<3>> extruded = {Point<3>(0, 0, 1), Point<3>(1, 0, 1), Point<3>(0, 0, 0), Point<3>(1, 0, 0)};
    const Point<3>            slave3(beyond, -0.01, 0.5), slave3_old(beyond - 0.0004, -0.01, 0.5);
    const auto r2 = free_end_contact(slave2, slave2_old, segment, segment, 1, NodeState<2>(), law, false);
    const auto r3 = free_edge_contact(slave3, slave3_old, extruded, extruded, 1, NodeState<3>(), law, false);
    std::cout << "  extruded facet vs 2D end segment: t_N " << r3.normal_force << " / " << r2.normal_force
              << ", slave force (" << r3.residual[0] << ", " << r3.residual[1] << ", " << r3.residual[2]
              << ") / (" << r2.residual[0] << ", " << r2.residual[1] << ")" << std::endl;
    check(r2.in_contact && r3.in_contact && r2.normal_force < law.penalty_normal * 0.01 &&
            std::abs(r3.normal_force - r2.normal_force) < 1e-12 * r2.normal_force &&
            std::abs(r3.residual[0] - r2.residual[0]) < 1e-12 * r2.normal_force &&
            std::abs(r3.residual[1] - r2.residual[1]) < 1e-12 * r2.normal_force && std::abs(r3.residual[2]) < 1e-12,
          "free edge: an extruded facet gives the 2D tapered end segment's force");
    return worst;
  }
} // namespace contact_test
