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
#include "check.h"

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/differentiation/ad.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <anvil/contact/contact_element.h>
#include <anvil/contact/free_end.h>
#include <anvil/contact/rigid_tool.h>
#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <unistd.h>

using namespace dealii;
using namespace anvil;
using namespace anvil::contact;

using ADNumber = Sacado::Fad::DFad<double>;

namespace
{
  anvil::testing::Checks check{anvil::testing::Checks::Print::failures_only};

  bool close(const double a, const double b, const double tol)
  {
    return std::abs(a - b) <= tol;
  }

  template <int dim>
  bool close(const Tensor<1, dim> &a, const Tensor<1, dim> &b, const double tol)
  {
    return (a - b).norm() <= tol;
  }

  template <int dim>
  Tensor<1, dim> vec(const std::vector<double> &v)
  {
    Tensor<1, dim> t;
    for (unsigned int d = 0; d < dim; ++d)
      t[d] = v[d];
    return t;
  }

  template <int dim>
  Point<dim> pt(const std::vector<double> &v)
  {
    return Point<dim>(vec<dim>(v));
  }

  using Settings = std::vector<std::pair<std::string, std::string>>;

  /// A tool from settings of its subsection, parsed as from a scene.
  template <int dim>
  RigidTool<dim> make_tool(const Settings &settings)
  {
    ParameterHandler prm;
    prm.enter_subsection("Contact");
    prm.enter_subsection("tool");
    RigidTool<dim>::declare_parameters(prm);
    for (const auto &[entry, value] : settings)
      prm.set(entry, value);
    RigidTool<dim> tool;
    tool.parse_parameters(prm, Scene(), "Contact/tool");
    prm.leave_subsection();
    prm.leave_subsection();
    return tool;
  }

  // ------------------------------------------------------------ 1. tools

  template <int dim>
  void check_projection(const std::string &name, const RigidTool<dim> &tool, const std::vector<double> &x,
                        const double t, const double gap_expected, const std::vector<double> &normal_expected)
  {
    double         gap = 0;
    Tensor<1, dim> normal;
    tool.project(vec<dim>(x), t, gap, normal);
    std::cout << "  " << std::left << std::setw(34) << name << " gap " << std::setw(12) << gap
              << " (expected " << std::setw(12) << gap_expected << ") normal " << normal << std::endl;
    check(close(gap, gap_expected, 1e-13), name + ": gap");
    check(close(normal, vec<dim>(normal_expected), 1e-13), name + ": normal");
  }

  /// d gap/dx and d normal/dx of project<DFad> against central differences.
  template <int dim>
  double projection_derivative_error(const std::string &name, const RigidTool<dim> &tool,
                                     const std::vector<double> &x0, const double t)
  {
    Tensor<1, dim, ADNumber> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = ADNumber(dim, d, x0[d]);
    ADNumber                 gap;
    Tensor<1, dim, ADNumber> normal;
    tool.project(x, t, gap, normal);

    const double h = 1e-6;
    double       error = 0, largest = 1;
    for (unsigned int j = 0; j < dim; ++j)
      {
        Tensor<1, dim> xp = vec<dim>(x0), xm = vec<dim>(x0);
        xp[j] += h;
        xm[j] -= h;
        double         gp, gm;
        Tensor<1, dim> np, nm;
        tool.project(xp, t, gp, np);
        tool.project(xm, t, gm, nm);
        const auto derivative = [j](const ADNumber &v) { return v.size() ? v.dx(j) : 0.; };
        error   = std::max(error, std::abs(derivative(gap) - (gp - gm) / (2 * h)));
        largest = std::max(largest, std::abs(derivative(gap)));
        for (unsigned int i = 0; i < dim; ++i)
          {
            error   = std::max(error, std::abs(derivative(normal[i]) - (np[i] - nm[i]) / (2 * h)));
            largest = std::max(largest, std::abs(derivative(normal[i])));
          }
      }
    error /= largest;
    std::cout << "  d/dx " << std::left << std::setw(34) << name << " gap " << std::setw(12) << gap.val()
              << " rel. error vs FD " << error << std::endl;
    check(error < 1e-6, name + ": projection derivatives");
    return error;
  }

  void expect_input_error(const std::function<void()> &f, const std::vector<std::string> &fragments)
  {
    try
      {
        f();
        check(false, "no InputError for a case expecting '" + fragments[0] + "'");
      }
    catch (const InputError &e)
      {
        const std::string message = e.what();
        std::cout << "  error: " << message << std::endl;
        bool ok = message.find('\n') == std::string::npos;
        for (const auto &fragment : fragments)
          ok = ok && message.find(fragment) != std::string::npos;
        check(ok, "message '" + message + "' should contain '" + fragments[0] + "'...");
      }
  }

  void test_tools()
  {
    std::cout << "1. Rigid tools: gap and normal against hand-computed values" << std::endl;
    const double s5 = std::sqrt(5.), s2 = std::sqrt(2.);
    {
      const auto plane = make_tool<2>({{"Type", "plane"}, {"Point", "0, 1"}, {"Normal", "3, 4"}});
      check_projection("2D plane, normal (3,4)", plane, {1, 2}, 0, 1.4, {0.6, 0.8});
      check_projection("2D plane, penetrating", plane, {0, 0.5}, 0, -0.4, {0.6, 0.8});
      const auto outside = make_tool<2>({{"Type", "circle"}, {"Center", "1, 2"}, {"Radius", "0.5"}});
      check_projection("circle outside |x-c| - R", outside, {1.6, 2.8}, 0, 0.5, {0.6, 0.8});
      check_projection("circle outside, penetrating", outside, {1.12, 2.16}, 0, -0.3, {0.6, 0.8});
      const auto inside =
        make_tool<2>({{"Type", "circle"}, {"Center", "1, 2"}, {"Radius", "2"}, {"Side", "inside"}});
      check_projection("circle inside R - |x-c|", inside, {1.6, 2.8}, 0, 1, {-0.6, -0.8});
      check_projection("circle inside, penetrating", inside, {1 + 1.5, 2 + 2}, 0, -0.5, {-0.6, -0.8});
      const auto arc = make_tool<2>(
        {{"Type", "arc"}, {"Center", "0, 0"}, {"Radius", "1"}, {"Start angle", "0"}, {"End angle", "90"}});
      check_projection("arc, within its range", arc, {1.2, 1.6}, 0, 1, {0.6, 0.8});
      check_projection("arc, below the start end (1,0)", arc, {0, -2}, 0, s5, {-1 / s5, -2 / s5});
      check_projection("arc, left of the end (0,1)", arc, {-2, 0.5}, 0, std::sqrt(4.25),
                       {-2 / std::sqrt(4.25), -0.5 / std::sqrt(4.25)});
      const auto cup = make_tool<2>({{"Type", "arc"}, {"Center", "0, 0"}, {"Radius", "1"}, {"Side", "inside"},
                                     {"Start angle", "180"}, {"End angle", "360"}});
      check_projection("arc inside (a cup), bottom", cup, {0, -0.5}, 0, 0.5, {0, 1});
      check_projection("arc inside, penetrating", cup, {0.75, -1}, 0, -0.25, {-0.6, 0.8});
      const auto convex = make_tool<2>({{"Type", "polyline"}, {"Points", "-1, 0; 0, 0; 1, -1"}});
      check_projection("polyline, on the first segment", convex, {-0.5, 0.2}, 0, 0.2, {0, 1});
      check_projection("polyline, convex vertex region", convex, {0.3, 0.4}, 0, 0.5, {0.6, 0.8});
      check_projection("polyline, second segment, penetr.", convex, {0.5, -0.6}, 0, -0.1 / s2, {1 / s2, 1 / s2});
      check_projection("polyline, first end (above)", convex, {-1.3, 0.4}, 0, 0.5, {-0.6, 0.8});
      check_projection("polyline, first end (below): open", convex, {-1.3, -0.4}, 0, 0.5, {-0.6, -0.8});
      const auto concave = make_tool<2>({{"Type", "polyline"}, {"Points", "-1, 1; 0, 0; 1, 1;"}});
      check_projection("polyline, concave vertex region", concave, {0.3, -0.4}, 0, -0.5, {-0.6, 0.8});
      check_projection("polyline, concave, bodies' side", concave, {-0.1, 0.3}, 0, 0.2 / s2, {1 / s2, 1 / s2});
      const auto straight = make_tool<2>({{"Type", "polyline"}, {"Points", "0, 0; 1, 0; 3, 0"}});
      check_projection("polyline, straight vertex", straight, {1, -0.25}, 0, -0.25, {0, 1});
    }
    {
      const auto plane = make_tool<3>({{"Type", "plane"}, {"Point", "0, 0, 1"}, {"Normal", "0, 0, -2"}});
      check_projection("3D plane", plane, {5, 5, 0.25}, 0, 0.75, {0, 0, -1});
      const auto cylinder = make_tool<3>({{"Type", "cylinder"}, {"Center", "0, 0, 0"}, {"Axis", "0, 0, 2"}});
      check_projection("cylinder along z", cylinder, {1.8, 2.4, 7}, 0, 2, {0.6, 0.8, 0});
      const auto tilted = make_tool<3>({{"Type", "cylinder"}, {"Center", "0, 0, 0"}, {"Axis", "1, 1, 0"}});
      check_projection("cylinder along (1,1,0)", tilted, {1, 1, 2}, 0, 1, {0, 0, 1});
      check_projection("cylinder, penetrating", tilted, {-3, -3, 0.5}, 0, -0.5, {0, 0, 1});
      const auto sphere = make_tool<3>(
        {{"Type", "sphere"}, {"Center", "1, 1, 1"}, {"Radius", "3"}, {"Side", "inside"}});
      check_projection("sphere inside", sphere, {1, 2.2, 2.6}, 0, 1, {0, -0.6, -0.8});
      const auto ball = make_tool<3>({{"Type", "sphere"}, {"Center", "1, 1, 1"}, {"Radius", "3"}});
      check_projection("sphere outside", ball, {1, 1 + 2.4, 1 + 3.2}, 0, 1, {0, 0.6, 0.8});
    }

    std::cout << "   motion and temperature" << std::endl;
    {
      const auto moving = make_tool<2>({{"Type", "circle"}, {"Center", "1, 2"}, {"Radius", "0.5"},
                                        {"Motion", "0.5*t, -2*t^2"}, {"Temperature", "293 + 10*t"}});
      const Tensor<1, 2> u = moving.displacement(2);
      std::cout << "  u(2) = " << u << " (expected 1 -8), T(3) = " << moving.temperature(3)
                << " (expected 323)" << std::endl;
      check(close(u, vec<2>({1, -8}), 1e-14), "translation expression");
      check(close(moving.temperature(3), 323, 1e-12), "temperature expression");
      check(moving.name == "tool" && moving.type() == "circle", "name and type");
      check_projection("circle translated by u(2)", moving, {1 + 1 + 0.6, 2 - 8 + 0.8}, 2, 0.5, {0.6, 0.8});
      const auto still = make_tool<3>({{"Type", "plane"}});
      check(still.displacement(7).norm() == 0 && still.temperature(7) == 293, "default motion 0 and 293 K");
      const auto moving3 = make_tool<3>({{"Type", "sphere"}, {"Center", "0, 0, 0"}, {"Motion", "t, 2*t, sin(pi*t/2)"}});
      check(close(moving3.displacement(1), vec<3>({1, 2, 1}), 1e-14), "3D translation expression");
      check_projection("sphere translated by u(1)", moving3, {1, 2, 1 + 3}, 1, 2, {0, 0, 1});
    }

    std::cout << "   derivatives of project<DFad> against central differences" << std::endl;
    {
      const Settings motion2 = {{"Motion", "0.1*t, -0.2*t"}};
      auto with_motion = [&](Settings s) {
        s.insert(s.end(), motion2.begin(), motion2.end());
        return make_tool<2>(s);
      };
      const auto arc = with_motion({{"Type", "arc"}, {"Radius", "1"}, {"Start angle", "0"}, {"End angle", "90"}});
      projection_derivative_error("arc, within its range", arc, {0.7, 0.5}, 1);
      projection_derivative_error("arc, end region", arc, {0.3, -1.1}, 1);
      const auto circle = with_motion({{"Type", "circle"}, {"Radius", "1"}, {"Side", "inside"}});
      projection_derivative_error("circle inside", circle, {0.5, -0.3}, 1);
      const auto convex = with_motion({{"Type", "polyline"}, {"Points", "-1, 0; 0, 0; 1, -1"}});
      projection_derivative_error("polyline, convex vertex region", convex, {0.4, 0.2}, 1);
      projection_derivative_error("polyline, end region", convex, {1.5, -1.5}, 1);
      const auto concave = with_motion({{"Type", "polyline"}, {"Points", "-1, 1; 0, 0; 1, 1"}});
      projection_derivative_error("polyline, concave vertex region", concave, {0.12, -0.33}, 1);
      const auto cylinder = make_tool<3>({{"Type", "cylinder"}, {"Axis", "1, 2, 3"}, {"Radius", "2"},
                                          {"Motion", "0.1*t, 0, -t"}});
      projection_derivative_error("cylinder", cylinder, {0.5, 1.7, -0.2}, 1);
      const auto sphere = make_tool<3>({{"Type", "sphere"}, {"Radius", "2"}, {"Center", "1, 0, 0"}});
      projection_derivative_error("sphere", sphere, {0.5, 1.7, -0.2}, 1);
    }

    std::cout << "   input validation (one-line InputError naming the entry)" << std::endl;
    {
      const auto bad2 = [](const Settings &s) { return [s]() { make_tool<2>(s); }; };
      const auto bad3 = [](const Settings &s) { return [s]() { make_tool<3>(s); }; };
      expect_input_error(bad2({{"Type", "circle"}, {"Radius", "0"}}), {"Contact/tool/Radius", "> 0"});
      expect_input_error(bad2({{"Type", "plane"}, {"Normal", "0, 0"}}), {"Contact/tool/Normal", "nonzero"});
      expect_input_error(bad2({{"Type", "plane"}, {"Point", "1, x"}}), {"Contact/tool/Point", "not a number"});
      expect_input_error(bad2({{"Type", "plane"}, {"Point", "1, 2, 3"}}), {"Contact/tool/Point", "'x, y'"});
      expect_input_error(bad2({{"Type", "polyline"}, {"Points", "0, 0; 0, 0"}}), {"Contact/tool/Points", "length > 0"});
      expect_input_error(bad2({{"Type", "polyline"}, {"Points", "0, 0"}}), {"Contact/tool/Points", "at least two"});
      expect_input_error(bad2({{"Type", "polyline"}, {"Points", "0, 0; 1"}}), {"Contact/tool/Points", "1 numbers"});
      expect_input_error(bad2({{"Type", "cylinder"}}), {"Contact/tool/Type", "3D tool"});
      expect_input_error(bad3({{"Type", "arc"}}), {"Contact/tool/Type", "2D tool"});
      expect_input_error(bad2({{"Type", "arc"}, {"Start angle", "90"}, {"End angle", "45"}}),
                         {"Contact/tool/End angle", "End angle - Start angle"});
      expect_input_error(bad3({{"Type", "cylinder"}, {"Axis", "0, 0, 0"}}), {"Contact/tool/Axis", "nonzero"});
      expect_input_error(bad2({{"Motion", "t"}}), {"Contact/tool/Motion", "2 ','-separated"});
      expect_input_error(bad2({{"Motion", "t, foo*t"}}), {"Contact/tool/Motion", "invalid expression"});
      expect_input_error(bad2({{"Temperature", "-5"}}), {"Contact/tool/Temperature", "> 0"});

      // From a scene file: the message names file:line.
      const std::string file =
        (std::filesystem::temp_directory_path() / ("anvil_contact_" + std::to_string(getpid()) + ".prm")).string();
      std::ofstream(file) << "subsection Contact\n  subsection die\n    set Type = circle\n"
                             "    set Radius = -2\n  end\nend\n";
      expect_input_error(
        [&]() {
          Scene scene(file, {});
          scene.read([](ParameterHandler &prm, const auto &) { // the declarator's second argument is not needed
            prm.enter_subsection("Contact");
            prm.enter_subsection("die");
            RigidTool<2>::declare_parameters(prm);
            prm.leave_subsection();
            prm.leave_subsection();
          });
          ParameterHandler &prm = scene.parameters();
          prm.enter_subsection("Contact");
          prm.enter_subsection("die");
          RigidTool<2> tool;
          tool.parse_parameters(prm, scene, "Contact/die");
        },
        {file + ":4", "Contact/die/Radius", "> 0"});
      std::remove(file.c_str());
    }
  }

  // ------------------------------------------------------------ 2. tangents

  template <int dim>
  using Evaluator = std::function<ContactResult<dim>(const std::vector<double> &, bool)>;

  /// The AD tangent against central differences of the residual, max-norm
  /// relative error; the branch (contact, stick/slide) must not change.
  template <int dim>
  double tangent_error(const std::string &name, const std::vector<double> &x0, const Evaluator<dim> &f,
                       const bool expect_sliding)
  {
    const ContactResult<dim> base  = f(x0, true);
    const ContactResult<dim> plain = f(x0, false);
    check(base.in_contact && base.projection_inside, name + ": in contact");
    check(base.sliding == expect_sliding, name + (expect_sliding ? ": sliding" : ": sticking"));
    const unsigned int n = x0.size();
    double             scale = 1;
    for (const double x : x0)
      scale = std::max(scale, std::abs(x));
    const double h = 1e-6 * scale;

    double error = 0, largest = 0, residual_difference = 0;
    for (unsigned int i = 0; i < n; ++i)
      residual_difference = std::max(residual_difference, std::abs(base.residual[i] - plain.residual[i]));
    for (unsigned int j = 0; j < n; ++j)
      {
        std::vector<double> xp = x0, xm = x0;
        xp[j] += h;
        xm[j] -= h;
        const auto rp = f(xp, false), rm = f(xm, false);
        check(rp.in_contact && rm.in_contact && rp.sliding == base.sliding && rm.sliding == base.sliding,
              name + ": the branch changed within the finite-difference step");
        for (unsigned int i = 0; i < n; ++i)
          {
            const double fd = (rp.residual[i] - rm.residual[i]) / (2 * h);
            error           = std::max(error, std::abs(base.tangent(i, j) - fd));
            largest         = std::max(largest, std::abs(base.tangent(i, j)));
          }
      }
    error /= largest;
    std::cout << "  " << std::left << std::setw(40) << name << " g_N " << std::setw(12) << base.gap << " t_N "
              << std::setw(10) << base.normal_force << " |t_T| " << std::setw(10)
              << base.tangential_force.norm() << (base.sliding ? " slide" : " stick") << "  max|K| "
              << std::setw(10) << largest << " rel. error vs FD " << error << std::endl;
    check(error < 1e-6, name + ": tangent vs finite differences");
    check(residual_difference < 1e-12 * (1 + base.residual.linfty_norm()), name + ": AD and plain residuals differ");
    return error;
  }

  template <int dim>
  std::vector<double> flatten(const Point<dim> &slave, const std::vector<Point<dim>> &master)
  {
    std::vector<double> x;
    for (unsigned int d = 0; d < dim; ++d)
      x.push_back(slave[d]);
    for (const auto &p : master)
      for (unsigned int d = 0; d < dim; ++d)
        x.push_back(p[d]);
    return x;
  }

  template <int dim>
  Evaluator<dim> segment_evaluator(const Point<dim> &slave_old, const std::vector<Point<dim>> &master_old,
                                   const NodeState<dim> &state, const FrictionLaw &law)
  {
    return [=](const std::vector<double> &x, const bool tangent) {
      Point<dim>              slave;
      std::vector<Point<dim>> master(master_old.size());
      for (unsigned int d = 0; d < dim; ++d)
        slave[d] = x[d];
      for (unsigned int a = 0; a < master.size(); ++a)
        for (unsigned int d = 0; d < dim; ++d)
          master[a][d] = x[dim * (a + 1) + d];
      return node_to_segment(slave, slave_old, master, master_old, state, law, tangent);
    };
  }

  template <int dim>
  Evaluator<dim> tool_evaluator(const Point<dim> &slave_old, const RigidTool<dim> &tool, const double t,
                                const double t_old, const NodeState<dim> &state, const FrictionLaw &law)
  {
    return [=](const std::vector<double> &x, const bool tangent) {
      Point<dim> slave;
      for (unsigned int d = 0; d < dim; ++d)
        slave[d] = x[d];
      return node_to_tool(slave, slave_old, tool, t, t_old, state, law, tangent);
    };
  }

  FrictionLaw seed_law()
  {
    FrictionLaw law;
    law.penalty_normal  = 1e3; // the seed's 2-block test, N/mm
    law.penalty_tangent = 1e3;
    law.mu_static       = 0.3;
    law.mu_dynamic      = 0.2;
    return law;
  }

  /// A point of the bilinear facet at (s, t) (the test's own formula).
  Point<3> facet_point(const std::vector<Point<3>> &x, const double s, const double t)
  {
    return Point<3>((1 - s) * (1 - t) * x[0] + s * (1 - t) * x[1] + (1 - s) * t * x[2] + s * t * x[3]);
  }

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
            std::vector<Point<3>> master = {Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0, 1, 0), Point<3>(1, 1, 0)};
            if (warped)
              master = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1), Point<3>(1.05, 1.1, 0.25)};
            std::vector<Point<3>> master_old = master;
            for (unsigned int a = 0; a < 4; ++a)
              master_old[a] += Tensor<1, 3>({0.0002 * a, -0.0004, 0.0001 * a});
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
            std::vector<Point<3>> master = {Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0, 1, 0), Point<3>(1, 1, 0)};
            if (warped)
              master = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1), Point<3>(1.05, 1.1, 0.25)};
            std::vector<Point<3>> master_old = master;
            for (unsigned int a = 0; a < 4; ++a)
              master_old[a] += Tensor<1, 3>({0.0002 * a, -0.0004, 0.0001 * a});
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
