#include <anvil/contact/tool_shapes/interface.h>
#include <anvil/core/scene.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * A polyline (2D) through `Points`, the bodies on its left when walking
     * from the first point to the last. Its ends behave like convex corners
     * (open); an interior vertex is a convex or a concave corner.
     */
    class Polyline : public ToolShapeImplementation<2, Polyline>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Points", "", Patterns::Anything(),
                          "polyline: vertices 'x1, y1; x2, y2; ...' in mm (at zero motion), at least "
                          "two distinct; the bodies are on the left when walking from the first to "
                          "the last.");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        const std::string entry = path + "/Points";
        vertices.clear();
        const std::string text = prm.get("Points");
        for (const auto &item : split_outside_parentheses(text, ';'))
          {
            if (item.empty())
              continue; // tolerate a trailing ';'
            const Point<2> p(tool_shapes::parse_vector<2>(item, scene, entry, "';'-separated points"));
            if (!vertices.empty() && (p - vertices.back()).norm() == 0)
              scene.fail(entry, "= '" + text + "' repeats the point (" + item +
                                  ") consecutively: a segment needs a length > 0");
            vertices.push_back(p);
          }
        if (vertices.size() < 2)
          scene.fail(entry, "= '" + text + "': expected at least two distinct points " +
                              "'x1, y1; x2, y2; ...' (mm)");
      }

      template <typename Number>
      void project_in_frame(const Tensor<1, 2, Number> &y, Number &gap, Tensor<1, 2, Number> &normal) const
      {
        using contact::internal::value_of;
        constexpr int dim = 2;
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
          const Tensor<1, dim> e =
            (vertices[i + 1] - vertices[i]) / (vertices[i + 1] - vertices[i]).norm();
          Tensor<1, dim> n;
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
            tool_shapes::to_vertex(y, vertices[k], 1., gap, normal); // an end: open, like a convex corner
            return;
          }
        // Interior vertex: convex for the bodies (on the left) if the
        // polyline turns right there, concave if it turns left.
        const Tensor<1, dim> before = vertices[k] - vertices[k - 1];
        const Tensor<1, dim> after  = vertices[k + 1] - vertices[k];
        const double         turn   = before[0] * after[1] - before[1] * after[0];
        if (turn < 0)
          tool_shapes::to_vertex(y, vertices[k], 1., gap, normal);
        else if (turn > 0)
          tool_shapes::to_vertex(y, vertices[k], -1., gap, normal);
        else
          to_segment(closest); // straight: the vertex is an ordinary point
      }

    private:
      std::vector<Point<2>> vertices;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(2, anvil::Polyline, "polyline",
                          "through Points, the bodies on its left walking from the first "
                          "point to the last; open at its ends")
