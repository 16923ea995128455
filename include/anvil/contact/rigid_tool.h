#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;
  template <int dim>
  class ToolShape;

  /**
   * A rigid tool (die, punch, anvil, wall): a surface that does not deform,
   * moves by a translation u(t) and has a prescribed temperature T(t). The
   * deformable bodies touch it through contact::node_to_tool().
   *
   * Surfaces (in the tool's own frame, i.e. at u = 0) are ToolShape<dim>s,
   * registered by name (contact/tool_shapes/interface.h); the built-in ones:
   *  - `plane` (2D, 3D): through `Point`, outward `Normal` (pointing to where
   *    the bodies are; need not be unit length).
   *  - `circle` (2D), `cylinder` (3D, infinite, along `Axis`), `sphere` (3D):
   *    `Center`, `Radius` > 0; `Side = outside` puts the bodies outside the
   *    circle (a punch nose, a roller), `inside` inside it (a ring die).
   *  - `arc` (2D): the part of a circle from `Start angle` to `End angle`
   *    (degrees, counter-clockwise from +x, 0 < end − start <= 360).
   *  - `polyline` (2D): `Points` "x1, y1; x2, y2; ..." with the bodies on the
   *    LEFT when walking from the first to the last point.
   *
   * All lengths in mm. The ends of an arc or a polyline behave like a convex
   * corner: a point whose closest point on the tool is an end measures its
   * distance to that end point (gap >= 0), so the tool is open there and its
   * ends must lie beyond where bodies can penetrate it.
   *
   *   subsection Contact
   *     subsection die
   *       set Type        = arc
   *       set Center      = 0, 10
   *       set Radius      = 10
   *       set Start angle = 180
   *       set End angle   = 360
   *       set Motion      = 0, -2*t
   *       set Temperature = 293 + 100*min(t, 1)
   *     end
   *   end
   */
  template <int dim>
  class RigidTool
  {
  public:
    /// Declares the entries above in the current subsection.
    static void declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Reads the current subsection; @p path (e.g. "Contact/die") names it in
     * error messages. Sets `name` to the last component of @p path. Every
     * entry the type uses is validated (InputError via Scene::fail).
     */
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene, const std::string &path);

    /// The tool's translation u(t) (mm).
    dealii::Tensor<1, dim> displacement(double t) const;

    /// The tool's temperature T(t) (K).
    double temperature(double t) const;

    /**
     * Signed distance @p gap (mm) from the current position @p x to the tool's
     * surface at time @p t (translated by u(t)): > 0 on the bodies' side, < 0
     * inside the tool's material (penetration). @p normal: the unit normal at
     * the closest point, pointing to the bodies' side; it is the gradient of
     * the gap with respect to @p x wherever that is smooth.
     *
     * Closest point: for an arc outside its angular range, or a polyline in
     * the region of a vertex, the closest point is that vertex and the normal
     * the direction from it to @p x (convex corner and ends, gap >= 0) or from
     * @p x to it (a concave corner of a polyline, the point is inside the
     * tool: gap <= 0). Which branch applies is decided by value, so that with
     * an automatic-differentiation @p Number the derivatives are those of the
     * branch taken.
     *
     * Instantiated for Number = double and Sacado::Fad::DFad<double>; a
     * caller using the latter includes <deal.II/differentiation/ad.h>.
     */
    template <typename Number>
    void project(const dealii::Tensor<1, dim, Number> &x,
                 double                                t,
                 Number                               &gap,
                 dealii::Tensor<1, dim, Number>       &normal) const;
    /// The same with the translation @p u = displacement(t) already evaluated.
    template <typename Number>
    void project_displaced(const dealii::Tensor<1, dim, Number> &x,
                           const dealii::Tensor<1, dim>         &u,
                           Number                               &gap,
                           dealii::Tensor<1, dim, Number>       &normal) const;

    /// The surface type as in the parameter file ("plane", "circle", ...).
    const std::string &type() const { return type_name; }

    std::string name;

  private:
    std::string                           type_name = "plane";
    std::shared_ptr<const ToolShape<dim>> shape; // the surface in the tool's frame

    std::vector<std::shared_ptr<dealii::FunctionParser<1>>> motion; // u_d(t), one per component
    std::shared_ptr<dealii::FunctionParser<1>>              temperature_function;
  };
} // namespace anvil
