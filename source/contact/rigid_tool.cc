#include <deal.II/base/utilities.h>
#include <deal.II/differentiation/ad.h>

#include <anvil/contact/ad_helpers.h>
#include <anvil/contact/rigid_tool.h>
#include <anvil/core/expression.h>
#include <anvil/core/scene.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    using contact::internal::dot;
    using contact::internal::value_of;

    /// "1, 2.5, -3" -> numbers; exactly @p count of them or an InputError.
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

    /// A direction: nonzero, returned with unit length.
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
  } // namespace

  template <int dim>
  void RigidTool<dim>::declare_parameters(ParameterHandler &prm)
  {
    const std::string zero = dim == 2 ? "0, 0" : "0, 0, 0";
    const std::string xyz  = dim == 2 ? "'x, y'" : "'x, y, z'";
    prm.declare_entry("Type", "plane", Patterns::Selection("plane|circle|arc|polyline|cylinder|sphere"),
                      "Surface of the rigid tool: in 2D plane, circle, arc or polyline; in 3D plane, "
                      "cylinder or sphere.");
    prm.declare_entry("Point", zero, Patterns::Anything(),
                      "plane: a point of the plane, " + xyz + " in mm (at zero motion).");
    prm.declare_entry("Normal", dim == 2 ? "0, 1" : "0, 0, 1", Patterns::Anything(),
                      "plane: normal " + xyz + " pointing out of the tool, towards the bodies "
                      "(any nonzero length).");
    prm.declare_entry("Center", zero, Patterns::Anything(),
                      "circle, arc, sphere: center; cylinder: a point of the axis; " + xyz +
                        " in mm (at zero motion).");
    prm.declare_entry("Radius", "1", Patterns::Double(),
                      "circle, arc, cylinder, sphere: radius in mm, > 0.");
    prm.declare_entry("Side", "outside", Patterns::Selection("outside|inside"),
                      "circle, arc, cylinder, sphere: where the bodies are, outside the circle "
                      "(a punch nose, a roller) or inside it (a ring die).");
    prm.declare_entry("Start angle", "0", Patterns::Double(),
                      "arc: angle of its first end, degrees counter-clockwise from +x.");
    prm.declare_entry("End angle", "90", Patterns::Double(),
                      "arc: angle of its second end, degrees counter-clockwise from +x; "
                      "0 < End angle - Start angle <= 360.");
    prm.declare_entry("Points", "", Patterns::Anything(),
                      "polyline: vertices 'x1, y1; x2, y2; ...' in mm (at zero motion), at least two "
                      "distinct; the bodies are on the left when walking from the first to the last.");
    prm.declare_entry("Axis", "0, 0, 1", Patterns::Anything(),
                      "cylinder (3D): direction of the axis 'x, y, z' (any nonzero length).");
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
    name      = path.substr(path.find_last_of('/') + 1);
    type_name = prm.get("Type");
    const auto entry = [&](const std::string &e) { return path + "/" + e; };

    if (dim == 2 && (type_name == "cylinder" || type_name == "sphere"))
      scene.fail(entry("Type"), "is " + type_name + ", a 3D tool: in 2D use circle, arc, plane or polyline");
    if (dim == 3 && (type_name == "circle" || type_name == "arc" || type_name == "polyline"))
      scene.fail(entry("Type"), "is " + type_name + ", a 2D tool: in 3D use plane, cylinder or sphere");

    const auto parse_radius = [&]() {
      radius = prm.get_double("Radius");
      if (!(radius > 0))
        scene.fail(entry("Radius"), "is " + Utilities::to_string(radius) + ": expected a radius > 0 (mm)");
      center         = Point<dim>(parse_vector<dim>(prm.get("Center"), scene, entry("Center"), "a center"));
      bodies_outside = prm.get("Side") == "outside";
    };

    if (type_name == "plane")
      {
        kind        = Kind::plane;
        point       = Point<dim>(parse_vector<dim>(prm.get("Point"), scene, entry("Point"), "a point"));
        unit_normal = parse_direction<dim>(prm.get("Normal"), scene, entry("Normal"), "normal");
      }
    else if (type_name == "circle" || type_name == "sphere")
      {
        kind = type_name == "circle" ? Kind::circle : Kind::sphere;
        parse_radius();
      }
    else if (type_name == "cylinder")
      {
        kind = Kind::cylinder;
        parse_radius();
        unit_axis = parse_direction<dim>(prm.get("Axis"), scene, entry("Axis"), "axis direction");
      }
    else if (type_name == "arc")
      {
        kind = Kind::arc;
        parse_radius();
        const double start = prm.get_double("Start angle"), end = prm.get_double("End angle");
        if (!(end > start) || end - start > 360)
          scene.fail(entry("End angle"), "is " + Utilities::to_string(end) + " with Start angle " +
                                           Utilities::to_string(start) +
                                           ": expected 0 < End angle - Start angle <= 360 (degrees, "
                                           "counter-clockwise)");
        start_angle  = start * numbers::PI / 180;
        angular_span = (end - start) * numbers::PI / 180;
      }
    else if (type_name == "polyline")
      {
        kind = Kind::polyline;
        vertices.clear();
        const std::string text = prm.get("Points");
        for (const auto &item : split_outside_parentheses(text, ';'))
          {
            if (item.empty())
              continue; // tolerate a trailing ';'
            const Point<dim> p(parse_vector<dim>(item, scene, entry("Points"), "';'-separated points"));
            if (!vertices.empty() && (p - vertices.back()).norm() == 0)
              scene.fail(entry("Points"), "= '" + text + "' repeats the point (" + item +
                                            ") consecutively: a segment needs a length > 0");
            vertices.push_back(p);
          }
        if (vertices.size() < 2)
          scene.fail(entry("Points"), "= '" + text + "': expected at least two distinct points " +
                                        "'x1, y1; x2, y2; ...' (mm)");
      }

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
    using std::sqrt;
    // The tool only translates: work in its own frame, y = x - u(t).
    const Tensor<1, dim>   u = displacement(t);
    Tensor<1, dim, Number> y;
    for (unsigned int d = 0; d < dim; ++d)
      y[d] = x[d] - u[d];

    // A unit vector for the degenerate cases (x at a center or a vertex),
    // where the normal is undefined.
    Tensor<1, dim, Number> fallback;
    fallback[dim - 1] = 1;

    // Distance to a point @p p, with sign +1 (p is a convex corner or an end:
    // x is on the bodies' side) or -1 (a concave corner: x is inside the tool).
    const auto to_vertex = [&](const Point<dim> &p, const double sign) {
      Tensor<1, dim, Number> d;
      for (unsigned int i = 0; i < dim; ++i)
        d[i] = y[i] - p[i];
      const Number length = sqrt(dot(d, d));
      if (value_of(length) == 0)
        {
          gap    = 0;
          normal = fallback;
          return;
        }
      gap = sign * length;
      for (unsigned int i = 0; i < dim; ++i)
        normal[i] = sign * d[i] / length;
    };

    // Circle, cylinder, sphere: r is the position relative to the center
    // (cylinder: its part normal to the axis).
    const auto to_round_surface = [&](const Tensor<1, dim, Number> &r) {
      const Number length = sqrt(dot(r, r));
      const double sign   = bodies_outside ? 1 : -1;
      gap                 = sign * (length - radius);
      if (value_of(length) == 0)
        normal = fallback;
      else
        for (unsigned int i = 0; i < dim; ++i)
          normal[i] = sign * r[i] / length;
    };

    Tensor<1, dim, Number> r;
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = y[d] - center[d];

    switch (kind)
      {
        case Kind::plane:
          {
            gap = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                gap += (y[d] - point[d]) * unit_normal[d];
                normal[d] = unit_normal[d];
              }
            return;
          }
        case Kind::circle:
        case Kind::sphere:
          to_round_surface(r);
          return;
        case Kind::cylinder:
          {
            const Number along = dot(r, unit_axis);
            for (unsigned int d = 0; d < dim; ++d)
              r[d] -= along * unit_axis[d];
            to_round_surface(r);
            return;
          }
        case Kind::arc:
          {
            // Angle from the start end, counter-clockwise, in [0, 2 pi).
            double phi = std::atan2(value_of(r[1]), value_of(r[0])) - start_angle;
            phi -= 2 * numbers::PI * std::floor(phi / (2 * numbers::PI));
            if (phi <= angular_span)
              {
                to_round_surface(r);
                return;
              }
            // Outside the arc's range: the closer end (distance to a point).
            Point<dim> ends[2];
            for (unsigned int e = 0; e < 2; ++e)
              {
                const double angle = start_angle + e * angular_span;
                ends[e]            = center;
                ends[e][0] += radius * std::cos(angle);
                ends[e][1] += radius * std::sin(angle);
              }
            double distance[2];
            for (unsigned int e = 0; e < 2; ++e)
              {
                distance[e] = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  distance[e] += std::pow(value_of(y[d]) - ends[e][d], 2);
              }
            to_vertex(ends[distance[1] < distance[0] ? 1 : 0], 1);
            return;
          }
        case Kind::polyline:
          {
            // The closest segment by value; s in [0, 1] along it.
            unsigned int closest = 0;
            double       s_closest = 0, best = std::numeric_limits<double>::max();
            for (unsigned int i = 0; i + 1 < vertices.size(); ++i)
              {
                const Tensor<1, dim> e = vertices[i + 1] - vertices[i];
                double               s = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  s += (value_of(y[d]) - vertices[i][d]) * e[d];
                s = std::min(1., std::max(0., s / e.norm_square()));
                double distance = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  distance += std::pow(value_of(y[d]) - vertices[i][d] - s * e[d], 2);
                if (distance < best)
                  best = distance, closest = i, s_closest = s;
              }
            const auto segment_normal = [&](const unsigned int i) {
              // Left of the walking direction.
              const Tensor<1, dim> e = (vertices[i + 1] - vertices[i]) / (vertices[i + 1] - vertices[i]).norm();
              Tensor<1, dim>       n;
              n[0] = -e[1];
              n[1] = e[0];
              return n;
            };
            const auto to_segment = [&](const unsigned int i) {
              const Tensor<1, dim> n = segment_normal(i);
              gap                    = 0;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  gap += (y[d] - vertices[i][d]) * n[d];
                  normal[d] = n[d];
                }
            };
            if (s_closest > 0 && s_closest < 1)
              {
                to_segment(closest);
                return;
              }
            const unsigned int k = closest + (s_closest >= 1 ? 1 : 0); // the vertex
            if (k == 0 || k + 1 == vertices.size())
              {
                to_vertex(vertices[k], 1); // an end: open, like a convex corner
                return;
              }
            // Interior vertex: convex for the bodies (on the left) if the
            // polyline turns right there, concave if it turns left.
            const Tensor<1, dim> before = vertices[k] - vertices[k - 1];
            const Tensor<1, dim> after  = vertices[k + 1] - vertices[k];
            const double         turn   = before[0] * after[1] - before[1] * after[0];
            if (turn < 0)
              to_vertex(vertices[k], 1);
            else if (turn > 0)
              to_vertex(vertices[k], -1);
            else
              to_segment(closest); // straight: the vertex is an ordinary point
            return;
          }
      }
  }

  template class RigidTool<2>;
  template class RigidTool<3>;

#define ANVIL_INSTANTIATE_PROJECT(dim, Number)                                                       \
  template void RigidTool<dim>::project<Number>(const Tensor<1, dim, Number> &, double, Number &, \
                                                Tensor<1, dim, Number> &) const;
  ANVIL_INSTANTIATE_PROJECT(2, double)
  ANVIL_INSTANTIATE_PROJECT(3, double)
  ANVIL_INSTANTIATE_PROJECT(2, Sacado::Fad::DFad<double>)
  ANVIL_INSTANTIATE_PROJECT(3, Sacado::Fad::DFad<double>)
#undef ANVIL_INSTANTIATE_PROJECT
} // namespace anvil
