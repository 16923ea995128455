// The material-point driver: a scene-free path through one point (anvil
// --material-point): its parameters, the local Newton loop of mixed strain/
// stress control, the run with its CSV and summary. The path parser is
// point_path.cc.
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/input_error.h>
#include <anvil/core/expression.h>
#include <anvil/core/scene.h>
#include <anvil/material/point_driver.h>
#include <anvil/material/kinematics.h>
#include <anvil/core/csv_history.h>

#include "dense_solve.h"
#include "point_driver_names.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  using namespace point_driver_detail;

  namespace
  {
    const MaterialRequest all_requests = request_stress | request_tangent |
                                         request_temperature_derivative | request_dissipation;
    constexpr unsigned int max_local_iterations = 50;

    // Each header carries its unit ("sxx [MPa]"); readers match the name before " [".
    std::vector<std::string> history_columns()
    {
      std::vector<std::string> columns = {"step", "time [s]", "temperature [K]"};
      for (const auto *name : strain_names)
        columns.emplace_back(std::string(name) + " [-]");
      for (const auto *name : stress_names)
        columns.emplace_back(std::string(name) + " [MPa]");
      for (const auto *name :
           {"von_mises [MPa]", "pressure [MPa]", "equivalent_plastic_strain [-]",
            "plastic_work_rate [MPa/s]", "plastic_dissipation_rate [MPa/s]",
            "thermoelastic_heating_rate [MPa/s]", "return_iterations", "local_iterations"})
        columns.emplace_back(name);
      return columns;
    }

    // A failure to create it shows when the file is opened, with the parameter's name.
    void create_parent_directory(const std::string &name)
    {
      const std::filesystem::path parent = std::filesystem::path(name).parent_path();
      std::error_code             ignored;
      if (!parent.empty())
        std::filesystem::create_directories(parent, ignored);
    }
  } // namespace


  void MaterialPointDriver::declare_parameters(ParameterHandler &prm)
  {
    MaterialFactory::declare_parameters(prm);

    prm.enter_subsection("Path");
    prm.declare_entry("Control", "strain", Patterns::Selection("strain|deformation gradient"),
                      "How the point is driven. strain: the components named in Strain are "
                      "prescribed, all others are stress-controlled (Stress), no rotation. "
                      "deformation gradient: F(t) is prescribed (Deformation gradient), "
                      "Hughes-Winget increments with their rotation; Strain and Stress are "
                      "not used.");
    prm.declare_entry("End time", "1", Patterns::Double(0),
                      "Duration of the path in s (> 0); the paths are functions of t in "
                      "[0, End time].");
    prm.declare_entry("Steps", "100", Patterns::Integer(0),
                      "Number of equal increments from t = 0 to End time (at least 1).");
    prm.declare_entry("Strain", "exx: 0.01*t", Patterns::Anything(),
                      "Control = strain: the prescribed strain components, a ';'-separated "
                      "list of 'component: expression' items with components exx eyy ezz exy "
                      "eyz exz (tensor components, i.e. half the engineering shear strain; "
                      "dimensionless) and muparser expressions in t (s) and the constant pi, "
                      "e.g. 'exx: 0.01*t; exy: 0.005*sin(pi*t)'. The strain is the sum of "
                      "the increments and must be 0 at t = 0.");
    prm.declare_entry("Stress", "", Patterns::Anything(),
                      "Control = strain: the stress of the components not named in Strain, "
                      "in MPa, as 'component: expression' items in t (s) (components sxx syy "
                      "szz sxy syz sxz, or exx ... exz for the same components). Components "
                      "named in neither entry have zero stress, so 'Strain = exx: ...' alone "
                      "is uniaxial stress. A component named in both entries is an error.");
    prm.declare_entry("Deformation gradient", "F11: 1 + 0.01*t", Patterns::Anything(),
                      "Control = deformation gradient: F(t) (dimensionless) as ';'-separated "
                      "'Fij: expression' items, i, j in 1..3, muparser in t (s) and pi, e.g. "
                      "'F11: 1 + t; F12: 0.5*t'. Components not named are those of the "
                      "identity; F(0) must be the identity and det F > 0 along the path.");
    prm.declare_entry("Objective rate", "Jaumann", Patterns::Selection(objective_rate_selection()),
                      "Control = deformation gradient: the objective stress rate, as "
                      "Mechanics/Objective rate of a scene (Jaumann, Green-Naghdi, logarithmic).");
    prm.declare_entry("Temperature", "293", Patterns::Anything(),
                      "Temperature of the point in K as a muparser expression in t (s), "
                      "e.g. '293 + 100*t'; must stay > 0.");
    prm.declare_entry("Adiabatic", "false", Patterns::Bool(),
                      "If true, the point heats by its own dissipation and thermoelastic "
                      "effect (adiabatic update): the temperature is T(t) of the path plus "
                      "the accumulated adiabatic temperature increments (K).");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("File", "point.csv", Patterns::FileName(Patterns::FileName::output),
                      "The CSV history, one row per step (and one for t = 0); a relative name "
                      "is relative to the directory of the .prm file (also when given with "
                      "--set), not the working directory: step, time (s), temperature (K), strain "
                      "exx..exz, Cauchy stress sxx..sxz, von_mises, pressure (MPa), "
                      "equivalent_plastic_strain, plastic_work_rate, "
                      "plastic_dissipation_rate, thermoelastic_heating_rate (MPa/s), "
                      "return_iterations, local_iterations.");
    prm.declare_entry("Summary", "", Patterns::FileName(Patterns::FileName::output),
                      "The run's summary (JSON: model, path, final stress, strain, plastic "
                      "strain and temperature with their units, iterations, wall time); "
                      "relative to the .prm file's directory; empty: the CSV's name with "
                      ".summary.json for .csv (point.csv -> point.summary.json).");
    prm.leave_subsection();
  }

  MaterialPointDriver::~MaterialPointDriver() = default;

  MaterialPointDriver::MaterialPointDriver(Scene &scene)
    : scene(scene)
  {
    ParameterHandler &prm = scene.parameters();

    // The factory names its entries "<prefix>/Material/..."; with the empty
    // prefix of a driver file that is "/Material/...", which neither reads
    // well nor finds the line in the file: name the entry without the slash.
    try
      {
        model = MaterialFactory::create(prm, scene, "");
      }
    catch (const InputError &e)
      {
        const std::string message = e.what();
        const std::string marker  = ": '/Material/";
        const auto        at      = message.find(marker);
        if (at == std::string::npos)
          throw;
        const auto close = message.find('\'', at + marker.size());
        if (close == std::string::npos)
          throw;
        const std::string path = message.substr(at + 4, close - at - 4);
        std::string       rest = message.substr(close + 1);
        scene.fail(path, trim(rest));
      }
    if (!(model->bulk_modulus() > 0))
      scene.fail("Material/Elasticity/Young's modulus",
                 "and 'Bulk modulus' are both 0: expected one of them > 0");

    prm.enter_subsection("Path");
    control   = prm.get("Control") == "strain" ? Control::strain : Control::deformation_gradient;
    end_time  = prm.get_double("End time");
    const int steps = prm.get_integer("Steps");
    const std::string strain      = prm.get("Strain");
    const std::string stress      = prm.get("Stress");
    const std::string F           = prm.get("Deformation gradient");
    const std::string temperature_text = prm.get("Temperature");
    adiabatic = prm.get_bool("Adiabatic");
    objective_rate = objective_rate_from_string(prm.get("Objective rate"));
    prm.leave_subsection();

    prm.enter_subsection("Output");
    file    = trim(prm.get("File"));
    summary = trim(prm.get("Summary"));
    prm.leave_subsection();

    if (!(end_time > 0))
      scene.fail(path_end_time, "= " + number(end_time) + ": expected a duration > 0 s");
    if (steps < 1)
      scene.fail(path_steps, "= " + std::to_string(steps) + ": expected at least 1 step");
    n_steps = steps;
    if (file.empty())
      scene.fail(path_file, "is empty: expected a file name such as point.csv");
    // Relative names belong to the .prm file, wherever anvil is started from
    // (as a scene's mesh files do): the working directory is an accident.
    const auto beside_prm = [&](const std::string &name) {
      const std::filesystem::path p(name);
      if (p.is_absolute() || scene.filename().empty())
        return name;
      return (std::filesystem::path(scene.filename()).parent_path() / p).lexically_normal().string();
    };
    if (summary.empty())
      {
        std::filesystem::path p(file);
        summary = (p.extension() == ".csv" ? p.replace_extension("") : p).string() + ".summary.json";
      }
    file    = beside_prm(file);
    summary = beside_prm(summary);

    temperature = parse(temperature_text, path_temperature, "");
    if (control == Control::strain)
      parse_strain_control(strain, stress);
    else
      parse_deformation_gradient(F);
    check_path();

    point = model->create_point({adiabatic});
  }

  unsigned int MaterialPointDriver::strain_step(const unsigned int     step,
                                                const double           t_new,
                                                SymmetricTensor<2, 3> &strain,
                                                MaterialIncrement     &increment,
                                                MaterialResponse      &response)
  {
    // Prescribed components: reach the path's value exactly; free ones start at 0.
    std::vector<unsigned int> free;
    std::vector<double>       target;
    SymmetricTensor<2, 3>     de;
    for (unsigned int c = 0; c < 6; ++c)
      if (strain_controlled[c])
        component(de, c) = value(component_path[c], t_new) - component(strain, c);
      else
        {
          free.push_back(c);
          target.push_back(component_path[c] ? value(component_path[c], t_new) : 0.);
        }

    const unsigned int n = free.size();
    // dσ/dε_c for a unit tensor component ε_c (both ij and ji for shear).
    std::array<SymmetricTensor<2, 3>, 6> unit;
    for (unsigned int c = 0; c < 6; ++c)
      component(unit[c], c) = 1.;

    for (unsigned int it = 0;; ++it)
      {
        increment.strain_increment = de;
        response                   = MaterialResponse();
        point->update(increment, all_requests, response);

        std::vector<double> r(n);
        double              norm = 0;
        for (unsigned int i = 0; i < n; ++i)
          {
            r[i] = component(response.stress, free[i]) - target[i];
            norm += r[i] * r[i];
          }
        norm = std::sqrt(norm);
        const double tolerance = 1e-10 * std::max(1., response.stress.norm());
        if (!std::isfinite(norm))
          throw SimulationError("material point, step " + std::to_string(step) + " (t = " +
                                number(t_new) + " s): the stress is not finite");
        if (norm <= tolerance)
          {
            strain += de;
            return it;
          }
        if (it == max_local_iterations)
          throw SimulationError("material point, step " + std::to_string(step) + " (t = " +
                                number(t_new) + " s): the stress-controlled components did not "
                                "converge in " + std::to_string(max_local_iterations) +
                                " local iterations (|r| = " + number(norm) +
                                " MPa, tolerance " + number(tolerance) +
                                " MPa); try more Steps");

        std::vector<std::vector<double>> A(n, std::vector<double>(n));
        for (unsigned int j = 0; j < n; ++j)
          {
            const SymmetricTensor<2, 3> column = response.tangent * unit[free[j]];
            for (unsigned int i = 0; i < n; ++i)
              A[i][j] = component(column, free[i]);
          }
        if (!point_driver::solve(A, r))
          {
            std::string names;
            for (const unsigned int c : free)
              names += std::string(names.empty() ? "" : " ") + stress_names[c];
            throw SimulationError("material point, step " + std::to_string(step) + " (t = " +
                                  number(t_new) + " s): the tangent restricted to the "
                                  "stress-controlled components (" + names +
                                  ") is singular: the prescribed stress cannot be reached");
          }
        for (unsigned int i = 0; i < n; ++i)
          component(de, free[i]) -= r[i];
      }
  }

  void MaterialPointDriver::run(const bool write, std::ostream *log)
  {
    const auto start = std::chrono::steady_clock::now();
    CsvHistory csv;
    if (write)
      for (const auto &name : {file, summary})
        create_parent_directory(name);
    csv.open(file, history_columns(), write);
    if (write && !csv.is_open())
      scene.fail(path_file, "= '" + file + "' cannot be opened for writing");

    SymmetricTensor<2, 3> strain;
    MaterialResponse      response;
    response.stress = point->committed_stress();
    double       T  = value(temperature, 0.);
    double       adiabatic_heating = 0; // accumulated adiabatic ΔT, K
    unsigned int max_return = 0, max_local = 0;

    const auto add_row = [&](const unsigned int step, const double t, const unsigned int local) {
      const SymmetricTensor<2, 3> &s = response.stress;
      std::vector<double>          row = {double(step), t, T};
      for (unsigned int c = 0; c < 6; ++c)
        row.push_back(component(strain, c));
      for (unsigned int c = 0; c < 6; ++c)
        row.push_back(component(s, c));
      const SymmetricTensor<2, 3> dev = deviator(s);
      row.push_back(std::sqrt(1.5 * (dev * dev)));
      row.push_back(-trace(s) / 3.);
      row.push_back(response.equivalent_plastic_strain);
      row.push_back(response.plastic_work_rate);
      row.push_back(response.plastic_dissipation_rate);
      row.push_back(response.thermoelastic_heating_rate);
      row.push_back(response.return_iterations);
      row.push_back(local);
      for (double &v : row)
        v += 0.; // -0 -> 0
      csv.add_row(row);
    };
    add_row(0, 0., 0);

    const auto F_at = [&](const double t) {
      Tensor<2, 3> F = unit_symmetric_tensor<3>();
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          if (F_path[i][j])
            F[i][j] = value(F_path[i][j], t);
      return F;
    };
    Tensor<2, 3>          F_old = F_at(0.);
    IncrementalKinematics kinematics;

    Final      done; // what the summary reports, also of a run that stops early
    const auto record = [&](const unsigned int k, const double t) {
      done.steps       = k;
      done.time        = t;
      done.temperature = T;
      done.strain      = strain;
      done.response    = response;
      done.max_return  = max_return;
      done.max_local   = max_local;
      done.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    record(0, 0.);

    const double dt = end_time / n_steps;
    for (unsigned int k = 1; k <= n_steps; ++k)
      {
        const double t = end_time * k / n_steps;

        // The temperature without this step's own adiabatic heating: the
        // point adds that itself when increment.adiabatic is set.
        const double      T_start = value(temperature, t) + adiabatic_heating;
        MaterialIncrement increment;
        increment.temperature           = T_start;
        increment.temperature_increment = T_start - T;
        increment.time_step             = dt;
        increment.adiabatic             = adiabatic;

        unsigned int local = 0;
        try
          {
            if (control == Control::strain)
              {
                increment.rotation_increment = unit_symmetric_tensor<3>();
                local = strain_step(k, t, strain, increment, response);
              }
            else
              {
                const Tensor<2, 3> F = F_at(t);
                kinematics.reinit(F, F_old, objective_rate);
                increment.strain_increment   = kinematics.strain_increment;
                increment.rotation_increment = kinematics.rotation_increment;
                response                     = MaterialResponse();
                point->update(increment, all_requests, response);
                const Tensor<2, 3> &R = kinematics.rotation_increment;
                strain = symmetrize(R * Tensor<2, 3>(strain) * transpose(R)) +
                         kinematics.strain_increment;
                F_old = F;
              }
          }
        catch (const MaterialPointError &e)
          {
            const SimulationError error("material point, step " + std::to_string(k) +
                                        " (t = " + number(t) + " s): " + e.what());
            if (write)
              write_summary(done, std::string("failed: ") + error.what());
            throw error;
          }
        catch (const SimulationError &e)
          {
            if (write)
              write_summary(done, std::string("failed: ") + e.what());
            throw;
          }
        point->commit();

        if (adiabatic)
          adiabatic_heating += response.adiabatic_temperature_increment;
        T = value(temperature, t) + adiabatic_heating;
        max_return = std::max(max_return, response.return_iterations);
        max_local  = std::max(max_local, local);
        add_row(k, t, local);
        record(k, t);
      }
    if (write)
      write_summary(done, "completed");

    if (log)
      {
        const SymmetricTensor<2, 3> &s = response.stress;
        std::ostringstream           line;
        line.precision(6);
        line << "anvil: material point (" << model->name() << ", "
             << (control == Control::strain ? "strain" : "deformation gradient")
             << " control): " << n_steps << " steps to t = " << end_time
             << " s, max return iterations " << max_return << ", max local iterations "
             << max_local << "; final stress (MPa)";
        for (unsigned int c = 0; c < 6; ++c)
          line << (c ? ", " : " ") << stress_names[c] << " = " << component(s, c);
        line << ", T = " << T << " K; history in " << file << ", summary in " << summary;
        *log << line.str() << std::endl;
      }
  }
} // namespace anvil
