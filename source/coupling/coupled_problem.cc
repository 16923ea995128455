#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/coupling/coupled_problem.h>
#include <anvil/material/material_point.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void CoupledProblem<dim>::declare_parameters(ParameterHandler               &prm,
                                               const std::vector<std::string> &body_names,
                                               const std::vector<std::string> &contact_pair_names,
                                               const std::vector<std::string> &contact_tool_names)
  {
    prm.enter_subsection("Bodies");
    for (const auto &name : body_names)
      {
        prm.enter_subsection(name);
        MaterialFactory::declare_parameters(prm);
        prm.enter_subsection("Material");
        ThermalMaterial::declare_parameters(prm);
        prm.leave_subsection();
        prm.leave_subsection();
      }
    prm.leave_subsection();
    ThermalProblem<dim>::Parameters::declare_parameters(prm);
    ContactProblem<dim>::declare_parameters(prm, contact_pair_names, contact_tool_names);
    MechanicalProblem<dim>::Parameters::declare_parameters(prm);
    BoundaryConditions<dim>::declare_parameters(prm);
  }

  template <int dim>
  void CoupledProblem<dim>::parse_parameters(ParameterHandler &prm, Scene &scene,
                                             const Geometry<dim> &geometry,
                                             const bool mechanics_on, const bool heat_on,
                                             const std::string &scheme_name)
  {
    with_mechanics = mechanics_on;
    with_heat      = heat_on;
    prm.enter_subsection("Bodies");
    for (const auto &name : scene.body_names())
      {
        const auto id = geometry.body_id(name, scene.where("Bodies/Names"));
        prm.enter_subsection(name);
        materials[id] = MaterialFactory::create(prm, scene, "Bodies/" + name);
        prm.leave_subsection();
        if (with_mechanics && !(materials[id]->bulk_modulus() > 0))
          scene.fail("Bodies/" + name + "/Material/Elasticity/Young's modulus",
                     "and 'Bulk modulus' are both 0: the mechanics needs one of them > 0 "
                     "(Physics/Coupling = thermal only needs neither)");
      }
    prm.leave_subsection();
    mechanical_parameters.parse_parameters(prm, scene);

    if (!with_mechanics)
      {
        // A scheme without mechanics has nothing to apply these to: say so rather than ignore them.
        std::vector<std::string> given;
        for (const std::string entry : {"Displacement", "Velocity", "Pressure"})
          if (!trim(prm.get({"Boundary conditions"}, entry)).empty())
            given.push_back("Boundary conditions/" + entry);
        if (!trim(prm.get({"Mechanics"}, "Gravity")).empty())
          given.push_back("Mechanics/Gravity");
        if (!given.empty())
          scene.fail(given.front(), "is given, but Physics/Coupling is '" + scheme_name +
                                      "': the scene has no mechanics (remove it, or choose a "
                                      "coupled scheme)");
      }
    if (with_heat)
      {
        thermal_parameters.parse_parameters(prm, scene);
        thermal_parameters.axisymmetric = mechanical_parameters.axisymmetric;
        thermal_boundary_conditions.parse_parameters(prm, scene, geometry);
        prm.enter_subsection("Bodies");
        for (const auto &name : scene.body_names())
          {
            const auto id = geometry.body_id(name, scene.where("Bodies/Names"));
            prm.enter_subsection(name);
            prm.enter_subsection("Material");
            thermal_materials[id] =
              ThermalMaterial::parse_parameters(prm, scene, "Bodies/" + name + "/Material",
                                                materials[id]->density(),
                                                materials[id]->heat_capacity());
            prm.leave_subsection();
            prm.leave_subsection();
          }
        prm.leave_subsection();
        check_steady(scene, scheme_name);
      }
    boundary_conditions.parse_parameters(prm, scene, geometry);
    contact.parse_parameters(prm, scene, geometry);
    if (!contact.empty() && !with_mechanics)
      scene.fail("Contact/Pairs", "names contact pairs, but Physics/Coupling is '" + scheme_name +
                                    "': contact needs the mechanics");
  }

  template <int dim>
  void CoupledProblem<dim>::setup(const parallel::DistributedTriangulationBase<dim> &tria,
                                  TimerOutput &timer, const bool quiet)
  {
    triangulation = &tria;
    log_stream    = std::make_unique<ConditionalOStream>(
      std::cout, !quiet && Utilities::MPI::this_mpi_process(tria.get_communicator()) == 0);
    if (with_mechanics)
      {
        mechanical = std::make_unique<MechanicalProblem<dim>>(tria, mechanical_parameters,
                                                              boundary_conditions, materials, timer);
        if (!contact.empty())
          mechanical->set_contact(&contact);
        mechanical->setup();
      }
    if (with_heat)
      {
        thermal = std::make_unique<ThermalProblem<dim>>(tria, thermal_parameters,
                                                        thermal_boundary_conditions,
                                                        thermal_materials, timer);
        thermal->setup(0);
        if (thermal_parameters.steady || thermal_parameters.steady_initial)
          {
            const auto s = thermal->solve_steady(0);
            log_steady(thermal_parameters.steady ? "steady heat" : "steady initial temperature");
            if (!s.converged)
              initial_steady_failure = s.failure;
            thermal->commit(); // the state of t = 0 (nothing flowed yet: no heat to account)
          }
        heat_content_at_start = thermal->heat_content();
      }
  }

  template <int dim>
  void CoupledProblem<dim>::check_steady(const Scene &scene, const std::string &scheme_name) const
  {
    const auto &p = thermal_parameters;
    if (p.steady && with_mechanics)
      scene.fail("Heat/Time integration/Method",
                 "is steady, but Physics/Coupling is '" + scheme_name +
                   "': a sequence of steady states is for 'thermal only'; a coupled scene "
                   "starts from the steady field with Heat/Initial temperature field = steady");
    if (!(p.steady || p.steady_initial))
      return;
    // Only fluxes (or nothing) on the boundary: K is singular (T up to a
    // constant) and sources without an outlet have no steady state.
    bool determined = false;
    for (const auto &[id, b] : thermal_boundary_conditions.boundaries)
      determined = determined || b.temperature || b.h || b.emissivity;
    if (!determined)
      scene.fail(p.steady ? "Heat/Time integration/Method" : "Heat/Initial temperature field",
                 "is steady, but no boundary has a Temperature, Convection or Radiation "
                 "condition (Heat/Boundary conditions): the steady temperature is then not "
                 "determined (the problem is singular); give one of them");
  }

  template <int dim>
  void CoupledProblem<dim>::log_steady(const std::string &what)
  {
    // Contraction orders log(r_k+1 / r_k) / log(r_k / r_k-1): 2 for Newton
    // with the consistent tangent, 1 for a wrong one.
    const auto        &r = thermal->steady_report();
    std::ostringstream line;
    line << "  " << what << " at t = " << r.time << " s: Newton " << r.increments.size()
         << " its, |f| =" << std::scientific << std::setprecision(3);
    for (const double x : r.residuals)
      line << " " << x;
    line << " mW, contraction orders";
    for (unsigned int k = 1; k + 1 < r.residuals.size(); ++k)
      if (r.residuals[k - 1] > 0 && r.residuals[k] > 0 && r.residuals[k + 1] > 0 &&
          r.residuals[k] != r.residuals[k - 1])
        line << " " << std::fixed << std::setprecision(2)
             << std::log(r.residuals[k + 1] / r.residuals[k]) /
                  std::log(r.residuals[k] / r.residuals[k - 1]);
    line << (r.converged ? "" : " (not converged)");
    log() << line.str() << std::endl;
  }

  template <int dim>
  void CoupledProblem<dim>::connect_point_temperatures(const bool adiabatic)
  {
    point_temperature.reinit(*triangulation, mechanical->get_quadrature().size());
    mechanical->set_temperature_field(
      [this](const typename Triangulation<dim>::active_cell_iterator &cell, std::vector<double> &T) {
        const auto values = point_temperature[cell];
        std::copy(values.begin(), values.end(), T.begin());
      },
      adiabatic);
  }

  template <int dim>
  void CoupledProblem<dim>::connect_heat_sources()
  {
    mechanical->keep_heat_sources();
    thermal->set_heat_source([this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                                    const unsigned int q) { return mechanical->heat_source(cell, q); });
    if (!contact.empty() && contact.has_heat())
      {
        // Contact conductance and frictional heat (seed eq. 30–34).
        contact.setup_heat(thermal->get_dof_handler());
        const ThermalProblem<dim> *heat = thermal.get();
        thermal->set_exchange(contact.heat_exchange(
          [heat](const types::global_dof_index i) { return heat->is_constrained(i); }));
      }
  }

  template <int dim>
  void CoupledProblem<dim>::connect_fields(const bool adiabatic)
  {
    connect_point_temperatures(adiabatic);
    point_temperatures_from_heat_field();
    mechanical->set_initial_point_temperatures(point_temperature.raw());
    connect_heat_sources();
  }

  template <int dim>
  void CoupledProblem<dim>::restarted()
  {
    if (thermal && mechanical)
      point_temperatures_from_heat_field();
  }

  template <int dim>
  void CoupledProblem<dim>::point_temperatures_from_heat_field()
  {
    // T(x_q) = Σ_j T_j φ_j(x_q) per owned cell: one small matrix-vector
    // product, summed as FEValues::get_function_values does (the same bits),
    // from a table made once per layout of the ghosted temperature.
    const Quadrature<dim>   &quadrature = mechanical->get_quadrature();
    const DoFHandler<dim>   &dof_handler = thermal->get_dof_handler();
    const unsigned int       n_q = quadrature.size(), n_dofs = dof_handler.get_fe().n_dofs_per_cell();
    const auto              &T   = thermal->temperature().trilinos_vector();
    const Epetra_BlockMap   &map = T.Map();
    PointInterpolation      &table = point_interpolation;
    const auto same_layout = [&]() {
      if (!table.map || table.local_dofs.size() !=
                          std::size_t(triangulation->n_locally_owned_active_cells()) * n_dofs)
        return false;
      if (map.DataPtr() == table.map->DataPtr())
        return true;
      const int n = map.NumMyElements();
      if (table.map->NumMyElements() != n)
        return false;
      for (int i = 0; i < n; ++i)
        if (map.GID64(i) != table.map->GID64(i))
          return false;
      return true;
    };
    if (!same_layout())
      {
        table.shape.assign(n_dofs * n_q, 0.);
        table.local_dofs.clear();
        FEValues<dim> values(mechanical->get_mapping(), dof_handler.get_fe(), quadrature, update_values);
        std::vector<types::global_dof_index> dofs(n_dofs);
        bool                                 first = true;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              if (first)
                {
                  values.reinit(cell);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    for (unsigned int k = 0; k < n_q; ++k)
                      table.shape[j * n_q + k] = values.shape_value(j, k);
                  first = false;
                }
              cell->get_dof_indices(dofs);
              for (const auto i : dofs)
                {
                  const int lid = map.LID(static_cast<TrilinosWrappers::types::int_type>(i));
                  AssertThrow(lid >= 0, ExcInternalError());
                  table.local_dofs.push_back(lid);
                }
            }
        table.map = std::make_unique<Epetra_BlockMap>(map);
      }
    const double *const array = T[0];
    const double       *shape = table.shape.data();
    const int          *local = table.local_dofs.data();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          auto out = point_temperature[cell];
          std::fill(out.begin(), out.end(), 0.);
          for (unsigned int j = 0; j < n_dofs; ++j)
            {
              const double value = array[local[j]];
              if (value == 0)
                continue;
              for (unsigned int k = 0; k < n_q; ++k)
                out[k] += value * shape[j * n_q + k];
            }
          local += n_dofs;
        }
  }

  template <int dim>
  bool CoupledProblem<dim>::solve_mechanics(const double t_old, const double t_new,
                                            const bool again, StepReport<dim> &report)
  {
    const double start = MPI_Wtime();
    auto         r     = mechanical->solve_step(t_old, t_new, again);
    const double limit = mechanical_parameters.maximum_plastic_increment;
    if (r.converged && limit > 0 && mechanical->largest_plastic_increment() > limit)
      {
        r.converged = false;
        r.failure   = "the plastic strain grew by " +
                    Utilities::to_string(mechanical->largest_plastic_increment(), 3) +
                    " at a point (limit " + Utilities::to_string(limit) + ")";
      }
    if (r.converged && !contact.empty() &&
        contact.last_max_penetration() > contact.maximum_penetration())
      {
        r.converged = false;
        r.failure   = "contact penetration " +
                    Utilities::to_string(contact.last_max_penetration(), 3) +
                    " mm exceeds Contact/Maximum penetration = " +
                    Utilities::to_string(contact.maximum_penetration(), 3) +
                    " mm (raise the penalty, or the limit)";
      }
    report.mechanical_wall += MPI_Wtime() - start;
    report.mechanical_solves.push_back(r);
    return r.converged;
  }

  template <int dim>
  bool CoupledProblem<dim>::solve_heat(const double t_old, const double t_new,
                                       StepReport<dim> &report)
  {
    const double start = MPI_Wtime();
    if (mechanical)
      thermal->set_configuration(mechanical->get_dof_handler(), mechanical->displacement());
    if (!contact.empty() && contact.has_heat())
      contact.prepare_heat(t_new - t_old);
    const auto s = thermal->solve_step(t_old, t_new);
    if (thermal_parameters.steady)
      log_steady("steady heat");
    report.thermal += s;
    report.thermal_wall += MPI_Wtime() - start;
    return s.converged;
  }

  template <int dim>
  void CoupledProblem<dim>::revert()
  {
    if (thermal)
      thermal->revert();
    if (mechanical)
      mechanical->revert_step();
    if (thermal && mechanical)
      point_temperatures_from_heat_field();
  }

  template <int dim>
  void CoupledProblem<dim>::commit(const double time_step)
  {
    if (thermal)
      {
        if (mechanical)
          {
            // The step's heat made by the mechanics (eq. 21–25) and by contact (eq. 31–33).
            const double source = thermal->integrate(
              [this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                     const unsigned int q) { return mechanical->heat_source(cell, q); });
            const double thermoelastic = thermal->integrate(
              [this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                     const unsigned int q) { return mechanical->thermoelastic_source(cell, q); });
            audit.plastic += time_step * (source - thermoelastic);
            audit.thermoelastic += time_step * thermoelastic;
            if (!contact.empty() && contact.has_heat())
              audit.contact +=
                contact.account_heat(thermal->old_temperature(), thermal->temperature(), time_step);
          }
        thermal->commit();
        if (mechanical)
          point_temperatures_from_heat_field();
      }
    if (mechanical)
      mechanical->commit_step();
  }

  template <int dim>
  typename CoupledProblem<dim>::HeatBalance CoupledProblem<dim>::heat_balance() const
  {
    HeatBalance b;
    b.content = thermal->heat_content();
    b.change  = b.content - heat_content_at_start;
    for (const auto &[id, q] : thermal->boundary_heat_flow())
      b.boundary += q;
    b.plastic       = audit.plastic;
    b.thermoelastic = audit.thermoelastic;
    b.source        = thermal->source_heat() - b.plastic - b.thermoelastic;
    b.contact       = audit.contact;
    const double residual = b.change - b.boundary - thermal->source_heat() - b.contact;
    const double scale    = std::max({std::abs(b.change), std::abs(b.boundary),
                                      std::abs(thermal->source_heat()), std::abs(b.contact), 1e-300});
    b.error = std::abs(residual) / scale;
    return b;
  }

  template <int dim>
  Vector<double> CoupledProblem<dim>::cell_temperature() const
  {
    if (thermal)
      return thermal->cell_mean_temperature();
    Vector<double> T;
    if (point_temperature.empty())
      return T;
    T.reinit(triangulation->n_active_cells());
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto values = point_temperature[cell];
          double     sum    = 0;
          for (const double x : values)
            sum += x;
          T[cell->active_cell_index()] = sum / values.size();
        }
    return T;
  }

  ANVIL_INSTANTIATE_CLASS(CoupledProblem)
} // namespace anvil
