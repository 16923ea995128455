#include <deal.II/base/multithread_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/input_error.h>
#include <anvil/core/simulator.h>
#include <anvil/material/material_point.h>

#include <deal.II/fe/fe_values.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void Simulator<dim>::declare_parameters(ParameterHandler               &prm,
                                          const std::vector<std::string> &body_names,
                                          const std::vector<std::string> &contact_pair_names,
                                          const std::vector<std::string> &contact_tool_names)
  {
    Scene::declare_shape_parameters(prm);
    prm.enter_subsection("Bodies");
    for (const auto &name : body_names)
      {
        prm.enter_subsection(name);
        MaterialFactory::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    prm.enter_subsection("Bodies");
    for (const auto &name : body_names)
      {
        prm.enter_subsection(name);
        prm.enter_subsection("Material");
        ThermalMaterial::declare_parameters(prm);
        prm.leave_subsection();
        prm.leave_subsection();
      }
    prm.leave_subsection();

    prm.enter_subsection("Physics");
    prm.declare_entry(
      "Coupling", "mechanical only",
      Patterns::Selection(
        "mechanical only|thermal only|isothermal split|adiabatic split|iterated staggered"),
      "Which physics the scene solves and how they are coupled (seed sec. 2.2). "
      "mechanical only: no temperature field and no ARKode object (Mechanics/Temperature is "
      "the uniform temperature); thermal only: the heat equation on the undeformed bodies, no "
      "mechanics; isothermal split: mechanics at the temperature of the last thermal phase, "
      "then heat at the new geometry with the step's mechanical heat sources (seed "
      "sec. 2.2.1); adiabatic split (Armero & Simo 1992, seed sec. 2.2.2): as the isothermal "
      "split, but each point carries its own adiabatic temperature change in the mechanical "
      "phase, rho c dT = dt (chi W_irr + W_thel); iterated staggered: the two phases repeated "
      "within the step, the mechanics at the end-of-step temperature, until the temperature "
      "changes by less than Staggered tolerance (the accuracy reference for the splits).");
    prm.declare_entry("Staggered tolerance", "0", Patterns::Double(0),
                      "iterated staggered: largest change of a nodal temperature between two "
                      "iterations at which the step is converged, K. 0: automatic, ten times "
                      "what the heat integration resolves (Heat/Time integration/Relative "
                      "tolerance x max T + Absolute tolerance); a smaller value is raised to "
                      "that (the iteration cannot converge below the integrator's own error) "
                      "and a note says so.");
    prm.declare_entry("Staggered iterations", "30", Patterns::Integer(1),
                      "iterated staggered: iterations before the step is cut back.");
    prm.leave_subsection();
    ThermalProblem<dim>::Parameters::declare_parameters(prm);

    Geometry<dim>::declare_parameters(prm);
    ContactProblem<dim>::declare_parameters(prm, contact_pair_names, contact_tool_names);
    MechanicalProblem<dim>::Parameters::declare_parameters(prm);
    BoundaryConditions<dim>::declare_parameters(prm);

    prm.enter_subsection("Time");
    prm.declare_entry("End time", "1", Patterns::Double(0), "End of the simulated interval, s.");
    prm.declare_entry("Time step", "0.1", Patterns::Double(0), "First time step, s.");
    prm.declare_entry("Minimum time step", "0", Patterns::Double(0),
                      "Smallest step the cut-back may reach, s; 0 means Time step / 1024.");
    prm.declare_entry("Maximum time step", "0", Patterns::Double(0),
                      "Largest step the re-growth may reach, s; 0 means Time step.");
    prm.declare_entry("Growth factor", "1.5", Patterns::Double(1),
                      "Factor by which the step grows after an easy step (dimensionless).");
    prm.declare_entry("Easy step iterations", "5", Patterns::Integer(0),
                      "A step that converged in at most this many Newton iterations is easy.");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "", Patterns::Anything(),
                      "Where fields, histories and summary.json go; empty means "
                      "output/<scene name> in the working directory.");
    prm.declare_entry("Field interval", "1", Patterns::Integer(0),
                      "Write VTU fields every this many steps (0: only the first and last).");
    prm.declare_entry("Probes", "", Patterns::Anything(),
                      "Named points of the reference configuration, mm: "
                      "'name: x, y[, z]; name2: ...'. Their displacement and stress are "
                      "written to probes.csv.");
    prm.declare_entry("Quantities of interest", "", Patterns::Anything(),
                      "Named results written to summary.json at the end: 'name: expr; ...' with "
                      "expr one of reaction(boundary, x|y|z) [N], probe(name, ux|uy|uz|<field>), "
                      "max(<field>), min(<field>), mean(<field>[, body]), contact(pair, "
                      "x|y|z|normal|tangential|friction_work|active_nodes|sliding_nodes|"
                      "max_penetration) [N, N mm, mm], optionally followed by '+ c' or '- c' "
                      "(e.g. 'dT: mean(temperature, upper) - 300'); <field> is a cell field: "
                      "stress_xx..stress_zz, von_mises, pressure [MPa], J, "
                      "equivalent_plastic_strain, temperature [K] (heat scenes).");
    prm.declare_entry("Checkpoint interval", "0", Patterns::Integer(0),
                      "Write a checkpoint (output/<dir>/checkpoint) every this many steps; one is "
                      "always written at the end and when a run stops on a failure.");
    prm.declare_entry("Restart from", "", Patterns::Anything(),
                      "A checkpoint directory to resume from (its time, state and histories); "
                      "empty: start at t = 0. The scene must be the one that wrote it (the "
                      "number of processes may differ).");
    prm.declare_entry("Verbosity", "normal", Patterns::Selection("normal|quiet"),
                      "normal: one line per step and a timing table; quiet: errors only.");
    prm.leave_subsection();
  }

  template <int dim>
  Simulator<dim>::Simulator(Scene &scene, MPI_Comm communicator)
    : scene(scene)
    , mpi_communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , triangulation(communicator)
  {
    auto &prm = scene.parameters();
    geometry.parse_parameters(prm, scene);

    // Bodies: every mesh body needs a material, every listed body must exist.
    for (const auto &[name, id] : geometry.body_names())
      if (std::find(scene.body_names().begin(), scene.body_names().end(), name) ==
          scene.body_names().end())
        scene.fail("Bodies/Names", "does not list the mesh body '" + name +
                                     "' (the mesh has: " + geometry.list_body_names() + ")");
    prm.enter_subsection("Bodies");
    for (const auto &name : scene.body_names())
      {
        const auto id = geometry.body_id(name, scene.where("Bodies/Names"));
        prm.enter_subsection(name);
        materials[id] = MaterialFactory::create(prm, scene, "Bodies/" + name);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    mechanics_parameters.parse_parameters(prm, scene);
    prm.enter_subsection("Physics");
    coupling                  = prm.get("Coupling");
    staggered_tolerance       = prm.get_double("Staggered tolerance");
    max_staggered_iterations  = prm.get_integer("Staggered iterations");
    prm.leave_subsection();
    heat      = coupling != "mechanical only";
    mechanics = coupling != "thermal only";
    if (!mechanics)
      {
        // A thermal-only scene has no mechanics to apply these to: say so rather than ignore them.
        std::vector<std::string> given;
        for (const std::string entry : {"Displacement", "Velocity", "Pressure"})
          if (!trim(prm.get({"Boundary conditions"}, entry)).empty())
            given.push_back("Boundary conditions/" + entry);
        if (!trim(prm.get({"Mechanics"}, "Gravity")).empty())
          given.push_back("Mechanics/Gravity");
        if (!given.empty())
          scene.fail(given.front(), "is given, but Physics/Coupling is 'thermal only': the scene "
                                    "has no mechanics (remove it, or choose a coupled scheme)");
      }
    if (heat)
      {
        thermal_parameters.parse_parameters(prm, scene);
        thermal_parameters.axisymmetric = mechanics_parameters.axisymmetric;
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
      }
    boundary_conditions.parse_parameters(prm, scene, geometry);
    contact.parse_parameters(prm, scene, geometry);
    if (!contact.empty() && !mechanics)
      scene.fail("Contact/Pairs", "names contact pairs, but Physics/Coupling is 'thermal only': "
                                  "contact needs the mechanics");

    prm.enter_subsection("Time");
    time.end_time          = prm.get_double("End time");
    time.time_step         = prm.get_double("Time step");
    time.minimum_time_step = prm.get_double("Minimum time step");
    time.maximum_time_step = prm.get_double("Maximum time step");
    time.growth_factor     = prm.get_double("Growth factor");
    time.easy_iterations   = prm.get_integer("Easy step iterations");
    prm.leave_subsection();
    if (!(time.time_step > 0))
      scene.fail("Time/Time step", "must be > 0 s");
    if (time.minimum_time_step == 0)
      time.minimum_time_step = time.time_step / 1024;
    if (time.maximum_time_step == 0)
      time.maximum_time_step = time.time_step;
    if (time.minimum_time_step > time.time_step)
      scene.fail("Time/Minimum time step", "must not exceed Time step");

    parse_output(prm, scene);
  }

  template <int dim>
  Simulator<dim>::~Simulator() = default;

  template <int dim>
  bool Simulator<dim>::run()
  {
    wall_start = MPI_Wtime();
    timer = std::make_unique<TimerOutput>(mpi_communicator, pcout, TimerOutput::never,
                                          TimerOutput::wall_times);
    {
      TimerOutput::Scope t(*timer, "Mesh");
      if (restart_directory.empty())
        geometry.create(triangulation);
      else
        {
          geometry.create_coarse(triangulation);
          triangulation.load(restart_directory + "/mesh");
          geometry.finish_loaded(triangulation);
        }
    }
    if (mechanics)
      {
        mechanical = std::make_unique<MechanicalProblem<dim>>(triangulation, mechanics_parameters,
                                                              boundary_conditions, materials, *timer);
        if (!contact.empty())
          mechanical->set_contact(&contact);
        mechanical->setup();
      }
    if (heat)
      {
        thermal = std::make_unique<ThermalProblem<dim>>(triangulation, thermal_parameters,
                                                        thermal_boundary_conditions,
                                                        thermal_materials, *timer);
        thermal->setup(0);
        initial_heat_content = thermal->heat_content();
      }
    if (heat && mechanics)
      {
        update_point_temperatures();
        mechanical->set_initial_point_temperatures(point_temperature);
        mechanical->set_temperature_field(
          [this](const typename Triangulation<dim>::active_cell_iterator &cell,
                 std::vector<double> &T) { mechanics_temperatures(cell, T); },
          coupling == "adiabatic split");
        thermal->set_heat_source([this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                                        const unsigned int q) {
          return mechanical->heat_source(cell, q);
        });
        if (!contact.empty() && contact.has_heat())
          {
            // Contact conductance and frictional heat (seed eq. 30–34).
            contact.setup_heat(thermal->get_dof_handler());
            thermal->set_exchange(contact.heat_exchange(*thermal));
          }
      }
    double t  = 0;
    double dt = time.time_step;
    if (!restart_directory.empty())
      {
        read_checkpoint(t, dt);
        if (heat && mechanics)
          update_point_temperatures();
      }
    double last_accepted_step = dt;

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::filesystem::create_directories(output_dir + "/fields");
    MPI_Barrier(mpi_communicator);
    if (!quiet)
      {
        pcout << "anvil: " << scene.filename() << ", " << dim << "D, "
              << triangulation.n_global_active_cells() << " cells, ";
        if (mechanical)
          pcout << mechanical->n_dofs() << " displacement DoFs, ";
        if (thermal)
          pcout << thermal->n_dofs() << " temperature DoFs, ";
        pcout << coupling << ", " << Utilities::MPI::n_mpi_processes(mpi_communicator)
              << " process(es) x " << MultithreadInfo::n_threads() << " thread(s) -> "
              << output_dir << std::endl;
      }

    open_histories();
    if (restart_directory.empty())
      {
        write_histories(0, 0);
        write_fields(0, 0);
      }
    const double eps = 1e-12 * time.end_time;
    std::string  status = "completed";
    while (t < time.end_time - eps)
      {
        const double step   = std::min(dt, time.end_time - t);
        CoupledStep  result = advance(t, t + step);
        if (!result.converged)
          {
            ++n_cut_backs;
            dt = step / 2;
            if (!quiet)
              pcout << "  step at t = " << t + step << " s failed: " << result.failure
                    << "; cutting back to dt = " << dt << " s" << std::endl;
            if (dt < time.minimum_time_step * (1 - 1e-12))
              {
                status = "failed at t = " + Utilities::to_string(t + step) + " s: " +
                         result.failure + "; minimum time step " +
                         Utilities::to_string(time.minimum_time_step) + " s reached";
                write_fields(t, n_steps);
                // Resume with the step of the last accepted one, not the cut one.
                write_checkpoint(t, last_accepted_step);
                write_summary(status);
                failure_reason = status + " (last converged state and a checkpoint written to " +
                                 output_dir + ")";
                return false;
              }
            continue;
          }

        // Accept: the heat balance of the step, then both halves commit.
        if (thermal)
          {
            if (mechanical)
              {
                const double source = thermal->integrate(
                  [this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                         const unsigned int q) { return mechanical->heat_source(cell, q); });
                const double thermoelastic = thermal->integrate(
                  [this](const typename DoFHandler<dim>::active_cell_iterator &cell,
                         const unsigned int q) { return mechanical->thermoelastic_source(cell, q); });
                heat_audit.plastic += step * (source - thermoelastic);
                heat_audit.thermoelastic += step * thermoelastic;
                if (!contact.empty() && contact.has_heat())
                  heat_audit.contact +=
                    contact.account_heat(thermal->old_temperature(), thermal->temperature(), step);
              }
            thermal->commit();
            if (mechanical)
              update_point_temperatures();
          }
        if (mechanical)
          mechanical->commit_step();
        last_accepted_step = step;
        t            = t + step;
        current_time = t;
        ++n_steps;
        write_histories(t, n_steps);
        if (thermal)
          {
            const auto &a = result.thermal;
            thermal_csv.add_row({double(n_steps), t, step, double(a.internal_steps),
                                 double(a.attempted_steps), double(a.error_test_failures),
                                 double(a.nonlinear_iterations), double(a.nonlinear_failures),
                                 double(a.linear_setups), double(a.linear_solves),
                                 double(a.linear_iterations), double(a.mass_solves),
                                 double(a.rhs_evaluations), a.last_internal_step,
                                 double(result.staggered_iterations), result.staggered_change,
                                 result.contraction, result.mechanical_wall, result.thermal_wall});
          }
        const bool last = t >= time.end_time - eps;
        if (last || (output_interval > 0 && n_steps % output_interval == 0))
          write_fields(t, n_steps);
        if (last || (checkpoint_interval > 0 && n_steps % checkpoint_interval == 0))
          write_checkpoint(t, dt);

        if (!quiet)
          {
            const double elapsed = MPI_Wtime() - wall_start;
            const double eta     = t > 0 ? elapsed / t * (time.end_time - t) : 0;
            std::ostringstream line;
            line << "step " << std::setw(5) << n_steps << "  t = " << std::scientific
                 << std::setprecision(4) << t << " s  dt = " << std::setprecision(2) << step << " s";
            if (mechanical)
              line << "  Newton " << std::setw(2) << result.mechanics.iterations << " |R| "
                   << std::setprecision(1) << result.mechanics.residuals.front() << " -> "
                   << result.mechanics.residuals.back() << " N";
            if (thermal)
              line << "  heat " << result.thermal.internal_steps << " steps";
            if (result.staggered_iterations > 0)
              line << "  staggered " << result.staggered_iterations << " its, dT "
                   << std::setprecision(1) << result.staggered_change << " K, contraction "
                   << std::setprecision(2) << result.contraction;
            line << "  ETA " << std::fixed << std::setprecision(1) << eta << " s";
            pcout << line.str() << std::endl;
          }
        const unsigned int effort =
          mechanical ? result.mechanics.iterations : 0;
        if (effort <= time.easy_iterations &&
            (!thermal || result.thermal.error_test_failures + result.thermal.nonlinear_failures == 0))
          dt = std::min(step * time.growth_factor, time.maximum_time_step);
        else
          dt = step;
      }

    evaluate_quantities();
    write_summary(status);
    if (!quiet)
      {
        timer->print_summary();
        for (const auto &[name, value] : qoi_values)
          pcout << "  " << name << " = " << std::setprecision(10) << value << std::endl;
      }
    return true;
  }

  template <int dim>
  typename Simulator<dim>::CoupledStep Simulator<dim>::advance(const double t_old, const double t_new)
  {
    CoupledStep result;
    // Both halves back to tₙ (and the points' temperature to Tₙ).
    auto fail = [&](const std::string &why) {
      if (thermal)
        thermal->revert();
      if (mechanical)
        mechanical->revert_step();
      if (thermal && mechanical)
        update_point_temperatures();
      result.converged = false;
      result.failure   = why;
      return result;
    };
    auto solve_mechanics = [&](const bool again = false) {
      const double start = MPI_Wtime();
      auto         r     = mechanical->solve_step(t_old, t_new, again);
      if (r.converged && mechanics_parameters.maximum_plastic_increment > 0 &&
          mechanical->largest_plastic_increment() > mechanics_parameters.maximum_plastic_increment)
        {
          r.converged = false;
          r.failure   = "the plastic strain grew by " +
                      Utilities::to_string(mechanical->largest_plastic_increment(), 3) +
                      " at a point (limit " +
                      Utilities::to_string(mechanics_parameters.maximum_plastic_increment) + ")";
        }
      if (r.converged && !contact.empty() &&
          contact.last_max_penetration() > contact.maximum_penetration())
        {
          r.converged = false;
          r.failure   = "contact penetration " + Utilities::to_string(contact.last_max_penetration(), 3) +
                      " mm exceeds Contact/Maximum penetration = " +
                      Utilities::to_string(contact.maximum_penetration(), 3) +
                      " mm (raise the penalty, or the limit)";
        }
      n_newton += r.iterations;
      n_linear += r.linear_iterations;
      for (unsigned int k = 0; k < r.residuals.size(); ++k)
        newton_csv.add_row({double(n_steps + 1), t_new, double(k), r.residuals[k],
                            k < r.increments.size() ? r.increments[k] : 0.,
                            k < r.line_search_steps.size() ? r.line_search_steps[k] : 1.,
                            r.converged ? 1. : 0.});
      result.mechanical_wall += MPI_Wtime() - start;
      result.mechanics = r;
      return r.converged;
    };
    auto solve_heat = [&]() {
      const double start = MPI_Wtime();
      if (mechanical)
        thermal->set_configuration(mechanical->get_dof_handler(), mechanical->displacement());
      if (!contact.empty() && contact.has_heat())
        contact.prepare_heat(t_new - t_old);
      const auto s = thermal->solve_step(t_old, t_new);
      result.thermal += s;
      n_thermal_steps += s.internal_steps;
      n_thermal_nonlinear += s.nonlinear_iterations;
      result.thermal_wall += MPI_Wtime() - start;
      return s.converged;
    };

    if (mechanical && !solve_mechanics())
      return fail(result.mechanics.failure);
    if (!thermal)
      return result;
    if (!solve_heat())
      return fail("heat: " + result.thermal.failure);
    if (coupling != "iterated staggered")
      return result;

    // Iterated staggered: the mechanics again at the end-of-step temperature
    // T^(k), the heat again with its sources, until T stops changing.
    TrilinosWrappers::MPI::Vector previous(thermal->temperature());
    double                        last_change = 0;
    // What the heat integration resolves: below it the changes are its noise.
    const double resolution = thermal_parameters.relative_tolerance * previous.linfty_norm() +
                              thermal_parameters.absolute_tolerance;
    const double tolerance  = std::max(staggered_tolerance, 10 * resolution);
    if (staggered_tolerance > 0 && tolerance > staggered_tolerance && !staggered_tolerance_noted)
      {
        staggered_tolerance_noted = true;
        if (!quiet)
          pcout << "  note: Physics/Staggered tolerance = " << staggered_tolerance
                << " K is below what the heat integration resolves; using " << tolerance
                << " K (tighten Heat/Time integration tolerances to go lower)" << std::endl;
      }
    unsigned int                  growing     = 0;
    for (unsigned int k = 1;; ++k)
      {
        if (k > max_staggered_iterations)
          return fail("the staggered iteration did not reach " +
                      Utilities::to_string(tolerance) + " K in " +
                      Utilities::to_string(max_staggered_iterations) + " iterations (last change " +
                      Utilities::to_string(last_change) + " K, contraction " +
                      Utilities::to_string(result.contraction) + ")");
        update_point_temperatures(); // T^(k) at the points
        thermal->revert();
        if (!solve_mechanics(/*again*/ true))
          return fail(result.mechanics.failure);
        if (!solve_heat())
          return fail("heat: " + result.thermal.failure);
        TrilinosWrappers::MPI::Vector change(thermal->temperature());
        change -= previous;
        const double dT = change.linfty_norm();
        previous        = thermal->temperature();
        if (k > 1 && last_change > 0)
          result.contraction = dT / last_change;
        last_change                   = dT;
        result.staggered_iterations   = k;
        result.staggered_change       = dT;
        n_staggered_iterations += 1;
        if (dT <= tolerance)
          return result;
        // Two growing changes in a row, well above the tolerance (below it the
        // changes are the thermal integrator's noise): the iteration diverges.
        growing = k > 1 && result.contraction >= 1 && dT > 10 * tolerance ? growing + 1 : 0;
        if (growing >= 2)
          return fail("the staggered iteration diverges (contraction " +
                      Utilities::to_string(result.contraction, 3) +
                      "): the coupling is too strong for it at this time step; the splits, "
                      "or a smaller step, may still work");
      }
  }

  template <int dim>
  void Simulator<dim>::update_point_temperatures()
  {
    // After a thermal phase: T_n at the mechanics' quadrature points.
    const unsigned int n_q = mechanical->get_quadrature().size();
    point_temperature.assign(triangulation.n_active_cells() * n_q, 0.);
    std::vector<double> T_new(n_q), T_old(n_q);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          thermal->temperature_at_quadrature_points(cell, mechanical->get_quadrature(), T_new, T_old);
          for (unsigned int q = 0; q < n_q; ++q)
            point_temperature[cell->active_cell_index() * n_q + q] = T_new[q];
        }
  }

  template <int dim>
  void Simulator<dim>::mechanics_temperatures(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    std::vector<double>                                     &T) const
  {
    for (unsigned int q = 0; q < T.size(); ++q)
      T[q] = point_temperature[cell->active_cell_index() * T.size() + q];
  }

  template class Simulator<2>;
  template class Simulator<3>;
} // namespace anvil
