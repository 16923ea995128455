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

    /// Values of the prescribed displacement components at time @p t, per dof.
    void interpolate(const dealii::DoFHandler<dim>            &dof_handler,
                     double                                    t,
                     std::map<dealii::types::global_dof_index, double> &values) const;

    /// Displacement increments over [t_old, t_new] of the velocity-driven
    /// components: Δt (v(t_old) + v(t_new))/2 (exact for v linear in t).
    void interpolate_velocity_increment(const dealii::DoFHandler<dim>                   &dof_handler,
                                        double                                           t_old,
                                        double                                           t_new,
                                        std::map<dealii::types::global_dof_index, double> &increments) const;

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
