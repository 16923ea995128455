#include <deal.II/base/utilities.h>
#include <deal.II/differentiation/ad.h>

#include <anvil/contact/ad_helpers.h>
#include <anvil/contact/rigid_tool.h>
#include <anvil/contact/tool_shapes/interface.h>
#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>

#include <algorithm>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// "a, b, c or d"
    std::string list_of(std::vector<std::string> names)
    {
      std::sort(names.begin(), names.end());
      std::string list;
      for (unsigned int i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
      return list;
    }

    /// Shapes of @p dim, then those only the other dimension has (refused with a clear line).
    template <int dim>
    std::vector<std::string> all_shape_names()
    {
      auto names = ToolShapeRegistry<dim>::instance().names();
      for (const auto &n : ToolShapeRegistry<dim == 2 ? 3 : 2>::instance().names())
        if (std::find(names.begin(), names.end(), n) == names.end())
          names.push_back(n);
      return names;
    }
  } // namespace

  template <int dim>
  void RigidTool<dim>::declare_parameters(ParameterHandler &prm)
  {
    constexpr int other = dim == 2 ? 3 : 2;
    const std::string zero  = dim == 2 ? "0, 0" : "0, 0, 0";
    const std::string names = [] {
      std::string p;
      for (const auto &n : all_shape_names<dim>())
        p += (p.empty() ? "" : "|") + n;
      return p;
    }();
    prm.declare_entry("Type", "plane", Patterns::Selection(names),
                      "Surface of the rigid tool: in " + std::to_string(dim) + "D " +
                        ToolShapeRegistry<dim>::instance().documentation(" ") + " (in " +
                        std::to_string(other) + "D: " + list_of(ToolShapeRegistry<other>::instance().names()) +
                        ").");
    // The entries of the other dimension's shapes too, so that a scene naming
    // one gets the clear refusal of parse_parameters(), not an unknown entry;
    // this dimension's shapes are declared last (their defaults win where the
    // names are shared).
    ToolShapeRegistry<other>::instance().declare_parameters(prm);
    ToolShapeRegistry<dim>::instance().declare_parameters(prm);
    prm.declare_entry("Motion", zero, Patterns::Anything(),
                      "Translation of the whole tool, " + std::string(dim == 2 ? "'ux, uy'" : "'ux, uy, uz'") +
                        ": muparser expressions of the time t in mm (pi is known), e.g. '0, -0.5*t'.");
    prm.declare_entry("Temperature", "293", Patterns::Anything(),
                      "Temperature of the tool in K: a muparser expression of the time t, e.g. "
                      "'293 + 100*min(t, 1)'.");
  }

  template <int dim>
  void RigidTool<dim>::parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path)
  {
    constexpr int other = dim == 2 ? 3 : 2;
    name      = path.substr(path.find_last_of('/') + 1);
    type_name = prm.get("Type");
    const auto entry = [&](const std::string &e) { return path + "/" + e; };

    const auto &registry = ToolShapeRegistry<dim>::instance();
    if (!registry.has(type_name))
      scene.fail(entry("Type"), "is " + type_name + ", a " + std::to_string(other) + "D tool: in " +
                                  std::to_string(dim) + "D use " + list_of(registry.names()));
    auto new_shape = registry.create(type_name);
    new_shape->parse_parameters(prm, scene, path);
    shape = std::move(new_shape);

    motion.clear();
    const std::string motion_text = prm.get("Motion");
    const auto        components  = split_outside_parentheses(motion_text, ',');
    if (components.size() != dim)
      scene.fail(entry("Motion"), "= '" + motion_text + "' has " + std::to_string(components.size()) +
                                    " components: expected " + std::to_string(dim) +
                                    " ','-separated expressions of t (mm)");
    for (unsigned int d = 0; d < dim; ++d)
      motion.push_back(parse_expression<1>(components[d], "t", false, scene, entry("Motion"),
                                           std::string("the tool's ") + "xyz"[d] + " translation"));

    temperature_function = parse_expression<1>(prm.get("Temperature"), "t", false, scene,
                                               entry("Temperature"), "the tool's temperature");
    const double T0 = temperature(0);
    if (!(T0 > 0))
      scene.fail(entry("Temperature"), "is " + Utilities::to_string(T0) +
                                         " K at t = 0: expected an absolute temperature > 0 (K)");
  }

  template <int dim>
  Tensor<1, dim> RigidTool<dim>::displacement(const double t) const
  {
    Tensor<1, dim> u;
    for (unsigned int d = 0; d < motion.size(); ++d)
      u[d] = motion[d]->value(Point<1>(t));
    return u;
  }

  template <int dim>
  double RigidTool<dim>::temperature(const double t) const
  {
    return temperature_function ? temperature_function->value(Point<1>(t)) : 293.;
  }

  template <int dim>
  template <typename Number>
  void RigidTool<dim>::project(const Tensor<1, dim, Number> &x,
                               const double                  t,
                               Number                       &gap,
                               Tensor<1, dim, Number>       &normal) const
  {
    project_displaced(x, displacement(t), gap, normal);
  }

  template <int dim>
  template <typename Number>
  void RigidTool<dim>::project_displaced(const Tensor<1, dim, Number> &x,
                                         const Tensor<1, dim>         &u,
                                         Number                       &gap,
                                         Tensor<1, dim, Number>       &normal) const
  {
    // The tool only translates: work in its own frame, y = x - u(t).
    Tensor<1, dim, Number> y;
    for (unsigned int d = 0; d < dim; ++d)
      y[d] = x[d] - u[d];
    shape->project(y, gap, normal);
  }

#define INSTANTIATE(dim)                                                                          \
  template class RigidTool<dim>;                                                                  \
  template void RigidTool<dim>::project<double>(const Tensor<1, dim, double> &, double, double &, \
                                                Tensor<1, dim, double> &) const;                  \
  template void RigidTool<dim>::project<Sacado::Fad::DFad<double>>(                               \
    const Tensor<1, dim, Sacado::Fad::DFad<double>> &, double, Sacado::Fad::DFad<double> &,       \
    Tensor<1, dim, Sacado::Fad::DFad<double>> &) const;                                           \
  template void RigidTool<dim>::project_displaced<double>(                                        \
    const Tensor<1, dim, double> &, const Tensor<1, dim> &, double &, Tensor<1, dim, double> &)   \
    const;                                                                                        \
  template void RigidTool<dim>::project_displaced<Sacado::Fad::DFad<double>>(                     \
    const Tensor<1, dim, Sacado::Fad::DFad<double>> &, const Tensor<1, dim> &,                    \
    Sacado::Fad::DFad<double> &, Tensor<1, dim, Sacado::Fad::DFad<double>> &) const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
