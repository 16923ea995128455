// Shared by the contact element test's files (contact_element.cc,
// contact_element_tools.cc, contact_element_corners.cc): one pass/fail
// bookkeeping, the tool parser and the finite-difference tangent check, so
// that every part checks its tangents against the same yardstick.
#ifndef anvil_tests_contact_element_support_h
#define anvil_tests_contact_element_support_h

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

namespace contact_test
{
  inline anvil::testing::Checks check{anvil::testing::Checks::Print::failures_only};

  inline bool close(const double a, const double b, const double tol)
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

  inline FrictionLaw seed_law()
  {
    FrictionLaw law;
    law.penalty_normal  = 1e3; // the seed's 2-block test, N/mm
    law.penalty_tangent = 1e3;
    law.mu_static       = 0.3;
    law.mu_dynamic      = 0.2;
    return law;
  }

  /// A point of the bilinear facet at (s, t) (the test's own formula).
  inline Point<3> facet_point(const std::vector<Point<3>> &x, const double s, const double t)
  {
    return Point<3>((1 - s) * (1 - t) * x[0] + s * (1 - t) * x[1] + (1 - s) * t * x[2] + s * t * x[3]);
  }

  /// The test facet, flat or warped, and its old position (moved a little).
  inline std::pair<std::vector<Point<3>>, std::vector<Point<3>>> test_facet(const bool warped)
  {
    std::vector<Point<3>> master = {Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0, 1, 0), Point<3>(1, 1, 0)};
    if (warped)
      master = {Point<3>(0, 0, 0.05), Point<3>(1.1, -0.05, 0), Point<3>(-0.05, 0.95, -0.1), Point<3>(1.05, 1.1, 0.25)};
    std::vector<Point<3>> master_old = master;
    for (unsigned int a = 0; a < 4; ++a)
      master_old[a] += Tensor<1, 3>({0.0002 * a, -0.0004, 0.0001 * a});
    return {master, master_old};
  }

  void   test_tools();           // 1. contact_element_tools.cc
  double test_concave_corner();  // 8. contact_element_corners.cc
  double test_free_edge();       // 9. contact_element_corners.cc
} // namespace contact_test

#endif
