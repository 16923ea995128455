// Part 1 of the contact element test (contact_element.cc says what all parts
// check): rigid tools' gap and normal against hand-computed values, their
// translation and temperature expressions, input validation messages, and
// project<DFad>'s derivatives against central differences.
#include "contact_element_support.h"

namespace contact_test
{
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

} // namespace contact_test
