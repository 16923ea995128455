#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/expression.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/simulator/simulator.h>

#include "step_clock.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // ANVIL_RANK_FAULT=R:N (tests only): process R alone fails after step N,
    // while the others go on into the next step's collective calls and wait
    // there: the case run.cc's end_with() must end by MPI_Abort.
    void injected_fault(const unsigned int step)
    {
      const char *fault = std::getenv("ANVIL_RANK_FAULT");
      if (!fault)
        return;
      const std::string f(fault), rank = f.substr(0, f.find(':'));
      if (rank == std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)) &&
          f.substr(f.find(':') + 1) == std::to_string(step))
        throw SimulationError("injected fault on process " + rank + " after step " +
                              std::to_string(step) + " (ANVIL_RANK_FAULT)");
    }
  } // namespace

  namespace
  {
    /// ANVIL_ETA_CLOCK=iterations (tests only): the progress line's clock
    /// counts Newton iterations, failed attempts included, instead of wall
    /// seconds, so that tests/eta_cut_back.py can hold the ETA's arithmetic
    /// against the work that was then actually left, whatever the machine's load.
    bool iteration_clock()
    {
      static const bool on = std::getenv("ANVIL_ETA_CLOCK") &&
                             std::string(std::getenv("ANVIL_ETA_CLOCK")) == "iterations";
      return on;
    }

    /// Resident memory of this process now, MB (/proc/self/status VmRSS).
    double resident_memory_mb()
    {
      std::ifstream status("/proc/self/status");
      for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0)
          return std::stod(line.substr(6)) / 1024.;
      return 0;
    }
  } // namespace

  template <int dim>
  void Simulator<dim>::declare_parameters(ParameterHandler               &prm,
                                          const std::vector<std::string> &body_names,
                                          const std::vector<std::string> &contact_pair_names,
                                          const std::vector<std::string> &contact_tool_names)
  {
    Scene::declare_shape_parameters(prm);
    declare_coupling_parameters<dim>(prm);
    CoupledProblem<dim>::declare_parameters(prm, body_names, contact_pair_names,
                                            contact_tool_names);
    Geometry<dim>::declare_parameters(prm);

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
    prm.declare_entry("Breakpoints", "", Patterns::List(Patterns::Double(0)),
                      "Times in s, increasing, > 0, where the loading changes character (end of "
                      "a ramp, start of an unloading): a step lands on each and the next one "
                      "restarts from 'Step after breakpoint'. Those past End time are ignored "
                      "(a shortened run keeps the scene's list). Empty: none.");
    prm.declare_entry("Step after breakpoint", "0", Patterns::Double(0),
                      "First step after a breakpoint, s; 0 means Time step.");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "", Patterns::Anything(),
                      "Where fields, histories and summary.json go; empty means "
                      "output/<scene name> in the working directory.");
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
    declare_postprocessor_parameters<dim>(prm);
  }

  template <int dim>
  Simulator<dim>::Simulator(Scene &scene, MPI_Comm communicator)
    : scene(scene)
    , mpi_communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    auto &prm = scene.parameters();
    geometry.parse_parameters(prm, scene);
    triangulation = geometry.make_triangulation(communicator);
    // Bodies: every mesh body needs a material, every listed body must exist.
    for (const auto &[name, id] : geometry.body_names())
      if (std::find(scene.body_names().begin(), scene.body_names().end(), name) ==
          scene.body_names().end())
        scene.fail("Bodies/Names", "does not list the mesh body '" + name +
                                     "' (the mesh has: " + geometry.list_body_names() +
                                     "; a generated mesh's body is named by Geometry/Body "
                                     "name, blocks by Geometry/Blocks, a gmsh mesh by its "
                                     "physical names)");

    coupling = prm.get({"Physics"}, "Coupling");
    scheme   = CouplingSchemeRegistry<dim>::instance().create(coupling);
    scheme->parse_parameters(prm, scene);
    physics.parse_parameters(prm, scene, geometry, scheme->needs_mechanics(),
                             scheme->needs_heat_equation(), coupling);
    contents.mechanics   = scheme->needs_mechanics();
    contents.heat        = scheme->needs_heat_equation();
    contents.temperature = scheme->provides_temperature();
    contents.steady_heat = contents.heat && (physics.heat_parameters().steady ||
                                             physics.heat_parameters().steady_initial);
    contents.geometry    = &geometry;
    contents.contact     = &physics.contact_problem();
    parse_time(prm);
    parse_output(prm);
  }

  template <int dim>
  Simulator<dim>::~Simulator() = default;

  template <int dim>
  void Simulator<dim>::parse_time(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    time.end_time          = prm.get_double("End time");
    time.time_step         = prm.get_double("Time step");
    time.minimum_time_step = prm.get_double("Minimum time step");
    time.maximum_time_step = prm.get_double("Maximum time step");
    time.growth_factor     = prm.get_double("Growth factor");
    time.easy_iterations   = prm.get_integer("Easy step iterations");
    const auto breakpoints = Utilities::string_to_double(
      Utilities::split_string_list(prm.get("Breakpoints")));
    time.step_after_breakpoint = prm.get_double("Step after breakpoint");
    prm.leave_subsection();
    for (unsigned int i = 0; i < breakpoints.size(); ++i)
      if (!(breakpoints[i] > (i == 0 ? 0. : breakpoints[i - 1])))
        scene.fail("Time/Breakpoints", "= " + Utilities::to_string(breakpoints[i]) +
                                         " s: expected increasing times > 0 s");
    time.breakpoints = StepBreakpoints(breakpoints);
    if (time.step_after_breakpoint == 0)
      time.step_after_breakpoint = time.time_step;
    if (!(time.time_step > 0))
      scene.fail("Time/Time step", "must be > 0 s");
    if (time.minimum_time_step == 0)
      time.minimum_time_step = time.time_step / 1024;
    if (time.maximum_time_step == 0)
      time.maximum_time_step = time.time_step;
    if (time.minimum_time_step > time.time_step)
      scene.fail("Time/Minimum time step", "must not exceed Time step");
    if (time.maximum_time_step < time.time_step)
      scene.fail("Time/Maximum time step", "= " + Utilities::to_string(time.maximum_time_step) +
                                             " s must not be smaller than Time step = " +
                                             Utilities::to_string(time.time_step) + " s");
  }

  template <int dim>
  void Simulator<dim>::parse_output(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    output_dir          = prm.get("Directory");
    checkpoint_interval = prm.get_integer("Checkpoint interval");
    restart_directory   = trim(prm.get("Restart from"));
    quiet               = prm.get("Verbosity") == "quiet";
    prm.leave_subsection();
    if (output_dir.empty())
      output_dir = "output/" +
                   std::filesystem::path(scene.filename().empty() ? "anvil" : scene.filename())
                     .stem()
                     .string();
    // A run killed between the two renames of write_checkpoint() has left its
    // last good checkpoint as <dir>.old: resume from that one.
    namespace fs = std::filesystem;
    if (!restart_directory.empty() && !fs::exists(restart_directory + "/state.txt") &&
        fs::exists(restart_directory + ".old/state.txt"))
      restart_directory += ".old";
    if (!restart_directory.empty())
      check_checkpoint();
    for (const auto &entry : PostprocessorRegistry<dim>::instance().all())
      {
        auto output = entry.create();
        output->parse_parameters(prm, scene, contents);
        if (output->applies(contents))
          outputs.push_back(std::move(output));
      }
    // Last: a scene with an error elsewhere leaves no directory behind.
    check_output_directory();
  }

  template <int dim>
  void Simulator<dim>::check_output_directory() const
  {
    // Before any work, on every rank the same answer: an output directory
    // that cannot be written would otherwise end the run at its first output.
    std::string problem;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::error_code ec;
        std::filesystem::create_directories(output_dir + "/fields", ec);
        const std::string probe = output_dir + "/.anvil_write_test";
        if (ec)
          problem = "cannot be created (" + ec.message() + ")";
        else if (!std::ofstream(probe).good())
          problem = "is not writable";
        std::filesystem::remove(probe, ec);
      }
    problem = Utilities::MPI::broadcast(mpi_communicator, problem, 0);
    if (!problem.empty())
      scene.fail("Output/Directory", "= '" + output_dir + "' " + problem);
  }

  template <int dim>
  void Simulator<dim>::setup()
  {
    TimerOutput::Scope t(*timer, "Mesh");
    if (restart_directory.empty())
      geometry.create(*triangulation);
    else
      geometry.load(*triangulation, restart_directory + "/mesh");
  }

  template <int dim>
  SimulationState<dim> Simulator<dim>::state(const double t, const unsigned int step,
                                             const bool last) const
  {
    SimulationState<dim> s{scene,    mpi_communicator, *triangulation, geometry, physics,
                           coupling, output_dir,       statistics,    *timer};
    s.time      = t;
    s.step      = step;
    s.last_step = last;
    return s;
  }

  template <int dim>
  bool Simulator<dim>::run()
  {
    try
      {
        return run_steps();
      }
    catch (...)
      {
        // Without this the TimerOutput, destroyed during the unwinding, prints
        // deal.II's banner about uncaught exceptions before anvil's one line.
        timer.reset();
        throw;
      }
  }

  template <int dim>
  void Simulator<dim>::check()
  {
    timer = std::make_unique<TimerOutput>(mpi_communicator, pcout, TimerOutput::never,
                                          TimerOutput::wall_times);
    try
      {
        setup();
        check_against_mesh();
      }
    catch (...)
      {
        timer.reset();
        throw;
      }
    timer.reset();
  }

  template <int dim>
  void Simulator<dim>::check_against_mesh()
  {
    physics.check_temperatures(*triangulation, scene, time.end_time, !scheme->provides_temperature());
    scheme->check(*triangulation, scene, time.end_time);
    for (auto &o : outputs)
      o->check(state(0, 0));
  }

  template <int dim>
  bool Simulator<dim>::run_steps()
  {
    wall_start         = MPI_Wtime();
    baseline_memory_mb = resident_memory_mb();
    timer = std::make_unique<TimerOutput>(mpi_communicator, pcout, TimerOutput::never,
                                          TimerOutput::wall_times);
    setup();
    check_against_mesh();
    physics.setup(*triangulation, *timer, quiet);
    scheme->initialize(physics);
    double t  = 0;
    double dt = time.time_step;
    if (!restart_directory.empty())
      {
        read_checkpoint(t, dt);
        physics.restarted();
        // The scene's step settings apply to the continuation (a checkpoint
        // written after a cut-back cascade would otherwise impose its tiny or,
        // after re-growth, its large step).
        const double saved = dt;
        dt                 = std::min({dt, time.time_step, time.maximum_time_step});
        if (!quiet)
          pcout << "anvil: restarting at t = " << t << " s from " << restart_directory
                << " with dt = " << dt << " s (saved step " << saved << " s, Time/Time step "
                << time.time_step << " s)" << std::endl;
      }
    double last_accepted_step = dt;

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::filesystem::create_directories(output_dir + "/fields");
    MPI_Barrier(mpi_communicator);
    print_start();
    for (auto &o : outputs)
      o->start(state(t, statistics.steps), !restart_directory.empty());
    if (restart_directory.empty())
      {
        TimerOutput::Scope s(*timer, "Output");
        for (auto &o : outputs)
          o->initial(state(0, 0));
      }
    throw_recorded_input_error(mpi_communicator);
    if (!physics.initial_failure().empty())
      {
        // The steady initial field did not converge: its last iterate is in the fields.
        stop("failed at t = 0 s: " + physics.initial_failure(), t, dt);
        return false;
      }
    const double eps = 1e-12 * time.end_time;
    while (t < time.end_time - eps)
      {
        // The steps' own work, attempts and commit included, without the
        // outputs and checkpoints: what perf.py sets against one assembly and
        // one linear solve per Newton iteration. The set-up before the first
        // step and the closing after the last are paid once per run.
        step_clock_detail::StepClock steps(step_loop_wall, step_loop_cpu);
        const double step = time.breakpoints.clip(t, std::min(dt, time.end_time - t), eps);
        auto         r    = scheme->advance(t, t + step);
        // A formula that gave NaN or inf is the scene's error: no cut-back.
        throw_recorded_input_error(mpi_communicator);
        r.time_step       = step;
        statistics.newton_iterations += r.mechanics_iterations();
        statistics.linear_iterations += r.linear_iterations();
        statistics.heat_internal_steps += r.thermal.internal_steps;
        statistics.heat_nonlinear_iterations += r.thermal.nonlinear_iterations;
        statistics.staggered_iterations += r.staggered_iterations;
        for (auto &o : outputs)
          o->attempt(state(t + step, statistics.steps), r);
        if (!r.converged)
          {
            ++statistics.cut_backs;
            dt = step / 2;
            if (!quiet)
              pcout << "  step at t = " << t + step << " s failed: " << r.failure
                    << "; cutting back to dt = " << dt << " s" << std::endl;
            if (dt < time.minimum_time_step * (1 - 1e-12))
              {
                steps.stop();
                stop("failed at t = " + Utilities::to_string(t + step) + " s: " + r.failure +
                       "; minimum time step " + Utilities::to_string(time.minimum_time_step) +
                       " s reached",
                     t, last_accepted_step);
                return false;
              }
            continue;
          }

        scheme->commit(t, t + step);
        steps.stop();
        injected_fault(statistics.steps + 1);
        last_accepted_step = step;
        t                  = t + step;
        current_time       = t;
        ++statistics.steps;
        const bool last = t >= time.end_time - eps;
        output_step(&r, t, last);
        if (last || (checkpoint_interval > 0 && statistics.steps % checkpoint_interval == 0))
          try
            {
              write_checkpoint(t, dt);
            }
          catch (const SimulationError &e)
            {
              // The histories are complete up to t: close them and say why.
              for (auto &o : outputs)
                o->finish(state(t, statistics.steps), true);
              write_summary(std::string("stopped: ") + e.what());
              throw;
            }
        step_clock_detail::StepClock rest_of_step(step_loop_wall, step_loop_cpu);
        if (!quiet)
          print_step(r, t, step);
        // A converged state whose temperature the yield stress does not
        // survive (softening past its vanishing temperature): every later
        // step would fail, so stop here with this state written.
        if (physics.mechanics())
          if (const std::string lost = physics.mechanics()->strength_lost(t); !lost.empty())
            {
              rest_of_step.stop();
              stop(lost, t, step);
              return false;
            }
        dt = scheme->easy(r, time.easy_iterations) ?
               std::min(step * time.growth_factor, time.maximum_time_step) :
               step;
        // The next phase starts like the run: small, growing while Newton is easy.
        if (time.breakpoints.lands_on(t, eps))
          dt = time.step_after_breakpoint;
      }

    throw_recorded_input_error(mpi_communicator);
    for (auto &o : outputs)
      o->finish(state(t, statistics.steps, true), false);
    write_summary("completed");
    if (!quiet)
      {
        timer->print_summary();
        std::map<std::string, std::string> units, notes;
        for (const auto &o : outputs)
          {
            for (const auto &[name, unit] : o->units())
              units[name] = unit;
            for (const auto &[name, note] : o->notes())
              notes[name] = note;
          }
        for (const auto &[name, value] : quantities_of_interest())
          pcout << "  " << name << " = " << std::setprecision(10) << value
                << (units[name].empty() || units[name] == "-" ? "" : " " + units[name])
                << (notes[name].empty() ? "" : "  (" + notes[name] + ")") << std::endl;
      }
    print_results();
    return true;
  }

  template <int dim>
  void Simulator<dim>::output_step(const StepReport<dim> *r, const double t, const bool last)
  {
    TimerOutput::Scope s(*timer, "Output");
    for (auto &o : outputs)
      o->accepted(state(t, statistics.steps, last), r);
  }

  template <int dim>
  void Simulator<dim>::stop(const std::string &status, const double t,
                            const double last_accepted_step)
  {
    {
      TimerOutput::Scope s(*timer, "Output");
      for (auto &o : outputs)
        o->finish(state(t, statistics.steps), true);
    }
    // Resume with the step of the last accepted one, not the cut one.
    try
      {
        write_checkpoint(t, last_accepted_step);
      }
    catch (const SimulationError &e)
      {
        write_summary(status + "; " + e.what());
        throw SimulationError(status + "; " + e.what());
      }
    write_summary(status);
    failure_reason =
      status + " (last converged state and a checkpoint written to " + output_dir + ")";
  }

  template <int dim>
  std::vector<std::pair<std::string, double>> Simulator<dim>::quantities_of_interest() const
  {
    std::vector<std::pair<std::string, double>> all;
    for (const auto &o : outputs)
      for (const auto &v : o->results())
        all.push_back(v);
    return all;
  }

  template <int dim>
  void Simulator<dim>::print_start() const
  {
    if (quiet)
      return;
    pcout << "anvil: " << scene.filename() << ", " << dim << "D, "
          << triangulation->n_global_active_cells() << " cells, ";
    if (physics.mechanics())
      pcout << physics.mechanics()->n_dofs() << " displacement DoFs, ";
    if (physics.heat())
      pcout << physics.heat()->n_dofs() << " temperature DoFs, ";
    pcout << coupling << ", " << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " process(es) x " << MultithreadInfo::n_threads() << " thread(s) -> " << output_dir
          << std::endl;
  }

  template <int dim>
  void Simulator<dim>::print_step(const StepReport<dim> &r, const double t, const double step) const
  {
    // The ETA from the rate of the last few steps (wall clock per simulated
    // second, the failed attempts in between included): after a cut-back
    // the steps are small and the rest of the run is that slow too, which an
    // average since the start would hide.
    const bool   counted = iteration_clock();
    const double now     = counted ? double(statistics.newton_iterations) : MPI_Wtime();
    recent_steps.emplace_back(now, t);
    if (recent_steps.size() > 6)
      recent_steps.erase(recent_steps.begin());
    const auto  &first = recent_steps.size() > 1 ? recent_steps.front() :
                                                   std::make_pair(counted ? 0. : wall_start, 0.);
    const double rate  = t > first.second ? (now - first.first) / (t - first.second) : 0;
    const double eta   = rate * (time.end_time - t);
    std::ostringstream line;
    line << "step " << std::setw(5) << statistics.steps << "  t = " << std::scientific
         << std::setprecision(4) << t << " / " << std::setprecision(3) << time.end_time << " s ("
         << std::fixed << std::setprecision(1) << std::setw(5) << 100 * t / time.end_time
         << " %)  dt = " << std::scientific << std::setprecision(2) << step << " s";
    if (physics.mechanics())
      line << "  Newton " << std::setw(2) << r.mechanics().iterations << " |R| "
           << std::setprecision(1) << r.mechanics().residuals.front() << " -> "
           << r.mechanics().residuals.back() << " N";
    if (physics.transient_heat())
      line << "  heat " << r.thermal.internal_steps << " steps";
    else if (physics.heat())
      line << "  steady heat Newton " << r.thermal.nonlinear_iterations << " its";
    if (r.staggered_iterations > 0)
      line << "  staggered " << r.staggered_iterations << " its, dT " << std::setprecision(1)
           << r.staggered_change << " K, contraction " << std::setprecision(2) << r.contraction;
    line << "  ETA " << std::fixed << std::setprecision(1) << eta << " s";
    if (counted)
      line << " (clock: " << std::setprecision(0) << now << " Newton iterations)";
    pcout << line.str() << std::endl;
  }

  template <int dim>
  void Simulator<dim>::print_results() const
  {
    if (quiet || Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    // What is on disk now (a restart's files included), files first, then
    // each directory with its number of files.
    std::vector<std::string> files, directories;
    std::error_code          ec;
    for (const auto &e : std::filesystem::directory_iterator(output_dir, ec))
      {
        const std::string name = e.path().filename().string();
        if (e.is_directory())
          {
            const auto n = std::distance(std::filesystem::directory_iterator(e.path(), ec),
                                         std::filesystem::directory_iterator());
            directories.push_back(name + "/ (" + std::to_string(n) + ")");
          }
        else if (name[0] != '.')
          files.push_back(name);
      }
    std::sort(files.begin(), files.end());
    std::sort(directories.begin(), directories.end());
    files.insert(files.end(), directories.begin(), directories.end());
    std::string list;
    for (const auto &f : files)
      list += (list.empty() ? "" : ", ") + f;
    std::cout << "anvil: results in " << output_dir << ": " << list << std::endl;
  }

  ANVIL_INSTANTIATE_CLASS(Simulator)
} // namespace anvil
