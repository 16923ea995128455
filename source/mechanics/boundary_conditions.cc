#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
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

  namespace
  {
    /**
     * The dofs interpolate_boundary_values() writes for @p list, with the
     * points it evaluates them at: its loop (deal.II 9.4,
     * vector_tools_boundary.templates.h) without the evaluation. Its writes
     * in order (entry by entry, each a call of its own; cells; faces; face
     * dofs), then the last write of each dof, which its map keeps.
     */
    template <int dim, typename Entry, typename Dof>
    std::vector<Dof> find_points(const DoFHandler<dim> &dof_handler, const std::vector<Entry> &list)
    {
      std::map<types::global_dof_index, Dof> last;
      if (list.empty())
        return {};
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      AssertThrow(fe.n_unique_faces() == 1 && fe.has_face_support_points(0) && fe.is_primitive(),
                  ExcMessage("boundary values need a primitive element with face support points"));
      FEFaceValues<dim> fe_values(get_default_linear_mapping(dof_handler.get_triangulation()), fe,
                                  Quadrature<dim - 1>(fe.get_unit_face_support_points(0)),
                                  update_quadrature_points);
      std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face(0));
      for (unsigned int e = 0; e < list.size(); ++e)
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int face_no : cell->face_indices())
              {
                const auto face = cell->face(face_no);
                if (face->boundary_id() != list[e].boundary || fe.n_dofs_per_face(face_no) == 0)
                  continue;
                fe_values.reinit(cell, face_no);
                face_dofs.resize(fe.n_dofs_per_face(face_no));
                face->get_dof_indices(face_dofs, cell->active_fe_index());
                for (unsigned int i = 0; i < face_dofs.size(); ++i)
                  {
                    const unsigned int c = fe.face_system_to_component_index(i, face_no).first;
                    if (list[e].mask[c])
                      last[face_dofs[i]] = Dof{face_dofs[i], e, c, fe_values.quadrature_point(i)};
                  }
              }
      std::vector<Dof> dofs;
      dofs.reserve(last.size());
      for (const auto &[index, dof] : last)
        dofs.push_back(dof);
      return dofs;
    }
  } // namespace

  template <int dim>
  typename BoundaryConditions<dim>::Points
  BoundaryConditions<dim>::points(const DoFHandler<dim> &dof_handler) const
  {
    Points p;
    p.displacement = find_points<dim, PrescribedDisplacement, typename Points::Dof>(dof_handler, prescribed);
    p.velocity = find_points<dim, PrescribedDisplacement, typename Points::Dof>(dof_handler, prescribed_velocity);
    return p;
  }

  template <int dim>
  void BoundaryConditions<dim>::values(const Points &points, const double t,
                                       std::vector<double> &values) const
  {
    // As ComponentFunction::value, at the same points.
    values.resize(points.displacement.size());
    for (unsigned int k = 0; k < values.size(); ++k)
      {
        const auto &dof = points.displacement[k];
        auto       &f   = *prescribed[dof.entry].components[dof.component];
        f.set_time(t);
        values[k] = f.value(dof.point);
      }
  }

  template <int dim>
  void BoundaryConditions<dim>::velocity_increments(const Points &points, const double t_old,
                                                    const double t_new,
                                                    std::vector<double> &increments) const
  {
    increments.resize(points.velocity.size());
    for (unsigned int k = 0; k < increments.size(); ++k)
      {
        const auto &dof = points.velocity[k];
        auto       &f   = *prescribed_velocity[dof.entry].components[dof.component];
        f.set_time(t_old);
        const double v_old = f.value(dof.point);
        f.set_time(t_new);
        const double v = f.value(dof.point);
        increments[k]  = 0.5 * (t_new - t_old) * (v + v_old);
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
