#include <deal.II/base/utilities.h>

#include <anvil/contact/tool_shapes/interface.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace tool_shapes
  {
    std::vector<double> parse_numbers(const std::string &text,
                                      const unsigned int count,
                                      const Scene       &scene,
                                      const std::string &path,
                                      const std::string &expected)
    {
      std::vector<double> numbers;
      for (const auto &item : split_outside_parentheses(text, ','))
        {
          std::size_t used  = 0;
          double      value = 0;
          try
            {
              value = std::stod(item, &used);
            }
          catch (...)
            {
              used = 0;
            }
          if (item.empty() || used != item.size() || !std::isfinite(value))
            scene.fail(path, "= '" + text + "': '" + item + "' is not a number; expected " + expected);
          numbers.push_back(value);
        }
      if (numbers.size() != count)
        scene.fail(path, "= '" + text + "' has " + std::to_string(numbers.size()) +
                           " numbers: expected " + expected);
      return numbers;
    }

    template <int dim>
    Tensor<1, dim> parse_vector(const std::string &text,
                                const Scene       &scene,
                                const std::string &path,
                                const std::string &what)
    {
      const auto     numbers = parse_numbers(text, dim, scene, path,
                                         what + (dim == 2 ? " 'x, y'" : " 'x, y, z'") + " in mm");
      Tensor<1, dim> v;
      for (unsigned int d = 0; d < dim; ++d)
        v[d] = numbers[d];
      return v;
    }

    template <int dim>
    Tensor<1, dim> parse_direction(const std::string &text,
                                   const Scene       &scene,
                                   const std::string &path,
                                   const std::string &what)
    {
      const Tensor<1, dim> v = parse_vector<dim>(text, scene, path, what);
      if (!(v.norm() > 0))
        scene.fail(path, "= '" + text + "' is the zero vector: expected a nonzero " + what);
      return v / v.norm();
    }

    template <int dim>
    void RoundSurface<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Center", dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
                        "circle, arc, sphere: center; cylinder: a point of the axis; " +
                          std::string(dim == 2 ? "'x, y'" : "'x, y, z'") + " in mm (at zero motion).");
      prm.declare_entry("Radius", "1", Patterns::Double(),
                        "circle, arc, cylinder, sphere: radius in mm, > 0.");
      prm.declare_entry("Side", "outside", Patterns::Selection("outside|inside"),
                        "circle, arc, cylinder, sphere: where the bodies are, outside the circle "
                        "(a punch nose, a roller) or inside it (a ring die).");
    }

    template <int dim>
    void RoundSurface<dim>::parse_parameters(ParameterHandler  &prm,
                                             const Scene       &scene,
                                             const std::string &path)
    {
      radius = prm.get_double("Radius");
      if (!(radius > 0))
        scene.fail(path + "/Radius",
                   "is " + Utilities::to_string(radius) + ": expected a radius > 0 (mm)");
      center = Point<dim>(parse_vector<dim>(prm.get("Center"), scene, path + "/Center", "a center"));
      bodies_outside = prm.get("Side") == "outside";
    }

#define INSTANTIATE(dim)                                                                        \
  template Tensor<1, dim> parse_vector<dim>(const std::string &, const Scene &,                 \
                                            const std::string &, const std::string &);          \
  template Tensor<1, dim> parse_direction<dim>(const std::string &, const Scene &,              \
                                               const std::string &, const std::string &);       \
  template struct RoundSurface<dim>;
    ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
  } // namespace tool_shapes
} // namespace anvil
