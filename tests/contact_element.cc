// Contact elements (seed §3.1, eq. 27-29) and rigid tools, each checked against
// something independent of the code under test:
//  1. rigid tools: gap and normal of every surface type against hand-computed
//     values (incl. arc ends and polyline vertices), the translation and the
//     temperature expressions, the input validation messages; the derivatives
//     of project<DFad> against central differences of project<double>;
//  2. the AD tangent of every element against central finite differences of
//     its residual: 2D segment, 3D flat and warped facet, every tool type, in
//     stick and in slide; the frictionless tangent is symmetric (it is the
//     Hessian of c_N g²/2);
//  3. friction closed forms on a flat master: stick c_T dg_T below mu_s t_N,
//     then mu_d t_N, the slip and the frictional work of radial return over a
//     sequence of steps, unloading, the force on the slave opposite to its
//     motion, action = reaction;
//  4. the closest point on a warped facet is orthogonal to its tangents;
//  5. objectivity: a rigid rotation of the whole configuration rotates the
//     residual and the tangent and leaves g_N and |t_T| unchanged;
//  6. a master (or a tool) moving with the slave produces no tangential force;
//  7. face_order_gives_outward_normal() against the faces of deal.II cells;
//  8. node to vertex below a concave corner;
//  9. beyond a free facet edge (3D taper, free_edge_contact): the tangent
//     (with the taper's derivative through the closest point) against central
//     differences on a flat and a warped facet, stick and slide, across every
//     edge; the force equals the facet's own at the parameter tolerance and is
//     zero past the taper; on an extruded flat facet the slave's force equals
//     the 2D tapered end segment's (free_end_contact).
// Prints the numbers; returns nonzero on failure.
#include "contact_element_support.h"

using namespace contact_test;

namespace
{
  double test_tangents()
  {
    std::cout << "2. Tangent (Sacado forward AD) against central finite differences of the residual" << std::endl;
    const FrictionLaw law   = seed_law();
    double            worst = 0;
    for (const bool slide : {false, true})
      {
        const std::string branch = slide ? " slide" : " stick";
        // 2D segment, penetration ~0.01 mm: t_N ~ 10 N, stick limit ~ 3 N.
        {
          const std::vector<Point<2>> master     = {Point<2>(0, 0), Point<2>(2, 0.3)};
          const std::vector<Point<2>> master_old = {Point<2>(0.001, -0.002), Point<2>(1.998, 0.301)};
          const Point<2>              slave(0.8, 0.11);
          const Point<2>              slave_old = slave - (slide ? Tensor<1, 2>({0.02, 0.005}) : Tensor<1, 2>({0.0007, 0.0004}));
          NodeState<2>                state;
          state.in_contact       = true;
          state.tangential_force = Tensor<1, 2>({0.8, 0.2});
          worst = std::max(worst, tangent_error<2>("2D segment" + branch, flatten(slave, master),
                                                   segment_evaluator(slave_old, master_old, state, law), slide));
        }
        // 3D facets: flat and warped.
        for (const bool warped : {false, true})
          {
            const auto [master, master_old] = test_facet(warped);
            // The slave 0.01 below the facet near (0.35, 0.6).
            const Point<3> on_facet = facet_point(master, 0.35, 0.6);
            const auto     probe    = node_to_segment(on_facet, on_facet, master, master_old, NodeState<3>(), law, false);
            const Point<3> slave    = on_facet - (probe.gap + 0.01) * probe.normal;
            const Point<3> slave_old =
              slave - (slide ? Tensor<1, 3>({0.02, -0.01, 0.003}) : Tensor<1, 3>({0.0003, -0.0011, 0.0002}));
            NodeState<3> state;
            state.in_contact       = true;
            state.tangential_force = Tensor<1, 3>({0.5, -0.7, 0.1});
            worst = std::max(worst, tangent_error<3>(std::string(warped ? "3D warped facet" : "3D flat facet") + branch,
                                                     flatten(slave, master),
                                                     segment_evaluator(slave_old, master_old, state, law), slide));
          }
        // Tools, moving by u(t); the step is t_old = 0.9 -> t = 1.
        const double t = 1, t_old = 0.9;
        const auto   tool_case = [&](const std::string &name, const auto &tool, const auto &y0, const bool at_given_point) {
          constexpr int dim = std::decay_t<decltype(y0)>::dimension;
          // Place the slave 0.01 inside the tool below y0 (or at y0 itself).
          Point<dim> slave = y0;
          if (!at_given_point)
            {
              double         gap;
              Tensor<1, dim> normal;
              tool.project(Tensor<1, dim>(y0), t, gap, normal);
              slave = y0 - (gap + 0.01) * normal;
            }
          Tensor<1, dim> step;
          for (unsigned int d = 0; d < dim; ++d)
            step[d] = (slide ? 0.02 : 0.0004) * (d == 0 ? 1. : d == 1 ? -0.5 : 0.3);
          const Point<dim> slave_old = slave - (tool.displacement(t) - tool.displacement(t_old)) - step;
          NodeState<dim>   state;
          worst = std::max(worst, tangent_error<dim>(name + branch, flatten(slave, std::vector<Point<dim>>()),
                                                     tool_evaluator(slave_old, tool, t, t_old, state, law), slide));
        };
        const Settings m2 = {{"Motion", "0.1*t, -0.2*t"}};
        const Settings m3 = {{"Motion", "0.1*t, -0.2*t, 0.05*t"}};
        const auto     tool2 = [&](Settings s) { s.insert(s.end(), m2.begin(), m2.end()); return make_tool<2>(s); };
        const auto     tool3 = [&](Settings s) { s.insert(s.end(), m3.begin(), m3.end()); return make_tool<3>(s); };
        tool_case("tool: 2D plane", tool2({{"Type", "plane"}, {"Point", "0, 1"}, {"Normal", "0.3, 1"}}), Point<2>(0.5, 1), false);
        tool_case("tool: circle outside", tool2({{"Type", "circle"}, {"Center", "1, 2"}, {"Radius", "0.5"}}),
                  Point<2>(1.5, 2.6), false);
        tool_case("tool: circle inside",
                  tool2({{"Type", "circle"}, {"Center", "1, 2"}, {"Radius", "2"}, {"Side", "inside"}}),
                  Point<2>(0.5, 0.9), false);
        tool_case("tool: arc", tool2({{"Type", "arc"}, {"Radius", "1"}, {"Start angle", "200"}, {"End angle", "340"}}),
                  Point<2>(0.4, -1), false);
        tool_case("tool: polyline near a convex vertex", tool2({{"Type", "polyline"}, {"Points", "-1, 0; 0, 0; 1, -1"}}),
                  Point<2>(0.05, -0.2), false);
        tool_case("tool: polyline in a concave vertex", tool2({{"Type", "polyline"}, {"Points", "-1, 1; 0, 0; 1, 1"}}),
                  Point<2>(0.1 + 0.004, -0.2 - 0.011), true);
        tool_case("tool: 3D plane", tool3({{"Type", "plane"}, {"Point", "0, 0, 1"}, {"Normal", "0.2, -0.1, 1"}}),
                  Point<3>(0.3, 0.4, 1), false);
        tool_case("tool: cylinder", tool3({{"Type", "cylinder"}, {"Axis", "1, 2, 3"}, {"Radius", "2"}}),
                  Point<3>(1.5, -1, 0.2), false);
        tool_case("tool: sphere outside", tool3({{"Type", "sphere"}, {"Center", "0, 0, 1"}, {"Radius", "2"}}),
                  Point<3>(0.5, 1.2, 2.5), false);
        tool_case("tool: sphere inside",
                  tool3({{"Type", "sphere"}, {"Center", "0, 0, 1"}, {"Radius", "2"}, {"Side", "inside"}}),
                  Point<3>(0.5, 1.2, 2.5), false);
      }

    // Frictionless: r = d(c_N g²/2)/dx, so the tangent is a Hessian: symmetric.
    FrictionLaw frictionless = law;
    frictionless.penalty_tangent = frictionless.mu_static = frictionless.mu_dynamic = 0;
    {
      const std::vector<Point<3>> master = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1),
                                            Point<3>(1.05, 1.1, 0.25)};
      const Point<3> slave(0.4, 0.5, 0.02);
      const auto     r = node_to_segment(slave, slave, master, master, NodeState<3>(), frictionless, true);
      FullMatrix<double> asym(r.tangent.m(), r.tangent.n());
      asym.copy_transposed(r.tangent);
      asym.add(-1, r.tangent);
      const double a = asym.linfty_norm() / r.tangent.linfty_norm();
      std::cout << "  frictionless warped facet: g_N " << r.gap << ", |K - K^T|/|K| = " << a << std::endl;
      check(r.in_contact && a < 1e-12, "frictionless tangent symmetric");
      worst = std::max(worst, tangent_error<3>("3D warped facet frictionless", flatten(slave, master),
                                               segment_evaluator(slave, master, NodeState<3>(), frictionless), true));
    }
    std::cout << "  largest relative tangent error: " << worst << std::endl;
    return worst;
  }

  // ------------------------------------------------------------ 3. friction closed forms

  void test_friction()
  {
    std::cout << "3. Friction closed forms on a flat master (c_N 1000, c_T 500, mu_s 0.3, mu_d 0.2)" << std::endl;
    FrictionLaw law;
    law.penalty_normal  = 1000;
    law.penalty_tangent = 500;
    law.mu_static       = 0.3;
    law.mu_dynamic      = 0.2;
    const std::vector<Point<2>> master = {Point<2>(0, 0), Point<2>(2, 0)}; // n = (0, 1)
    // Penetration 0.01: t_N = 10 N, stick limit 3 N, sliding force 2 N.
    Point<2>     slave(0.8, -0.01);
    NodeState<2> state;
    double       total_work = 0, total_slip = 0;
    // Steps of +0.0025 in x: trial forces 1.25, 2.5 (stick), 3.75 -> 2 (slip
    // 0.0035), then 2 + 1.25 = 3.25 -> 2 (slip 0.0025: steady sliding).
    const double expected_force[] = {1.25, 2.5, 2, 2, 2};
    const double expected_slip[]  = {0, 0, 0.0035, 0.0025, 0.0025};
    for (unsigned int step = 0; step < 5; ++step)
      {
        const Point<2> slave_old = slave;
        slave[0] += 0.0025;
        const auto r = node_to_segment(slave, slave_old, master, master, state, law, false);
        std::cout << "  step " << step << ": t_N " << r.normal_force << " t_T " << r.tangential_force
                  << " slip " << r.slip_increment[0] << " work " << r.frictional_work
                  << (r.sliding ? " slide" : " stick") << std::endl;
        check(close(r.normal_force, 10, 1e-10), "t_N = c_N * penetration");
        check(close(r.tangential_force, Tensor<1, 2>({expected_force[step], 0}), 1e-10),
              "t_T = c_T dg_T (stick) or mu_d t_N (slide)");
        check(close(r.slip_increment, Tensor<1, 2>({expected_slip[step], 0}), 1e-12), "slip increment");
        check(r.sliding == (step >= 2), "stick for the first two steps, then slide");
        check(close(r.frictional_work, 0.2 * 10 * expected_slip[step], 1e-12), "work = mu_d t_N slip");
        // The force of the contact on the slave, -r_s, opposes the motion (+x),
        // pushes it out (+y), and the master receives the opposite.
        check(-r.residual[0] < 0 && close(-r.residual[0], -expected_force[step], 1e-10), "friction opposes the motion");
        check(close(-r.residual[1], 10, 1e-10), "normal force pushes the slave out");
        check(close(r.residual[0] + r.residual[2] + r.residual[4], 0, 1e-12) &&
                close(r.residual[1] + r.residual[3] + r.residual[5], 0, 1e-12),
              "action = reaction");
        const double xi = slave[0] / 2;
        check(close(r.xi[0], xi, 1e-14) && close(r.residual[3], (1 - xi) * 10, 1e-10) &&
                close(r.residual[5], xi * 10, 1e-10),
              "reaction shared by the master nodes as (1 - xi, xi)");
        total_work += r.frictional_work;
        total_slip += r.slip_increment[0];
        state = r.new_state;
      }
    std::cout << "  total slip " << total_slip << " (expected 0.0085), work " << total_work
              << " (expected mu_d t_N slip = " << 2 * 0.0085 << ")" << std::endl;
    check(close(total_work, 2 * 0.0085, 1e-12), "total frictional work");
    {
      // Reverse by 0.002 from sliding at 2 N: elastic unloading, 2 - 1 = 1 N, stick.
      const Point<2> slave_old = slave;
      slave[0] -= 0.002;
      const auto r = node_to_segment(slave, slave_old, master, master, state, law, false);
      std::cout << "  reverse 0.002: t_T " << r.tangential_force << (r.sliding ? " slide" : " stick") << std::endl;
      check(!r.sliding && close(r.tangential_force, Tensor<1, 2>({1, 0}), 1e-10), "unloading sticks");
      // One large step back: slide at 2 N in -x, the slave's friction force is +x.
      const auto back = node_to_segment(Point<2>(slave[0] - 0.05, slave[1]), slave, master, master, r.new_state, law, false);
      // trial = 1 - c_T 0.05 = -24 N: slip -(24 - 2)/c_T.
      std::cout << "  back 0.05: t_T " << back.tangential_force << " slip " << back.slip_increment
                << " (expected -2 and " << -(0.05 * 500 - 1 - 2) / 500 << ")" << std::endl;
      check(back.sliding && close(back.tangential_force, Tensor<1, 2>({-2, 0}), 1e-10) && -back.residual[0] > 0,
            "slide backwards: friction on the slave opposes the motion");
      check(close(back.slip_increment[0], -(0.05 * 500 - 1 - 2) / 500, 1e-12), "backward slip");
    }
    {
      // Separated: nothing.
      const auto r = node_to_segment(Point<2>(0.8, 0.001), Point<2>(0.7, 0.001), master, master, state, law, true);
      check(!r.in_contact && r.normal_force == 0 && r.tangential_force.norm() == 0 && r.residual.l2_norm() == 0 &&
              r.tangent.frobenius_norm() == 0 && !r.new_state.in_contact,
            "no contact when g_N >= 0");
      // Beyond the segment's end: not inside, the caller tries the neighbour.
      const auto out = node_to_segment(Point<2>(2.1, -0.01), Point<2>(2.1, -0.01), master, master, state, law, true);
      std::cout << "  beyond the end: xi " << out.xi[0] << ", projection_inside " << out.projection_inside << std::endl;
      check(!out.projection_inside && !out.in_contact && out.residual.l2_norm() == 0, "projection outside the segment");
    }
    {
      // The same closed forms against a tool (plane y = 0), 3D, in z.
      const auto tool = make_tool<3>({{"Type", "plane"}, {"Motion", "t, 0, 0"}});
      NodeState<3> s;
      const Point<3> x_old(0.3, 0.2, -0.01), x = x_old + Tensor<1, 3>({0, 0.004, 0}) + Tensor<1, 3>({0.5, 0, 0});
      const auto r = node_to_tool(x, x_old, tool, 1.5, 1, s, law, true); // the tool moved +0.5 in x with the slave
      std::cout << "  3D tool, slave moved with the tool + 0.004 in y: t_T " << r.tangential_force << std::endl;
      check(close(r.tangential_force, Tensor<1, 3>({0, 2, 0}), 1e-10), "tool: stick force c_T dg_T relative to the tool");
    }
  }

  // ------------------------------------------------------------ 4. warped facet projection

  void test_facet_projection()
  {
    std::cout << "4. Closest point on a warped facet" << std::endl;
    const std::vector<Point<3>> x = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1),
                                     Point<3>(1.05, 1.1, 0.25)};
    const Point<3> slave(0.7, 0.3, -0.04);
    const auto     r = node_to_segment(slave, slave, x, x, NodeState<3>(), seed_law(), false);
    const double   s = r.xi[0], t = r.xi[1];
    const Tensor<1, 3> d     = slave - facet_point(x, s, t);
    const Tensor<1, 3> a1    = (1 - t) * (x[1] - x[0]) + t * (x[3] - x[2]);
    const Tensor<1, 3> a2    = (1 - s) * (x[2] - x[0]) + s * (x[3] - x[1]);
    const Tensor<1, 3> n     = cross_product_3d(a1, a2) / cross_product_3d(a1, a2).norm();
    std::cout << "  xi " << s << " " << t << ", gap " << r.gap << ", |x_s - x_m| " << d.norm()
              << ", (x_s - x_m).a1 " << d * a1 << ", .a2 " << d * a2 << std::endl;
    check(std::abs(d * a1) < 1e-14 && std::abs(d * a2) < 1e-14, "orthogonal to the facet's tangents");
    check(close(std::abs(r.gap), d.norm(), 1e-14) && close(r.gap, d * n, 1e-14) && close(r.normal, n, 1e-14),
          "gap and normal");
  }

  // ------------------------------------------------------------ 5. objectivity

  template <int dim>
  void check_objectivity(const std::string &name, const Point<dim> &slave, const Point<dim> &slave_old,
                         const std::vector<Point<dim>> &master, const std::vector<Point<dim>> &master_old,
                         const NodeState<dim> &state, const Tensor<2, dim> &R, const bool expect_sliding)
  {
    const FrictionLaw law = seed_law();
    const auto        rotate = [&](const Point<dim> &p) { return Point<dim>(R * p); };
    std::vector<Point<dim>> m, m_old;
    for (unsigned int a = 0; a < master.size(); ++a)
      {
        m.push_back(rotate(master[a]));
        m_old.push_back(rotate(master_old[a]));
      }
    NodeState<dim> rotated_state = state;
    rotated_state.tangential_force = R * state.tangential_force;
    const auto r  = node_to_segment(slave, slave_old, master, master_old, state, law, true);
    const auto rr = node_to_segment(rotate(slave), rotate(slave_old), m, m_old, rotated_state, law, true);

    const unsigned int n_nodes = 1 + master.size();
    double             residual_error = 0, tangent_error = 0;
    for (unsigned int a = 0; a < n_nodes; ++a)
      {
        Tensor<1, dim> ra, rra;
        for (unsigned int d = 0; d < dim; ++d)
          ra[d] = r.residual[dim * a + d], rra[d] = rr.residual[dim * a + d];
        residual_error = std::max(residual_error, (R * ra - rra).norm());
        for (unsigned int b = 0; b < n_nodes; ++b)
          {
            Tensor<2, dim> K, KK;
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                K[i][j] = r.tangent(dim * a + i, dim * b + j), KK[i][j] = rr.tangent(dim * a + i, dim * b + j);
            tangent_error = std::max(tangent_error, (R * K * transpose(R) - KK).norm());
          }
      }
    residual_error /= r.residual.linfty_norm();
    tangent_error /= r.tangent.linfty_norm();
    const double gap_error = std::abs(r.gap - rr.gap);
    const double force_error = std::abs(r.tangential_force.norm() - rr.tangential_force.norm());
    std::cout << "  " << std::left << std::setw(28) << name << " g_N " << r.gap << " vs " << rr.gap << ", |t_T| "
              << r.tangential_force.norm() << " vs " << rr.tangential_force.norm() << "; rel. error residual "
              << residual_error << ", tangent " << tangent_error << (r.sliding ? " (slide)" : " (stick)") << std::endl;
    check(r.in_contact && r.sliding == expect_sliding, name + ": branch");
    check(gap_error < 1e-12 && force_error < 1e-12 * (1 + r.tangential_force.norm()), name + ": g_N and |t_T| invariant");
    check(residual_error < 1e-12 && tangent_error < 1e-12, name + ": residual and tangent rotate");
    check((R * r.normal - rr.normal).norm() < 1e-12, name + ": normal rotates");
  }

  void test_objectivity()
  {
    std::cout << "5. Objectivity under a rigid rotation of the whole configuration" << std::endl;
    Tensor<2, 2> R2;
    const double a = 0.7;
    R2[0][0] = std::cos(a), R2[0][1] = -std::sin(a), R2[1][0] = std::sin(a), R2[1][1] = std::cos(a);
    // 3D: rotation by 1.1 rad about (1, 2, 3)/|.| (Rodrigues).
    Tensor<1, 3> k({1, 2, 3});
    k /= k.norm();
    Tensor<2, 3> K, R3 = unit_symmetric_tensor<3>();
    K[0][1] = -k[2], K[0][2] = k[1], K[1][0] = k[2], K[1][2] = -k[0], K[2][0] = -k[1], K[2][1] = k[0];
    R3 += std::sin(1.1) * K + (1 - std::cos(1.1)) * K * K;

    const std::vector<Point<2>> m2 = {Point<2>(0, 0), Point<2>(2, 0.3)}, m2_old = {Point<2>(0.001, -0.002),
                                                                                   Point<2>(1.998, 0.301)};
    NodeState<2> s2;
    s2.in_contact = true, s2.tangential_force = Tensor<1, 2>({0.8, 0.2});
    check_objectivity<2>("2D segment stick", Point<2>(0.8, 0.11), Point<2>(0.7993, 0.1096), m2, m2_old, s2, R2, false);
    check_objectivity<2>("2D segment slide", Point<2>(0.8, 0.11), Point<2>(0.78, 0.105), m2, m2_old, s2, R2, true);
    const std::vector<Point<3>> m3 = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1),
                                      Point<3>(1.05, 1.1, 0.25)};
    std::vector<Point<3>> m3_old = m3;
    for (unsigned int i = 0; i < 4; ++i)
      m3_old[i] += Tensor<1, 3>({0.0002 * i, -0.0004, 0.0001 * i});
    NodeState<3> s3;
    s3.in_contact = true, s3.tangential_force = Tensor<1, 3>({0.5, -0.7, 0.1});
    const Point<3> slave(0.4, 0.55, 0.02);
    check_objectivity<3>("3D warped facet stick", slave, slave - Tensor<1, 3>({0.0003, -0.0011, 0.0002}), m3, m3_old, s3,
                         R3, false);
    check_objectivity<3>("3D warped facet slide", slave, slave - Tensor<1, 3>({0.02, -0.01, 0.003}), m3, m3_old, s3, R3,
                         true);
  }

  // ------------------------------------------------------------ 6. moving master

  void test_moving_master()
  {
    std::cout << "6. Slave and master translated together: no tangential force" << std::endl;
    const FrictionLaw law = seed_law();
    {
      const std::vector<Point<2>> m = {Point<2>(0, 0), Point<2>(2, 0.3)};
      const Tensor<1, 2>          u({0.3, -0.1});
      std::vector<Point<2>>       m_new = {m[0] + u, m[1] + u};
      const Point<2>              slave_old(0.8, 0.11);
      const auto r = node_to_segment(slave_old + u, slave_old, m_new, m, NodeState<2>(), law, false);
      std::cout << "  2D: g_N " << r.gap << " |t_T| " << r.tangential_force.norm() << std::endl;
      check(r.in_contact && r.tangential_force.norm() < 1e-12, "2D: no tangential force");
      NodeState<2> s;
      s.in_contact = true, s.tangential_force = 1.5 * (m[1] - m[0]) / (m[1] - m[0]).norm();
      const auto rs = node_to_segment(slave_old + u, slave_old, m_new, m, s, law, false);
      std::cout << "  2D with an old force 1.5 N: t_T " << rs.tangential_force << std::endl;
      check(close(rs.tangential_force, s.tangential_force, 1e-12), "2D: the old force is kept, nothing added");
    }
    {
      const std::vector<Point<3>> m = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1),
                                       Point<3>(1.05, 1.1, 0.25)};
      const Tensor<1, 3>    u({0.3, -0.1, 0.2});
      std::vector<Point<3>> m_new;
      for (const auto &p : m)
        m_new.push_back(p + u);
      const Point<3> slave_old(0.4, 0.55, 0.02);
      const auto     r = node_to_segment(slave_old + u, slave_old, m_new, m, NodeState<3>(), law, false);
      std::cout << "  3D: g_N " << r.gap << " |t_T| " << r.tangential_force.norm() << std::endl;
      check(r.in_contact && r.tangential_force.norm() < 1e-12, "3D: no tangential force");
    }
    {
      const auto     tool = make_tool<2>({{"Type", "circle"}, {"Radius", "1"}, {"Motion", "0.3*t, -t^2"}});
      const Point<2> slave_old = Point<2>(0, 0.99) + tool.displacement(0.5); // 0.01 inside at t_old
      const auto     r = node_to_tool(Point<2>(slave_old + tool.displacement(1) - tool.displacement(0.5)), slave_old,
                                      tool, 1, 0.5, NodeState<2>(), law, false);
      std::cout << "  tool: g_N " << r.gap << " |t_T| " << r.tangential_force.norm() << std::endl;
      check(r.in_contact && r.tangential_force.norm() < 1e-12, "tool: no tangential force");
    }
  }

  // ------------------------------------------------------------ 7. deal.II face order

  template <int dim>
  void test_face_order()
  {
    // A unit cell, rotated, sheared and moved: each face as a master, ordered
    // per face_order_gives_outward_normal(), must have its normal pointing
    // out of the cell (a slave just outside the face center sees g_N > 0).
    Triangulation<dim> tria;
    GridGenerator::hyper_cube(tria, 0, 1);
    GridTools::transform(
      [](const Point<dim> &p) {
        Point<dim> q;
        q[0] = 1.3 * p[0] + 0.4 * p[1] + 2;
        q[1] = -0.3 * p[0] + 0.9 * p[1] - 1;
        if constexpr (dim == 3)
          q[0] += 0.2 * p[2], q[1] += 0.1 * p[2], q[2] = 0.1 * p[0] + 1.1 * p[2];
        return q;
      },
      tria);
    const auto cell = tria.begin_active();
    unsigned int ok = 0;
    for (unsigned int f = 0; f < GeometryInfo<dim>::faces_per_cell; ++f)
      {
        std::vector<Point<dim>> master;
        for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_face; ++v)
          master.push_back(cell->vertex(GeometryInfo<dim>::face_to_cell_vertices(f, v)));
        if (!face_order_gives_outward_normal<dim>(f))
          {
            if (dim == 2)
              std::swap(master[0], master[1]);
            else
              std::swap(master[1], master[2]);
          }
        const Tensor<1, dim> outward = cell->face(f)->center() - cell->center();
        const Point<dim>     slave   = cell->face(f)->center() + 0.01 * outward;
        const auto r = node_to_segment(slave, slave, master, master, NodeState<dim>(), seed_law(), false);
        if (r.gap > 0 && r.normal * outward > 0 && r.projection_inside)
          ++ok;
      }
    std::cout << "  " << dim << "D: " << ok << " of " << GeometryInfo<dim>::faces_per_cell
              << " faces with the master normal pointing out of the cell" << std::endl;
    check(ok == GeometryInfo<dim>::faces_per_cell, "face_order_gives_outward_normal<" + std::to_string(dim) + ">");
  }
} // namespace

int main()
{
  std::cout << std::setprecision(6);
  try
    {
      test_tools();
      double worst = test_tangents();
      test_friction();
      test_facet_projection();
      test_objectivity();
      test_moving_master();
      std::cout << "7. Master node order of deal.II faces" << std::endl;
      test_face_order<2>();
      test_face_order<3>();
      worst = std::max(worst, test_concave_corner());
      worst = std::max(worst, test_free_edge());
      std::cout << "largest tangent error " << worst << std::endl;
    }
  catch (const std::exception &e)
    {
      std::cout << "exception: " << e.what() << std::endl;
      return 1;
    }
  return check.finish();
}
