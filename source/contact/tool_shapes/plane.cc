#include <anvil/contact/tool_shapes/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// A plane through `Point` with outward `Normal` (towards the bodies), 2D and 3D.
    template <int dim>
    class Plane : public ToolShapeImplementation<dim, Plane<dim>>
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        const std::string xyz = dim == 2 ? "'x, y'" : "'x, y, z'";
        prm.declare_entry("Point", dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
                          "plane: a point of the plane, " + xyz + " in mm (at zero motion).");
        prm.declare_entry("Normal", dim == 2 ? "0, 1" : "0, 0, 1", Patterns::Anything(),
                          "plane: normal " + xyz + " pointing out of the tool, towards the bodies "
                          "(any nonzero length).");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        point = Point<dim>(tool_shapes::parse_vector<dim>(prm.get("Point"), scene, path + "/Point",
                                                          "a point"));
        unit_normal = tool_shapes::parse_direction<dim>(prm.get("Normal"), scene, path + "/Normal",
                                                        "normal");
      }

      template <typename Number>
      void project_in_frame(const Tensor<1, dim, Number> &y, Number &gap,
                            Tensor<1, dim, Number> &normal) const
      {
        gap = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            gap += (y[d] - point[d]) * unit_normal[d];
            normal[d] = unit_normal[d];
          }
      }

    private:
      Point<dim>     point;
      Tensor<1, dim> unit_normal;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_TOOL_SHAPE(2, anvil::Plane<2>, "plane",
                          "a line through Point with Normal towards the bodies")
ANVIL_REGISTER_TOOL_SHAPE(3, anvil::Plane<3>, "plane", "through Point with Normal towards the bodies")
