#include <anvil/contact/tool_shapes/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// A full circle (2D): Center, Radius, Side.
    class Circle : public ToolShapeImplementation<2, Circle>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        tool_shapes::RoundSurface<2>::declare_parameters(prm);
      }
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        round.parse_parameters(prm, scene, path);
      }
      template <typename Number>
      void project_in_frame(const Tensor<1, 2, Number> &y, Number &gap, Tensor<1, 2, Number> &normal) const
      {
        round.project(round.relative(y), gap, normal);
      }

    private:
      tool_shapes::RoundSurface<2> round;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(2, anvil::Circle, "circle",
                          "Radius around Center, bodies on its Side (a punch nose, a "
                          "roller, a ring die)")
