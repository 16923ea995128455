#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/lac/affine_constraints.h>

#include <anvil/core/expression.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;
  template <int dim>
  class Geometry;

  /**
   * Mechanical boundary conditions of a scene, as functions of the reference
   * coordinates x, y, z and time t (muparser syntax; pi is known):
   *
   *   set Displacement = left: ux = 0, uy = 0; right: ux = 0.5*t
   *   set Pressure     = top: 10*min(t, 1)
   *   set Velocity     = top: uy = -15278          (mm/s; the face is driven)
   *
   * Displacement components not named stay free. Pressure is a follower load
   * (it acts along the current normal, on the current area; positive pushes
   * into the body).
   */
  template <int dim>
  class BoundaryConditions
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const Geometry<dim>      &geometry);

    struct PrescribedDisplacement
    {
      std::string                name;
      dealii::types::boundary_id boundary;
      dealii::ComponentMask      mask;
      std::vector<std::shared_ptr<dealii::FunctionParser<dim>>> components; // null if free
    };
    struct Pressure
    {
      std::string                                 name;
      dealii::types::boundary_id                  boundary;
      std::shared_ptr<dealii::FunctionParser<dim>> value;
    };

    const std::vector<PrescribedDisplacement> &displacements() const { return prescribed; }
    const std::vector<PrescribedDisplacement> &velocities() const { return prescribed_velocity; }
    const std::vector<Pressure>               &pressures() const { return pressure_loads; }

    /// Values of the prescribed displacement components at time @p t, per dof
    /// (deal.II's interpolate_boundary_values: a test's reference for Points).
    void interpolate(const dealii::DoFHandler<dim>            &dof_handler,
                     double                                    t,
                     std::map<dealii::types::global_dof_index, double> &values) const;

    /// Displacement increments over [t_old, t_new] of the velocity-driven
    /// components: Δt (v(t_old) + v(t_new))/2 (exact for v linear in t).
    void interpolate_velocity_increment(const dealii::DoFHandler<dim>                   &dof_handler,
                                        double                                           t_old,
                                        double                                           t_new,
                                        std::map<dealii::types::global_dof_index, double> &increments) const;

    /**
     * The prescribed components' dofs and their support points, found once
     * per dof numbering by interpolate_boundary_values' own loop (faces,
     * unit face support points through the default Q1 mapping): each step
     * then evaluates the functions only, at the same points, so the values
     * are interpolate()'s bit for bit. Each dof once, in increasing order,
     * with the point and list entry of the face that wrote it last (later
     * faces and entries overwrite earlier ones in interpolate()'s map).
     */
    struct Points
    {
      struct Dof
      {
        dealii::types::global_dof_index index;
        unsigned int                    entry, component; // in the list, of the function
        dealii::Point<dim>              point;
      };
      std::vector<Dof> displacement, velocity; // displacements(), velocities()
      bool             empty() const { return displacement.empty() && velocity.empty(); }
    };
    Points points(const dealii::DoFHandler<dim> &dof_handler) const;
    /// interpolate() at the kept points: @p values[k] for points.displacement[k].
    void values(const Points &points, double t, std::vector<double> &values) const;
    /// interpolate_velocity_increment() at the kept points, per points.velocity[k].
    void velocity_increments(const Points &points, double t_old, double t_new,
                             std::vector<double> &increments) const;

    /// Zero constraints on every prescribed component (for Newton updates).
    void make_homogeneous_constraints(const dealii::DoFHandler<dim>     &dof_handler,
                                      dealii::AffineConstraints<double> &constraints) const;

    /// Pressure on boundary @p id at reference point @p p and time @p t (0 if none).
    bool has_pressure() const { return !pressure_loads.empty(); }

  private:
    std::vector<PrescribedDisplacement> prescribed, prescribed_velocity;
    std::vector<Pressure>               pressure_loads;
  };

} // namespace anvil
