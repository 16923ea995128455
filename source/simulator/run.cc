#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/input_error.h>
#include <anvil/simulator/simulator.h>
#include <anvil/material/point_driver.h>
#include <anvil/thermal/thermal_problem.h>

#include <chrono>
#include <iostream>
#include <thread>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    const char *usage =
      "usage: anvil SCENE.prm [--set 'Section/Entry=value']... [--threads N] [--check]\n"
      "       anvil --print-parameters [SCENE.prm]   every parameter as a .prm file\n"
      "       anvil --help                           this text and every parameter, documented\n"
      "       anvil --material-point POINT.prm [--set 'Section/Entry=value']... [--check]\n"
      "                                              drive one material point along a path\n"
      "       anvil --material-point --print-parameters | --help   the same for a point file\n"
      "       anvil --study STUDY.prm [--set 'Section/Entry=value']... [--jobs N] [--check]\n"
      "                                              run a study: ladders, work-precision,\n"
      "                                              stability maps (doc/study.md; anvil --study -h)\n"
      "\n"
      "  SCENE.prm      the scene to run (deal.II ParameterHandler format)\n"
      "  --set P=V      override entry P (a path like 'Time/End time') with V; repeatable\n"
      "  --check        read and check the scene and its mesh, then stop\n"
      "  --threads N    threads per process for the assembly (default: the cores given\n"
      "                 to the process, shared among the MPI processes of a node;\n"
      "                 DEAL_II_NUM_THREADS caps it)\n"
      "  --material-point  the file is a material-point driver file (Material, Path,\n"
      "                 Output), not a scene: one point along prescribed strain, stress,\n"
      "                 deformation gradient and temperature paths, written to a CSV\n"
      "Units: mm, N, s, K (stresses in MPa). Results go to Output/Directory.\n"
      "Exit status: 0 done, 2 bad input, 3 the simulation could not be completed.\n";

    template <int dim>
    void declare(ParameterHandler &prm, const Scene &scene)
    {
      Simulator<dim>::declare_parameters(prm, scene.body_names(), scene.contact_pair_names(),
                                         scene.contact_tool_names());
    }

    // --help: a scene without contact still shows what a pair's and a
    // tool's subsection hold, as Contact/<pair> and Contact/<tool>.
    template <int dim>
    void declare_with_templates(ParameterHandler &prm, const Scene &scene)
    {
      auto pairs = scene.contact_pair_names();
      auto tools = scene.contact_tool_names();
      if (pairs.empty())
        pairs = {"<pair>"};
      if (tools.empty())
        tools = {"<tool>"};
      Simulator<dim>::declare_parameters(prm, scene.body_names(), pairs, tools);
    }

    // Returns why the run stopped early, or "" (the Simulator is gone by then).
    template <int dim>
    std::string run_scene(Scene &scene, const bool check_only)
    {
      Simulator<dim> simulator(scene, MPI_COMM_WORLD);
      if (check_only)
        simulator.check();
      if (check_only || simulator.run())
        return "";
      return simulator.failure();
    }

    void read_scene(Scene &scene)
    {
      scene.read_shape();
      if (scene.dimension() == 2)
        scene.read(declare<2>);
      else
        scene.read(declare<3>);
    }

    // --material-point: one material point driven along a path (no scene).
    // The driver's file has no Dimension or Bodies: only pass two is read.
    int run_material_point(const std::string                                        &filename,
                           const std::vector<std::pair<std::string, std::string>> &overrides,
                           const bool help, const bool print, const bool check, const bool root)
    {
      const auto declare = [](ParameterHandler &prm, const Scene &) {
        MaterialPointDriver::declare_parameters(prm);
        // A body's Material block, copied from a scene, must read as is: its
        // Thermal subsection (conduction, no meaning for one point) is
        // accepted and not used. Declared here, not in material/, which
        // does not know the thermal layer.
        prm.enter_subsection("Material");
        ThermalMaterial::declare_parameters(prm);
        prm.leave_subsection();
      };
      if (help || print)
        {
          Scene scene = filename.empty() ? Scene() : Scene(filename, overrides);
          scene.read(declare);
          if (root)
            {
              if (help)
                std::cout << usage
                          << "\nMaterial-point driver parameters (with defaults, patterns and "
                             "documentation):\n\n";
              scene.parameters().print_parameters(std::cout, help ? ParameterHandler::Text :
                                                                    ParameterHandler::PRM);
            }
          return 0;
        }
      if (filename.empty())
        {
          if (root)
            std::cerr << usage;
          return 2;
        }
      Scene scene(filename, overrides);
      scene.read(declare);
      MaterialPointDriver driver(scene);
      if (check)
        {
          if (root)
            std::cout << "anvil: " << filename << " is valid" << std::endl;
          return 0;
        }
      driver.run(root, root ? &std::cout : nullptr);
      return 0;
    }
  } // namespace

  namespace
  {
    unsigned int parse_threads(const std::string &value)
    {
      try
        {
          std::size_t used = 0;
          const int   t    = std::stoi(value, &used);
          if (used == value.size() && t > 0)
            return t;
        }
      catch (...)
        {
        }
      throw InputError("--threads: expected a positive number of threads, not '" + value + "'");
    }

    // --threads N, read before MPI starts: deal.II sets the thread limit in
    // MPI_InitFinalize. Default: deal.II chooses (the cores of the node
    // divided among its MPI processes). A bad value is reported below.
    unsigned int thread_limit(int argc, char **argv)
    {
      unsigned int n = numbers::invalid_unsigned_int;
      for (int i = 1; i < argc; ++i)
        try
          {
            const std::string a = argv[i];
            if (a == "--threads" && i + 1 < argc)
              n = parse_threads(argv[i + 1]);
            else if (a.rfind("--threads=", 0) == 0)
              n = parse_threads(a.substr(10));
          }
        catch (const InputError &)
          {
          }
      return n;
    }
  } // namespace

  namespace
  {
    // One line, and not a megabyte of it: a hostile scene can put 100 000
    // characters into the value or name an error message quotes.
    std::string one_clear_line(const std::string &text)
    {
      std::string line;
      for (const char c : text)
        line += (c == '\n' || c == '\r') ? ' ' : c;
      if (line.size() <= 1200)
        return line;
      return line.substr(0, 800) + " [... " + std::to_string(line.size() - 1100) +
             " characters left out ...] " + line.substr(line.size() - 300);
    }

    // An error seen by some processes only (a formula that is not finite at a
    // point of one process, a file one process cannot write) must end all of
    // them: the others may wait in a collective call forever. The processes
    // that stop meet in a barrier of their own; if all arrive, the first one
    // prints and all return; if some do not within a few seconds, this one
    // prints its message and MPI_Abort ends the job with the same status.
    int end_with(const std::string &prefix, const std::string &message, const int status,
                 MPI_Comm errors)
    {
      const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
      if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        {
          MPI_Request request;
          MPI_Ibarrier(errors, &request);
          int          all_here = 0;
          const double start    = MPI_Wtime();
          while (!all_here && MPI_Wtime() - start < 10)
            {
              MPI_Test(&request, &all_here, MPI_STATUS_IGNORE);
              if (!all_here)
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
            }
          if (!all_here)
            {
              std::cerr << prefix << one_clear_line(message) << std::endl;
              MPI_Abort(MPI_COMM_WORLD, status);
            }
        }
      if (root)
        std::cerr << prefix << one_clear_line(message) << std::endl;
      return status;
    }
  } // namespace

  int run_anvil(int argc, char **argv)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, thread_limit(argc, argv));
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    MPI_Comm   errors; // only for end_with(): no other message may match its barrier
    MPI_Comm_dup(MPI_COMM_WORLD, &errors);

    std::string                                        filename;
    std::vector<std::pair<std::string, std::string>> overrides;
    bool help = false, print = false, check = false, material_point = false;
    try
      {
        for (int i = 1; i < argc; ++i)
          {
            const std::string a = argv[i];
            if (a == "--help" || a == "-h")
              help = true;
            else if (a == "--print-parameters")
              print = true;
            else if (a == "--check")
              check = true;
            else if (a == "--material-point")
              material_point = true;
            else if (a.rfind("--material-point=", 0) == 0)
              {
                material_point = true;
                if (!filename.empty())
                  throw InputError("more than one file given ('" + filename + "' and '" +
                                   a.substr(17) + "')");
                filename = a.substr(17);
              }
            else if (a == "--set")
              {
                if (i + 1 >= argc)
                  throw InputError("--set: expected 'Section/Entry=value' after it");
                overrides.push_back(Scene::parse_override(argv[++i]));
              }
            else if (a.rfind("--set=", 0) == 0)
              overrides.push_back(Scene::parse_override(a.substr(6)));
            else if (a == "--threads")
              {
                if (i + 1 >= argc)
                  throw InputError("--threads: expected a number of threads after it");
                parse_threads(argv[++i]);
              }
            else if (a.rfind("--threads=", 0) == 0)
              parse_threads(a.substr(10));
            else if (a.rfind("-", 0) == 0)
              throw InputError("unknown option '" + a + "' (see anvil --help)");
            else if (filename.empty())
              filename = a;
            else
              throw InputError("more than one scene file given ('" + filename + "' and '" + a + "')");
          }

        if (material_point)
          return run_material_point(filename, overrides, help, print, check, root);

        if (help || print)
          {
            Scene scene = filename.empty() ? Scene() : Scene(filename, overrides);
            if (help)
              {
                scene.read_shape();
                if (scene.dimension() == 2)
                  scene.read(declare_with_templates<2>);
                else
                  scene.read(declare_with_templates<3>);
              }
            else
              read_scene(scene);
            if (root)
              {
                if (help)
                  std::cout << usage
                            << "\nParameters (with defaults, patterns and documentation). "
                               "Contact/<pair> and Contact/<tool> stand for the subsection of "
                               "each name listed in Contact/Pairs and Contact/Tools; Bodies/body "
                               "for each name in Bodies/Names:\n\n";
                scene.parameters().print_parameters(std::cout, help ? ParameterHandler::Text
                                                                    : ParameterHandler::PRM);
              }
            return 0;
          }
        if (filename.empty())
          {
            if (root)
              std::cerr << usage;
            return 2;
          }

        Scene scene(filename, overrides);
        read_scene(scene);
        const std::string failure = scene.dimension() == 2 ? run_scene<2>(scene, check) :
                                                             run_scene<3>(scene, check);
        if (!failure.empty())
          throw SimulationError(failure);
        if (check && root)
          std::cout << "anvil: " << filename << " is valid" << std::endl;
      }
    catch (const InputError &e)
      {
        return end_with("anvil: error: ", e.what(), 2, errors);
      }
    catch (const SimulationError &e)
      {
        return end_with("anvil: simulation stopped: ", e.what(), 3, errors);
      }
    catch (const std::exception &e)
      {
        // A value its pattern accepts but strtod cannot hold (a subnormal such
        // as 1e-308 sets ERANGE): deal.II's get_double() refuses it late. It is
        // the scene's error, not ours.
        const std::string what = e.what();
        const std::string tag  = "Can't convert the parameter value <";
        const auto        at   = what.find(tag);
        const auto        mid  = at == std::string::npos ? at : what.find("> for entry <", at);
        const auto        end  = mid == std::string::npos ? mid : what.find('>', mid + 13);
        if (end != std::string::npos)
          return end_with("anvil: error: ",
                          filename + ": '" + what.substr(mid + 13, end - mid - 13) + "' = " +
                            what.substr(at + tag.size(), mid - at - tag.size()) +
                            ": not representable as a double (too small or too large); expected "
                            "a normal floating-point number",
                          2, errors);
        return end_with("anvil: internal error: ", e.what(), 1, errors);
      }
    catch (...)
      {
        return end_with("anvil: internal error: ", "an unknown exception", 1, errors);
      }
    return 0;
  }
} // namespace anvil
