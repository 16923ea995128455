#include <deal.II/base/utilities.h>

#include <anvil/contact/tool_shapes/interface.h>
#include <anvil/core/scene.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * The part of a circle (2D) from `Start angle` to `End angle` (degrees,
     * counter-clockwise from +x). Outside its angular range the closest point
     * is the closer end, which behaves like a convex corner (gap >= 0).
     */
    class Arc : public ToolShapeImplementation<2, Arc>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        tool_shapes::RoundSurface<2>::declare_parameters(prm);
        prm.declare_entry("Start angle", "0", Patterns::Double(),
                          "arc: angle of its first end, degrees counter-clockwise from +x.");
        prm.declare_entry("End angle", "90", Patterns::Double(),
                          "arc: angle of its second end, degrees counter-clockwise from +x; "
                          "0 < End angle - Start angle <= 360.");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        round.parse_parameters(prm, scene, path);
        const double start = prm.get_double("Start angle"), end = prm.get_double("End angle");
        if (!(end > start) || end - start > 360)
          scene.fail(path + "/End angle", "is " + Utilities::to_string(end) + " with Start angle " +
                                            Utilities::to_string(start) +
                                            ": expected 0 < End angle - Start angle <= 360 (degrees, "
                                            "counter-clockwise)");
        start_angle  = start * numbers::PI / 180;
        angular_span = (end - start) * numbers::PI / 180;
      }

      template <typename Number>
      void project_in_frame(const Tensor<1, 2, Number> &y, Number &gap, Tensor<1, 2, Number> &normal) const
      {
        using contact::internal::value_of;
        const Tensor<1, 2, Number> r = round.relative(y);
        // Angle from the start end, counter-clockwise, in [0, 2 pi).
        double phi = std::atan2(value_of(r[1]), value_of(r[0])) - start_angle;
        phi -= 2 * numbers::PI * std::floor(phi / (2 * numbers::PI));
        if (phi <= angular_span)
          {
            round.project(r, gap, normal);
            return;
          }
        // Outside the arc's range: the closer end (distance to a point).
        Point<2> ends[2];
        for (unsigned int e = 0; e < 2; ++e)
          {
            const double angle = start_angle + e * angular_span;
            ends[e]            = round.center;
            ends[e][0] += round.radius * std::cos(angle);
            ends[e][1] += round.radius * std::sin(angle);
          }
        double distance[2];
        for (unsigned int e = 0; e < 2; ++e)
          {
            distance[e] = 0;
            for (unsigned int d = 0; d < 2; ++d)
              distance[e] += std::pow(value_of(y[d]) - ends[e][d], 2);
          }
        tool_shapes::to_vertex(y, ends[distance[1] < distance[0] ? 1 : 0], 1., gap, normal);
      }

    private:
      tool_shapes::RoundSurface<2> round;
      double                       start_angle = 0, angular_span = 0; // radians
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(2, anvil::Arc, "arc",
                          "the part of the circle of Radius around Center from Start angle to End angle "
                          "(degrees, counter-clockwise), bodies on its Side; open at its ends")
