#include <anvil/contact/tool_shapes/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// An infinite circular cylinder (3D) along Axis through Center: Radius, Side.
    class Cylinder : public ToolShapeImplementation<3, Cylinder>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        tool_shapes::RoundSurface<3>::declare_parameters(prm);
        prm.declare_entry("Axis", "0, 0, 1", Patterns::Anything(),
                          "cylinder (3D): direction of the axis 'x, y, z' (any nonzero length).");
      }
      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        round.parse_parameters(prm, scene, path);
        unit_axis = tool_shapes::parse_direction<3>(prm.get("Axis"), scene, path + "/Axis",
                                                    "axis direction");
      }
      template <typename Number>
      void project_in_frame(const Tensor<1, 3, Number> &y, Number &gap, Tensor<1, 3, Number> &normal) const
      {
        // The position relative to the axis, normal to it.
        Tensor<1, 3, Number> r     = round.relative(y);
        const Number         along = contact::internal::dot(r, unit_axis);
        for (unsigned int d = 0; d < 3; ++d)
          r[d] -= along * unit_axis[d];
        round.project(r, gap, normal);
      }

    private:
      tool_shapes::RoundSurface<3> round;
      Tensor<1, 3>                 unit_axis;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(3, anvil::Cylinder, "cylinder",
                          "infinite, Radius along Axis through Center, bodies on its Side")
