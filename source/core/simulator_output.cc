#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>

#include <anvil/core/input_error.h>
#include <anvil/core/simulator.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // "f(a, b)" -> ("f", {"a", "b"}); empty name if malformed.
    std::pair<std::string, std::vector<std::string>> parse_call(const std::string &text)
    {
      const auto open  = text.find('(');
      const auto close = text.rfind(')');
      if (open == std::string::npos || close == std::string::npos || close < open)
        return {"", {}};
      return {trim(text.substr(0, open)),
              split_outside_parentheses(text.substr(open + 1, close - open - 1), ',')};
    }

    double peak_memory_mb()
    {
      std::ifstream status("/proc/self/status");
      std::string   line;
      while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0)
          return std::stod(line.substr(6)) / 1024.;
      return 0;
    }
  } // namespace

  template <int dim>
  void Simulator<dim>::parse_output(ParameterHandler &prm, Scene &scene)
  {
    prm.enter_subsection("Output");
    output_dir      = prm.get("Directory");
    output_interval     = prm.get_integer("Field interval");
    checkpoint_interval = prm.get_integer("Checkpoint interval");
    restart_directory   = trim(prm.get("Restart from"));
    quiet           = prm.get("Verbosity") == "quiet";
    const std::string probe_text = prm.get("Probes");
    const std::string qoi_text   = prm.get("Quantities of interest");
    prm.leave_subsection();

    if (!restart_directory.empty() &&
        !std::filesystem::exists(restart_directory + "/state.txt"))
      scene.fail("Output/Restart from", "= '" + restart_directory +
                                          "' is not a checkpoint directory (no state.txt in it)");
    if (output_dir.empty())
      output_dir = "output/" + std::filesystem::path(scene.filename().empty() ? "anvil" : scene.filename())
                                 .stem()
                                 .string();

    for (const auto &item : split_outside_parentheses(probe_text, ';'))
      {
        if (item.empty())
          continue;
        const auto colon = item.find(':');
        Probe      p;
        std::vector<std::string> coords;
        if (colon != std::string::npos)
          {
            p.name = trim(item.substr(0, colon));
            coords = split_outside_parentheses(item.substr(colon + 1), ',');
          }
        if (p.name.empty() || coords.size() != dim)
          scene.fail("Output/Probes", "item '" + item + "': expected 'name: " +
                                        (dim == 2 ? "x, y'" : "x, y, z'") + " in mm");
        for (unsigned int d = 0; d < dim; ++d)
          try
            {
              std::size_t used = 0;
              p.point[d]       = std::stod(coords[d], &used);
              if (used != coords[d].size())
                throw std::invalid_argument("");
            }
          catch (...)
            {
              scene.fail("Output/Probes", "item '" + item + "': '" + coords[d] + "' is not a number");
            }
        probes.push_back(p);
      }

    std::vector<std::string> fields;
    if (mechanics)
      fields = {"stress_xx", "stress_xy", "stress_xz", "stress_yy", "stress_yz",
                "stress_zz", "von_mises", "pressure",  "J",         "equivalent_plastic_strain"};
    if (heat)
      fields.push_back("temperature");
    auto is_field = [&](const std::string &f) {
      return std::find(fields.begin(), fields.end(), f) != fields.end();
    };
    const std::string qpath = "Output/Quantities of interest";
    std::string       known_fields;
    for (const auto &f : fields)
      known_fields += (known_fields.empty() ? "" : ", ") + f;
    for (const auto &item : split_outside_parentheses(qoi_text, ';'))
      {
        if (item.empty())
          continue;
        const auto colon = item.find(':');
        if (colon == std::string::npos)
          scene.fail(qpath, "item '" + item + "': expected 'name: expression'");
        Quantity q;
        q.name                = trim(item.substr(0, colon));
        const auto [f, args]  = parse_call(item.substr(colon + 1));
        {
          // An optional constant after the call: "mean(temperature, upper) - 300".
          const std::string expr  = item.substr(colon + 1);
          const auto        close = expr.rfind(')');
          const std::string tail  = close == std::string::npos ? "" : trim(expr.substr(close + 1));
          if (!tail.empty())
            {
              std::size_t used = 0;
              double      c    = 0;
              try
                {
                  if (tail[0] != '+' && tail[0] != '-')
                    throw std::invalid_argument("");
                  c = std::stod(trim(tail.substr(1)), &used);
                  if (used != trim(tail.substr(1)).size())
                    throw std::invalid_argument("");
                }
              catch (...)
                {
                  scene.fail(qpath, "item '" + item + "': after the call only '+ number' or "
                                    "'- number' may follow, not '" + tail + "'");
                }
              q.offset = tail[0] == '-' ? -c : c;
            }
        }
        q.kind                = f;
        auto component_of = [&](const std::string &c) -> unsigned int {
          for (unsigned int d = 0; d < dim; ++d)
            if (c == std::string(1, "xyz"[d]))
              return d;
          scene.fail(qpath, "item '" + item + "': component '" + c + "' should be x, y" +
                              (dim == 3 ? " or z" : ""));
        };
        if (f == "reaction" && args.size() == 2 && !mechanics)
          scene.fail(qpath, "item '" + item + "': a reaction needs the mechanics, and "
                              "Physics/Coupling is 'thermal only'");
        if (f == "reaction" && args.size() == 2)
          {
            q.target    = args[0];
            q.boundary  = geometry.boundary_id(args[0], scene.where(qpath));
            q.component = component_of(args[1]);
          }
        else if (f == "probe" && args.size() == 2)
          {
            q.target = args[0];
            q.field  = args[1];
            if (std::none_of(probes.begin(), probes.end(),
                             [&](const Probe &p) { return p.name == args[0]; }))
              scene.fail(qpath, "item '" + item + "': no probe named '" + args[0] +
                                  "' in Output/Probes");
            if (!is_field(q.field) && !(mechanics && q.field.size() == 2 && q.field[0] == 'u'))
              scene.fail(qpath, "item '" + item + "': unknown field '" + q.field +
                                  "' for this scene (expected " +
                                  (mechanics ? std::string(dim == 3 ? "ux, uy, uz, " : "ux, uy, ") : "") +
                                  "one of: " + known_fields + ")");
            if (q.field[0] == 'u' && q.field.size() == 2)
              q.component = component_of(q.field.substr(1));
          }
        else if (f == "contact" && args.size() == 2)
          {
            q.target = args[0];
            q.field  = args[1];
            const auto &pairs = contact.get_pairs();
            if (std::none_of(pairs.begin(), pairs.end(), [&](const auto &p) { return p.name == args[0]; }))
              scene.fail(qpath, "item '" + item + "': no contact pair named '" + args[0] +
                                  "' in Contact/Pairs");
            const std::vector<std::string> known = {"x", "y", "z", "normal", "tangential",
                                                    "friction_work", "active_nodes",
                                                    "sliding_nodes", "max_penetration"};
            if (std::find(known.begin(), known.end(), args[1]) == known.end() ||
                (args[1] == "z" && dim == 2))
              scene.fail(qpath, "item '" + item + "': expected contact(pair, x|y" +
                                  (dim == 3 ? "|z" : "") +
                                  "|normal|tangential|friction_work|active_nodes|sliding_nodes|"
                                  "max_penetration)");
          }
        else if ((f == "max" || f == "min") && args.size() == 1 && is_field(args[0]))
          q.field = args[0];
        else if (f == "mean" && (args.size() == 1 || args.size() == 2) && is_field(args[0]))
          {
            q.field = args[0];
            if (args.size() == 2)
              q.body = geometry.body_id(args[1], scene.where(qpath));
          }
        else
          scene.fail(qpath, "item '" + item + "': expected reaction(boundary, x), "
                              "probe(name, field), max(field), min(field) or mean(field[, body]) "
                              "with a field of this scene (" + known_fields + ")");
        quantities.push_back(q);
      }
  }

  template <int dim>
  void Simulator<dim>::open_histories()
  {
    const bool root   = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    const bool append = !restart_directory.empty();
    std::vector<std::string> columns;
    if (mechanical)
      {
        // Reactions on every named boundary: what a user plots first.
        columns = {"step", "time"};
        reaction_boundaries.clear();
        for (const auto &[name, id] : geometry.boundary_names())
          {
            reaction_boundaries.emplace_back(name, id);
            for (unsigned int d = 0; d < dim; ++d)
              columns.push_back(name + "_F" + "xyz"[d]);
          }
        reactions_csv.open(output_dir + "/reactions.csv", columns, root, append);
      }

    if (!probes.empty())
      {
        columns = {"step", "time"};
        for (const auto &p : probes)
          {
            if (mechanical)
              {
                for (unsigned int d = 0; d < dim; ++d)
                  columns.push_back(p.name + "_u" + "xyz"[d]);
                for (const auto *c : {"xx", "yy", "zz", "xy", "yz", "xz"})
                  columns.push_back(p.name + "_stress_" + c);
                columns.push_back(p.name + "_equivalent_plastic_strain");
              }
            if (thermal)
              columns.push_back(p.name + "_temperature");
          }
        probes_csv.open(output_dir + "/probes.csv", columns, root, append);
      }
    columns = {"step", "time"};
    if (mechanical)
      columns.insert(columns.end(), {"external_work", "internal_work", "kinetic_energy",
                                     "plastic_work", "elastic_energy", "stress_work",
                                     "balance_error"});
    if (thermal)
      columns.insert(columns.end(),
                     {"heat_content", "heat_content_change", "boundary_heat_in", "source_heat",
                      "plastic_heat", "thermoelastic_heat", "contact_heat", "heat_balance_error"});
    energy_csv.open(output_dir + "/energy.csv", columns, root, append);
    if (mechanical)
      newton_csv.open(output_dir + "/newton.csv",
                      {"step", "time", "iteration", "residual", "increment", "line_search",
                       "converged"},
                      root, append);
    if (!contact.empty())
      {
        columns = {"step", "time"};
        for (const auto &p : contact.get_pairs())
          {
            for (unsigned int d = 0; d < dim; ++d)
              columns.push_back(p.name + "_F" + "xyz"[d]);
            for (const auto *c : {"_normal", "_tangential", "_friction_work", "_active_nodes",
                                  "_sliding_nodes", "_max_penetration", "_heat_exchanged",
                                  "_friction_heat"})
              columns.push_back(p.name + c);
          }
        contact_csv.open(output_dir + "/contact.csv", columns, root, append);
      }
    if (thermal)
      thermal_csv.open(output_dir + "/thermal.csv",
                       {"step", "time", "time_step", "arkode_steps", "arkode_attempts",
                        "error_test_failures", "nonlinear_iterations", "nonlinear_failures",
                        "linear_setups", "linear_solves", "linear_iterations", "mass_solves",
                        "rhs_evaluations", "last_internal_step", "staggered_iterations",
                        "staggered_change", "staggered_contraction", "mechanics_wall_time",
                        "thermal_wall_time"},
                       root, append);
  }

  template <int dim>
  typename Simulator<dim>::HeatBalance Simulator<dim>::heat_balance() const
  {
    HeatBalance b;
    b.content = thermal->heat_content();
    b.change  = b.content - initial_heat_content;
    for (const auto &[id, q] : thermal->boundary_heat_flow())
      b.boundary += q;
    b.plastic       = heat_audit.plastic;
    b.thermoelastic = heat_audit.thermoelastic;
    b.source        = thermal->source_heat() - b.plastic - b.thermoelastic;
    b.contact       = heat_audit.contact;
    const double residual = b.change - b.boundary - thermal->source_heat() - b.contact;
    const double scale    = std::max({std::abs(b.change), std::abs(b.boundary),
                                      std::abs(thermal->source_heat()), std::abs(b.contact), 1e-300});
    b.error = std::abs(residual) / scale;
    return b;
  }

  template <int dim>
  void Simulator<dim>::write_histories(const double t, const unsigned int step)
  {
    TimerOutput::Scope  s(*timer, "Output");
    std::vector<double> row = {double(step), t};
    if (mechanical)
      {
        for (const auto &[name, id] : reaction_boundaries)
          {
            const auto f = mechanical->reaction(id);
            for (unsigned int d = 0; d < dim; ++d)
              row.push_back(f[d]);
          }
        reactions_csv.add_row(row);
      }

    if (!probes.empty())
      {
        row = {double(step), t};
        for (const auto &p : probes)
          {
            if (mechanical)
              {
                Tensor<1, dim>        u;
                SymmetricTensor<2, 3> s;
                double                eqps = 0;
                mechanical->probe(p.point, u, s, eqps);
                for (unsigned int d = 0; d < dim; ++d)
                  row.push_back(u[d]);
                row.insert(row.end(), {s[0][0], s[1][1], s[2][2], s[0][1], s[1][2], s[0][2], eqps});
              }
            if (thermal)
              row.push_back(thermal->temperature_at(p.point));
          }
        probes_csv.add_row(row);
      }
    if (!contact.empty())
      {
        row = {double(step), t};
        for (const auto &c : contact.totals())
          {
            for (unsigned int d = 0; d < dim; ++d)
              row.push_back(c.force[d]);
            row.insert(row.end(), {c.normal, c.tangential, c.friction_work, double(c.active),
                                   double(c.sliding), c.max_penetration, c.heat_exchanged,
                                   c.friction_heat});
          }
        contact_csv.add_row(row);
      }
    row = {double(step), t};
    if (mechanical)
      {
        const auto &e = mechanical->energy();
        row.insert(row.end(), {e.external_work, e.internal_work, e.kinetic, e.plastic_work,
                               e.elastic_energy, e.stress_work, e.balance_error()});
      }
    if (thermal)
      {
        const auto b = heat_balance();
        row.insert(row.end(),
                   {b.content, b.change, b.boundary, b.source, b.plastic, b.thermoelastic,
                    b.contact, b.error});
      }
    energy_csv.add_row(row);
  }

  template <int dim>
  void Simulator<dim>::write_fields(const double t, const unsigned int step)
  {
    TimerOutput::Scope s(*timer, "Output");
    DataOut<dim>       data_out;
    if (mechanical)
      {
        data_out.attach_dof_handler(mechanical->get_dof_handler());
        std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
          dim, DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(mechanical->displacement(),
                                 std::vector<std::string>(dim, "displacement"),
                                 DataOut<dim>::type_dof_data, interpretation);
        if (mechanical->is_dynamic())
          data_out.add_data_vector(mechanical->velocity(), std::vector<std::string>(dim, "velocity"),
                                   DataOut<dim>::type_dof_data, interpretation);
        if (thermal)
          data_out.add_data_vector(thermal->get_dof_handler(), thermal->temperature(), "temperature");
        const auto fields = mechanical->cell_fields();
        for (unsigned int i = 0; i < fields.names.size(); ++i)
          data_out.add_data_vector(fields.values[i], fields.names[i], DataOut<dim>::type_cell_data);
      }
    else
      {
        data_out.attach_dof_handler(thermal->get_dof_handler());
        data_out.add_data_vector(thermal->temperature(), "temperature");
      }
    Vector<float> rank(triangulation.n_active_cells());
    rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    data_out.add_data_vector(rank, "rank", DataOut<dim>::type_cell_data);
    data_out.build_patches(mechanical ? mechanical->get_mapping() : thermal->get_mapping());
    // best_compression costs several seconds per write at 10⁵ cells.
    DataOutBase::VtkFlags flags;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);
    const std::string name = data_out.write_vtu_with_pvtu_record(output_dir + "/fields/",
                                                                 "solution", step,
                                                                 mpi_communicator, 5);
    if (!contact.empty())
      write_contact_fields(t, step);
    // Replace a record at the same time (a final write after a failure).
    if (!pvd_records.empty() && pvd_records.back().first == t)
      pvd_records.pop_back();
    pvd_records.emplace_back(t, "fields/" + name);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream pvd(output_dir + "/solution.pvd");
        DataOutBase::write_pvd_record(pvd, pvd_records);
      }
  }

  template <int dim>
  void Simulator<dim>::write_contact_fields(const double t, const unsigned int step)
  {
    // The slave nodes as a point cloud (fields/contact_<step>.vtu, contact.pvd):
    // pressure, gap, slip, status, frictional power, conductance, heat flux, pair.
    std::vector<double> local;
    for (const auto &o : contact.node_outputs())
      {
        for (unsigned int d = 0; d < 3; ++d)
          local.push_back(d < dim ? o.position[d] : 0.);
        local.insert(local.end(), {o.pressure, o.gap, o.slip, double(o.status), o.friction_power,
                                   o.conductance, o.heat_flux, double(o.pair)});
      }
    const auto parts = Utilities::MPI::all_gather(mpi_communicator, local);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::vector<double> all;
    for (const auto &part : parts)
      all.insert(all.end(), part.begin(), part.end());
    const unsigned int width = 11, n = all.size() / width;
    const std::string  name  = "contact_" + Utilities::int_to_string(step, 5) + ".vtu";
    std::ofstream      vtu(output_dir + "/fields/" + name);
    vtu << std::setprecision(10)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
        << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (unsigned int i = 0; i < n; ++i)
      vtu << all[i * width] << ' ' << all[i * width + 1] << ' ' << all[i * width + 2] << '\n';
    vtu << "</DataArray></Points>\n<Cells>\n"
        << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (unsigned int i = 0; i < n; ++i)
      vtu << i << ' ';
    vtu << "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (unsigned int i = 0; i < n; ++i)
      vtu << i + 1 << ' ';
    vtu << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (unsigned int i = 0; i < n; ++i)
      vtu << "1 "; // VTK_VERTEX
    vtu << "\n</DataArray>\n</Cells>\n<PointData>\n";
    const char *names[] = {"contact_pressure", "gap", "slip", "status", "frictional_power",
                           "conductance", "contact_heat_flux", "pair"};
    for (unsigned int f = 0; f < 8; ++f)
      {
        vtu << "<DataArray type=\"Float64\" Name=\"" << names[f] << "\" format=\"ascii\">\n";
        for (unsigned int i = 0; i < n; ++i)
          vtu << all[i * width + 3 + f] << ' ';
        vtu << "\n</DataArray>\n";
      }
    vtu << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    if (!contact_records.empty() && contact_records.back().first == t)
      contact_records.pop_back();
    contact_records.emplace_back(t, "fields/" + name);
    std::ofstream pvd(output_dir + "/contact.pvd");
    DataOutBase::write_pvd_record(pvd, contact_records);
  }

  template <int dim>
  void Simulator<dim>::write_checkpoint(const double t, const double dt)
  {
    TimerOutput::Scope s(*timer, "Checkpoint");
    const std::string dir = output_dir + "/checkpoint";
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::filesystem::create_directories(dir);
    MPI_Barrier(mpi_communicator);
    // Attachments are read back in this order: mechanics (vectors, points), heat.
    if (mechanical)
      mechanical->prepare_checkpoint();
    if (thermal)
      thermal->prepare_checkpoint();
    triangulation.save(dir + "/mesh");
    std::ostringstream contact_state; // collective
    if (!contact.empty())
      contact.save(contact_state);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream state(dir + "/state.txt");
        state << std::setprecision(17) << t << ' ' << dt << ' ' << n_steps << ' ' << n_cut_backs
              << ' ' << n_newton << ' ' << n_linear << '\n';
        auto line = [&](const std::vector<double> &values) {
          state << values.size();
          for (const double x : values)
            state << ' ' << x;
          state << '\n';
        };
        line(mechanical ? mechanical->checkpoint_scalars() : std::vector<double>());
        line(thermal ? thermal->checkpoint_scalars() : std::vector<double>());
        line({initial_heat_content, heat_audit.plastic, heat_audit.thermoelastic, heat_audit.contact,
              double(n_thermal_steps), double(n_thermal_nonlinear), double(n_staggered_iterations)});
        state << pvd_records.size() << '\n';
        for (const auto &[time, name] : pvd_records)
          state << time << ' ' << name << '\n';
        state << (contact.empty() ? "0\n" : contact_state.str());
      }
  }

  template <int dim>
  void Simulator<dim>::read_checkpoint(double &t, double &dt)
  {
    if (mechanical)
      mechanical->load_checkpoint();
    if (thermal)
      thermal->load_checkpoint();
    std::ifstream state(restart_directory + "/state.txt");
    state >> t >> dt >> n_steps >> n_cut_backs >> n_newton >> n_linear;
    auto line = [&]() {
      std::size_t n = 0;
      state >> n;
      std::vector<double> values(state ? n : 0);
      for (double &x : values)
        state >> x;
      return values;
    };
    const auto mechanical_scalars = line();
    const auto thermal_scalars    = line();
    const auto heat_scalars       = line();
    if (!state || (mechanical && mechanical_scalars.empty()) || (thermal && thermal_scalars.empty()) ||
        heat_scalars.size() != 7)
      throw InputError(restart_directory +
                       "/state.txt: the checkpoint was not written by this scene's physics "
                       "(Physics/Coupling differs) or is damaged");
    if (mechanical)
      mechanical->restore_scalars(mechanical_scalars);
    if (thermal)
      thermal->restore_scalars(thermal_scalars);
    initial_heat_content     = heat_scalars[0];
    heat_audit.plastic       = heat_scalars[1];
    heat_audit.thermoelastic = heat_scalars[2];
    heat_audit.contact       = heat_scalars[3];
    n_thermal_steps          = static_cast<unsigned long>(heat_scalars[4]);
    n_thermal_nonlinear      = static_cast<unsigned long>(heat_scalars[5]);
    n_staggered_iterations   = static_cast<unsigned long>(heat_scalars[6]);
    std::size_t n = 0;
    state >> n;
    pvd_records.resize(n);
    for (auto &[time, name] : pvd_records)
      state >> time >> name;
    if (!contact.empty())
      contact.load(state);
    if (!state)
      throw InputError(restart_directory + "/state.txt: cannot read the checkpoint state");
    current_time = t;
  }

  template <int dim>
  void Simulator<dim>::evaluate_quantities()
  {
    qoi_values.clear();
    if (quantities.empty())
      return;
    typename MechanicalProblem<dim>::CellFields fields;
    if (mechanical)
      fields = mechanical->cell_fields();
    if (thermal)
      {
        fields.names.push_back("temperature");
        fields.values.push_back(thermal->cell_mean_temperature());
      }
    auto field_index = [&](const std::string &f) {
      return std::find(fields.names.begin(), fields.names.end(), f) - fields.names.begin();
    };
    for (const auto &q : quantities)
      {
        double value = 0;
        if (q.kind == "reaction")
          value = mechanical->reaction(q.boundary)[q.component];
        else if (q.kind == "contact")
          {
            const auto &pairs = contact.get_pairs();
            const auto  k     = std::find_if(pairs.begin(), pairs.end(),
                                        [&](const auto &p) { return p.name == q.target; }) -
                           pairs.begin();
            const auto &c = contact.totals()[k];
            if (q.field.size() == 1)
              value = c.force[q.field[0] - 'x'];
            else if (q.field == "normal")
              value = c.normal;
            else if (q.field == "tangential")
              value = c.tangential;
            else if (q.field == "friction_work")
              value = c.friction_work;
            else if (q.field == "active_nodes")
              value = c.active;
            else if (q.field == "sliding_nodes")
              value = c.sliding;
            else
              value = c.max_penetration;
          }
        else if (q.kind == "probe")
          {
            const auto &p = *std::find_if(probes.begin(), probes.end(),
                                          [&](const Probe &p) { return p.name == q.target; });
            Tensor<1, dim>        u;
            SymmetricTensor<2, 3> s;
            double                eqps = 0;
            if (mechanical)
              mechanical->probe(p.point, u, s, eqps);
            if (q.field == "temperature")
              value = thermal->temperature_at(p.point);
            else if (q.field[0] == 'u' && q.field.size() == 2)
              value = u[q.component];
            else if (q.field == "equivalent_plastic_strain")
              value = eqps;
            else
              {
                // The probe's cell average; evaluated from the stress tensor.
                const auto dev = deviator(s);
                if (q.field == "von_mises")
                  value = std::sqrt(1.5 * (dev * dev));
                else if (q.field == "pressure")
                  value = -trace(s) / 3;
                else if (q.field.rfind("stress_", 0) == 0)
                  value = s[q.field[7] - 'x'][q.field[8] - 'x'];
              }
          }
        else
          {
            const auto   &v   = fields.values[field_index(q.field)];
            double        sum = 0, volume = 0;
            double        extreme = q.kind == "max" ? -1e300 : 1e300;
            for (const auto &cell : triangulation.active_cell_iterators())
              if (cell->is_locally_owned() &&
                  (q.body < 0 || cell->material_id() == types::material_id(q.body)))
                {
                  const double x = v[cell->active_cell_index()];
                  sum += x * cell->measure();
                  volume += cell->measure();
                  extreme = q.kind == "max" ? std::max(extreme, x) : std::min(extreme, x);
                }
            if (q.kind == "mean")
              value = Utilities::MPI::sum(sum, mpi_communicator) /
                      Utilities::MPI::sum(volume, mpi_communicator);
            else if (q.kind == "max")
              value = Utilities::MPI::max(extreme, mpi_communicator);
            else
              value = Utilities::MPI::min(extreme, mpi_communicator);
          }
        qoi_values.emplace_back(q.name, value + q.offset);
      }
  }

  template <int dim>
  void Simulator<dim>::write_summary(const std::string &status)
  {
    Summary s;
    s.set("scene", scene.filename());
    s.set("status", status);
    s.set("dimension", dim);
    s.set("processes", Utilities::MPI::n_mpi_processes(mpi_communicator));
    s.set("cells", triangulation.n_global_active_cells());
    s.set("coupling", coupling);
    s.set("dofs", mechanical ? double(mechanical->n_dofs()) : 0.);
    if (thermal)
      s.set("temperature_dofs", double(thermal->n_dofs()));
    s.set("time", current_time);
    s.set("steps", n_steps);
    s.set("cut_backs", n_cut_backs);
    s.set("newton_iterations", n_newton);
    s.set("linear_iterations", n_linear);
    s.set("wall_time", MPI_Wtime() - wall_start);
    for (const auto &[section, seconds] : timer->get_summary_data(TimerOutput::total_wall_time))
      s.set("wall_time_per_phase", section, Utilities::MPI::max(seconds, mpi_communicator));
    if (mechanical)
      {
        const double assembly =
          Utilities::MPI::min(mechanical->last_assembly_rate(), mpi_communicator);
        s.set("assembly_cells_per_second_per_process", assembly);
      }
    const double memory = Utilities::MPI::sum(peak_memory_mb(), mpi_communicator);
    s.set("peak_memory_MB", memory);
    const double all_dofs =
      (mechanical ? mechanical->n_dofs() : 0) + (thermal ? thermal->n_dofs() : 0);
    s.set("memory_per_dof_bytes", memory * 1024. * 1024. / std::max<double>(1, all_dofs));
    if (mechanical)
      {
        const auto &e = mechanical->energy();
        s.set("energy", "external_work", e.external_work);
        s.set("energy", "internal_work", e.internal_work);
        s.set("energy", "kinetic_energy", e.kinetic);
        s.set("energy", "initial_kinetic_energy", e.initial_kinetic);
        s.set("energy", "plastic_work", e.plastic_work);
        s.set("energy", "elastic_energy", e.elastic_energy);
        s.set("energy", "stress_work", e.stress_work);
        s.set("energy", "balance_error", e.balance_error());
      }
    if (thermal)
      {
        const auto b = heat_balance();
        s.set("heat", "heat_content", b.content);
        s.set("heat", "heat_content_change", b.change);
        s.set("heat", "boundary_heat_in", b.boundary);
        s.set("heat", "source_heat", b.source);
        s.set("heat", "plastic_heat", b.plastic);
        s.set("heat", "thermoelastic_heat", b.thermoelastic);
        s.set("heat", "contact_heat", b.contact);
        s.set("heat", "balance_error", b.error);
        s.set("heat", "arkode_internal_steps", double(n_thermal_steps));
        s.set("heat", "arkode_steps_per_step", n_steps ? double(n_thermal_steps) / n_steps : 0.);
        s.set("heat", "arkode_nonlinear_iterations", double(n_thermal_nonlinear));
        s.set("heat", "staggered_iterations", double(n_staggered_iterations));
      }
    for (unsigned int k = 0; k < contact.get_pairs().size(); ++k)
      {
        const auto &c = contact.totals()[k];
        const auto &name = contact.get_pairs()[k].name;
        s.set("contact", name + "_normal", c.normal);
        s.set("contact", name + "_tangential", c.tangential);
        s.set("contact", name + "_friction_work", c.friction_work);
        s.set("contact", name + "_max_penetration", c.max_penetration);
        s.set("contact", name + "_heat_exchanged", c.heat_exchanged);
        s.set("contact", name + "_friction_heat", c.friction_heat);
      }
    for (const auto &[name, value] : qoi_values)
      s.set("quantities_of_interest", name, value);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      s.write(output_dir + "/summary.json");
  }

  template class Simulator<2>;
  template class Simulator<3>;
} // namespace anvil
