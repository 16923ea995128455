#include <anvil/contact/tool_shapes/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// A sphere (3D): Center, Radius, Side.
    class Sphere : public ToolShapeImplementation<3, Sphere>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        tool_shapes::RoundSurface<3>::declare_parameters(prm);
      }
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        round.parse_parameters(prm, scene, path);
      }
      template <typename Number>
      void project_in_frame(const Tensor<1, 3, Number> &y, Number &gap, Tensor<1, 3, Number> &normal) const
      {
        round.project(round.relative(y), gap, normal);
      }

    private:
      tool_shapes::RoundSurface<3> round;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(3, anvil::Sphere, "sphere",
                          "Radius around Center, bodies on its Side")
