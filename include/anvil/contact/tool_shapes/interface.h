#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <anvil/contact/ad_helpers.h>
#include <anvil/core/registry.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * The surface of a rigid tool in the tool's own frame (RigidTool adds the
   * motion). One file per shape under source/contact/tool_shapes/, registered
   * for dim 2, 3 or both with ANVIL_REGISTER_TOOL_SHAPE; a tool's `Type`
   * names one. A shape registered for the other dimension only is refused
   * with one line naming `Type` and the shapes of this dimension.
   *
   * A shape's entries sit flat in the tool's subsection (beside Type, Motion,
   * Temperature); each shape declares those it reads (a static
   * declare_parameters(), dim-templated shapes with dim-dependent defaults).
   * Entries several shapes read (Center, Radius, Side) are declared by
   * RoundSurface::declare_parameters() so that they are declared the same way.
   */
  template <int dim>
  class ToolShape
  {
  public:
    using ADNumber = contact::internal::ADNumber;

    virtual ~ToolShape() = default;

    /// The shape's own entries (none by default).
    static void declare_parameters(dealii::ParameterHandler &) {}

    /// Reads and checks the shape's entries (the tool's subsection entered);
    /// @p path (e.g. "Contact/die") names the subsection in errors.
    virtual void parse_parameters(dealii::ParameterHandler &prm,
                                  const Scene              &scene,
                                  const std::string        &path) = 0;

    /**
     * Signed distance @p gap from @p y (in the tool's frame) to the surface,
     * > 0 on the bodies' side, and the unit normal towards the bodies (the
     * gap's gradient where it is smooth); see RigidTool::project(). With
     * ADNumber the derivatives are those of the branch taken by value.
     */
    virtual void project(const dealii::Tensor<1, dim, double> &y,
                         double                               &gap,
                         dealii::Tensor<1, dim, double>       &normal) const = 0;
    virtual void project(const dealii::Tensor<1, dim, ADNumber> &y,
                         ADNumber                               &gap,
                         dealii::Tensor<1, dim, ADNumber>       &normal) const = 0;
  };

  /**
   * A shape with one template `project_in_frame<Number>(y, gap, normal)`
   * implementing both overloads of ToolShape::project() (CRTP).
   */
  template <int dim, class Derived>
  class ToolShapeImplementation : public ToolShape<dim>
  {
  public:
    using ADNumber = typename ToolShape<dim>::ADNumber;
    void project(const dealii::Tensor<1, dim, double> &y,
                 double                               &gap,
                 dealii::Tensor<1, dim, double>       &normal) const override
    {
      static_cast<const Derived &>(*this).project_in_frame(y, gap, normal);
    }
    void project(const dealii::Tensor<1, dim, ADNumber> &y,
                 ADNumber                               &gap,
                 dealii::Tensor<1, dim, ADNumber>       &normal) const override
    {
      static_cast<const Derived &>(*this).project_in_frame(y, gap, normal);
    }
  };

  template <int dim>
  using ToolShapeRegistry = Registry<ToolShape<dim>>;

  namespace tool_shapes
  {
    /// "1, 2.5, -3" -> exactly @p count numbers, or Scene::fail naming @p path and @p expected.
    std::vector<double> parse_numbers(const std::string &text,
                                      unsigned int       count,
                                      const Scene       &scene,
                                      const std::string &path,
                                      const std::string &expected);

    /// A point or vector of dim numbers (mm); @p what names it in errors.
    template <int dim>
    dealii::Tensor<1, dim> parse_vector(const std::string &text,
                                        const Scene       &scene,
                                        const std::string &path,
                                        const std::string &what);

    /// A nonzero direction, returned with unit length.
    template <int dim>
    dealii::Tensor<1, dim> parse_direction(const std::string &text,
                                           const Scene       &scene,
                                           const std::string &path,
                                           const std::string &what);

    /// The unit vector used where a normal is undefined (at a center or a vertex).
    template <int dim, typename Number>
    dealii::Tensor<1, dim, Number> fallback_normal()
    {
      dealii::Tensor<1, dim, Number> fallback;
      fallback[dim - 1] = 1;
      return fallback;
    }

    /**
     * Distance from @p y to the point @p p with sign +1 (p is a convex corner
     * or an end: y is on the bodies' side) or −1 (a concave corner: y is
     * inside the tool).
     */
    template <int dim, typename Number>
    void to_vertex(const dealii::Tensor<1, dim, Number> &y,
                   const dealii::Point<dim>             &p,
                   const double                          sign,
                   Number                               &gap,
                   dealii::Tensor<1, dim, Number>       &normal)
    {
      using std::sqrt;
      using contact::internal::dot;
      using contact::internal::value_of;
      dealii::Tensor<1, dim, Number> d;
      for (unsigned int i = 0; i < dim; ++i)
        d[i] = y[i] - p[i];
      const Number length = sqrt(dot(d, d));
      if (value_of(length) == 0)
        {
          gap    = 0;
          normal = fallback_normal<dim, Number>();
          return;
        }
      gap = sign * length;
      for (unsigned int i = 0; i < dim; ++i)
        normal[i] = sign * d[i] / length;
    }

    /**
     * What circle, arc, cylinder and sphere share: `Center`, `Radius` > 0 and
     * `Side` (bodies outside or inside), and the distance to the round surface.
     */
    template <int dim>
    struct RoundSurface
    {
      static void declare_parameters(dealii::ParameterHandler &prm);
      void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene, const std::string &path);

      /// @p r: the position relative to the center (cylinder: its part normal to the axis).
      template <typename Number>
      void project(const dealii::Tensor<1, dim, Number> &r,
                   Number                               &gap,
                   dealii::Tensor<1, dim, Number>       &normal) const
      {
        using std::sqrt;
        using contact::internal::dot;
        using contact::internal::value_of;
        const Number length = sqrt(dot(r, r));
        const double sign   = bodies_outside ? 1 : -1;
        gap                 = sign * (length - radius);
        if (value_of(length) == 0)
          normal = fallback_normal<dim, Number>();
        else
          for (unsigned int i = 0; i < dim; ++i)
            normal[i] = sign * r[i] / length;
      }

      /// y − center.
      template <typename Number>
      dealii::Tensor<1, dim, Number> relative(const dealii::Tensor<1, dim, Number> &y) const
      {
        dealii::Tensor<1, dim, Number> r;
        for (unsigned int d = 0; d < dim; ++d)
          r[d] = y[d] - center[d];
        return r;
      }

      dealii::Point<dim> center;
      double             radius         = 1;
      bool               bodies_outside = true;
    };
  } // namespace tool_shapes
} // namespace anvil

/**
 * Registers tool shape @p classname (default constructible, derived from
 * anvil::ToolShape<dim>, with a static declare_parameters(ParameterHandler &))
 * for dimension @p dim under @p name with @p documentation (it becomes part of
 * the help of a tool's `Type`). A shape for both dimensions is registered
 * twice, once per dim. At namespace scope of one .cc file.
 */
#define ANVIL_REGISTER_TOOL_SHAPE(dim, classname, name, documentation)                           \
  namespace                                                                                      \
  {                                                                                              \
    const bool ANVIL_REGISTRY_UNIQUE(anvil_tool_shape_) =                                        \
      ::anvil::ToolShapeRegistry<dim>::instance().add(                                           \
        name, documentation,                                                                     \
        []() -> std::unique_ptr<::anvil::ToolShape<dim>> {                                       \
          return std::make_unique<classname>();                                                  \
        },                                                                                       \
        [](dealii::ParameterHandler &prm) { classname::declare_parameters(prm); });              \
  }
