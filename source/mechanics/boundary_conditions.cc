#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/boundary_conditions.h>

#include <iostream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // A vector function whose components are given scalar functions (or 0).
    template <int dim>
    class ComponentFunction : public Function<dim>
    {
    public:
      ComponentFunction(const std::vector<std::shared_ptr<FunctionParser<dim>>> &c, double t)
        : Function<dim>(dim, t)
        , components(c)
      {}
      double value(const Point<dim> &p, const unsigned int component) const override
      {
        if (!components[component])
          return 0.;
        components[component]->set_time(this->get_time());
        return components[component]->value(p);
      }

    private:
      const std::vector<std::shared_ptr<FunctionParser<dim>>> &components;
    };
  } // namespace

  template <int dim>
  void BoundaryConditions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry(
      "Displacement", "", Patterns::Anything(),
      "Prescribed displacements in mm: a ';'-separated list of "
      "'boundary: ux = expr, uy = expr' items (uz in 3D). Expressions in the "
      "reference coordinates x, y, z (mm) and time t (s). Unnamed components stay free.");
    prm.declare_entry(
      "Velocity", "", Patterns::Anything(),
      "Prescribed velocities in mm/s: a ';'-separated list of 'boundary: ux = expr, ...' "
      "items like Displacement (expressions in x, y, z and t); the face moves by "
      "dt (v(t_n) + v(t_n+1))/2 per step. A component may not be both here and in Displacement.");
    prm.declare_entry("Pressure", "", Patterns::Anything(),
                      "Follower pressures in MPa: a ';'-separated list of 'boundary: expr' "
                      "items. Positive pressure pushes into the body along the current normal.");
    prm.leave_subsection();
  }

  template <int dim>
  void BoundaryConditions<dim>::parse_parameters(ParameterHandler    &prm,
                                                 const Scene         &scene,
                                                 const Geometry<dim> &geometry)
  {
    prm.enter_subsection("Boundary conditions");
    const std::string displacement = prm.get("Displacement");
    const std::string pressure     = prm.get("Pressure");
    const std::string velocity     = prm.get("Velocity");
    prm.leave_subsection();

    auto parse_list = [&](const std::string &text, const std::string &dpath) {
      std::vector<PrescribedDisplacement> list;
      for (const auto &item : split_outside_parentheses(text, ';'))
        {
          if (item.empty())
            continue;
          const auto colon = item.find(':');
          if (colon == std::string::npos)
            scene.fail(dpath, "item '" + item + "': expected 'boundary: ux = expr, ...'");
          PrescribedDisplacement bc;
          bc.name     = trim(item.substr(0, colon));
          bc.boundary = geometry.boundary_id(bc.name, scene.where(dpath));
          bc.mask     = ComponentMask(dim, false);
          bc.components.resize(dim);
          for (const auto &assignment : split_outside_parentheses(item.substr(colon + 1), ','))
            {
              const auto eq = assignment.find('=');
              const std::string component =
                eq == std::string::npos ? "" : trim(assignment.substr(0, eq));
              int c = -1;
              for (unsigned int d = 0; d < dim; ++d)
                if (component == std::string("u") + "xyz"[d])
                  c = d;
              if (c < 0)
                scene.fail(dpath, "item '" + item + "': '" + assignment + "' should be " +
                                    (dim == 2 ? "ux = expr or uy = expr" : "ux, uy or uz = expr"));
              if (bc.mask[c])
                scene.fail(dpath, "item '" + item + "' sets " + component + " twice");
              bc.mask.set(c, true);
              bc.components[c] =
                parse_expression<dim>(trim(assignment.substr(eq + 1)), scene, dpath);
            }
          list.push_back(bc);
        }
      return list;
    };
    prescribed          = parse_list(displacement, "Boundary conditions/Displacement");
    prescribed_velocity = parse_list(velocity, "Boundary conditions/Velocity");
    for (const auto &v : prescribed_velocity)
      for (const auto &d : prescribed)
        if (v.boundary == d.boundary)
          for (unsigned int c = 0; c < dim; ++c)
            if (v.mask[c] && d.mask[c])
              scene.fail("Boundary conditions/Velocity",
                         "prescribes u" + std::string(1, "xyz"[c]) + " on '" + v.name +
                           "', which Boundary conditions/Displacement prescribes already");

    const std::string ppath = "Boundary conditions/Pressure";
    pressure_loads.clear();
    for (const auto &item : split_outside_parentheses(pressure, ';'))
      {
        if (item.empty())
          continue;
        const auto colon = item.find(':');
        if (colon == std::string::npos)
          scene.fail(ppath, "item '" + item + "': expected 'boundary: expr'");
        Pressure p;
        p.name     = trim(item.substr(0, colon));
        p.boundary = geometry.boundary_id(p.name, scene.where(ppath));
        p.value    = parse_expression<dim>(trim(item.substr(colon + 1)), scene, ppath);
        pressure_loads.push_back(p);
      }
  }

  template <int dim>
  void BoundaryConditions<dim>::interpolate(const DoFHandler<dim>                   &dof_handler,
                                            const double                             t,
                                            std::map<types::global_dof_index, double> &values) const
  {
    for (const auto &bc : prescribed)
      {
        ComponentFunction<dim> f(bc.components, t);
        VectorTools::interpolate_boundary_values(dof_handler, bc.boundary, f, values, bc.mask);
      }
  }

  template <int dim>
  void BoundaryConditions<dim>::interpolate_velocity_increment(
    const DoFHandler<dim>                     &dof_handler,
    const double                               t_old,
    const double                               t_new,
    std::map<types::global_dof_index, double> &increments) const
  {
    for (const auto &bc : prescribed_velocity)
      {
        std::map<types::global_dof_index, double> v_old, v_new;
        ComponentFunction<dim> f_old(bc.components, t_old), f_new(bc.components, t_new);
        VectorTools::interpolate_boundary_values(dof_handler, bc.boundary, f_old, v_old, bc.mask);
        VectorTools::interpolate_boundary_values(dof_handler, bc.boundary, f_new, v_new, bc.mask);
        for (const auto &[dof, v] : v_new)
          increments[dof] = 0.5 * (t_new - t_old) * (v + v_old[dof]);
      }
  }

  template <int dim>
  void BoundaryConditions<dim>::make_homogeneous_constraints(const DoFHandler<dim>     &dof_handler,
                                                             AffineConstraints<double> &constraints) const
  {
    for (const auto *list : {&prescribed, &prescribed_velocity})
      for (const auto &bc : *list)
        VectorTools::interpolate_boundary_values(dof_handler, bc.boundary,
                                                 Functions::ZeroFunction<dim>(dim), constraints,
                                                 bc.mask);
  }

  ANVIL_INSTANTIATE_CLASS(BoundaryConditions)
} // namespace anvil
