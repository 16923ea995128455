// ---------------------------------------------------------------------
// step-2: extending anvil from outside the library
//
// anvil's hardening laws, thermal-softening laws, material models, tool
// shapes, coupling schemes and outputs are parts that register themselves by
// name. This program adds two parts of its own, without touching anvil:
//
//  - a hardening law, Ludwik's  σᵥ = σ₀ + K ε̄ⁿ,  with thermal softening
//    applied the way the built-in laws apply it, and exact derivatives;
//  - an output (a postprocessor): a CSV of the largest equivalent plastic
//    strain of every step and where it is.
//
// It then checks them: the law's derivatives against finite differences, a
// material point in uniaxial stress against the closed-form stress-strain
// curve (to round-off), and a block stretched by 10 % against the same curve
// at finite strain, read through the new output. It prints value against
// expected and exits with a non-zero status on a mismatch.
// ---------------------------------------------------------------------

// @sect3{Include files}
//
// The interfaces a part implements live with their registries:
// <anvil/material/hardening/interface.h> (HardeningLaw,
// ANVIL_REGISTER_HARDENING_LAW) and <anvil/postprocess/interface.h>
// (Postprocessor, ANVIL_REGISTER_POSTPROCESSOR). The rest is what step-1
// used: Scene reads a .prm file, Simulator runs it; MaterialPointDriver is
// `anvil --material-point`.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>
#include <anvil/material/j2_plasticity.h>
#include <anvil/material/point_driver.h>
#include <anvil/mechanics/mechanical_problem.h>
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace Step2
{
  using namespace dealii;

  // @sect3{The Ludwik hardening law}
  //
  // A hardening law is a class derived from anvil::HardeningLaw with three
  // duties:
  //
  //  - a static declare_parameters() declaring the entries it reads. They sit
  //    flat in `subsection Hardening` beside those of the other laws, so an
  //    entry several laws read ("Initial yield stress") is declared with
  //    declare_common_entry(), which declares it the same way for everyone;
  //    the entries only Ludwik reads get names of their own.
  //  - parse_parameters(): read and check them. An error goes through
  //    Scene::fail() with the entry's path, so the user gets one line naming
  //    the file, the line and the parameter.
  //  - evaluate(ε̄, T): σᵥ, ∂σᵥ/∂ε̄ and ∂σᵥ/∂T. It runs several times per
  //    material point update, so it does arithmetic only.
  //
  // Thermal softening: the base class owns the law θ(T) chosen in
  // `subsection Thermal softening` (the member `thermal`) and the list
  // `Softened parameters`; softened("...") says whether a parameter is
  // multiplied by θ. Ludwik's σ₀ answers to "initial yield stress" and its K
  // to "strength coefficient", the names the built-in laws use. With both
  // softened (the default, "all"),
  //
  //   σᵥ = θ(T) (σ₀ + K ε̄ⁿ),
  //   ∂σᵥ/∂ε̄ = θ(T) n K ε̄ⁿ⁻¹,
  //   ∂σᵥ/∂T = θ'(T) (σ₀ + K ε̄ⁿ).
  //
  // For n < 1 the slope is infinite at ε̄ = 0: evaluate() says so
  // (+infinity), and anvil's return map, which brackets its root, starts its
  // search away from zero.
  class LudwikHardening : public anvil::HardeningLaw
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      declare_common_entry(prm, "Initial yield stress");
      prm.declare_entry("Ludwik coefficient", "0", Patterns::Double(0),
                        "K in MPa (ludwik: s0 + K eps^n).");
      prm.declare_entry("Ludwik exponent", "0.5", Patterns::Double(0),
                        "n, dimensionless, 0 < n <= 1 (ludwik: s0 + K eps^n).");
    }

    void parse_parameters(ParameterHandler   &prm,
                          const anvil::Scene &scene,
                          const std::string  &path) override
    {
      sigma0      = prm.get_double("Initial yield stress");
      K           = prm.get_double("Ludwik coefficient");
      n           = prm.get_double("Ludwik exponent");
      soft_sigma0 = softened("initial yield stress");
      soft_K      = softened("strength coefficient");
      if (!(sigma0 > 0))
        scene.fail(path + "/Initial yield stress", "must be > 0 MPa for the ludwik model");
      if (!(n > 0 && n <= 1))
        scene.fail(path + "/Ludwik exponent", "must be in (0, 1] for the ludwik model");
    }

    Value evaluate(const double eps, const double T) const override
    {
      const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
      const double power = std::pow(eps, n); // ε̄ⁿ
      const double s0 = scale(soft_sigma0, theta) * sigma0, k = scale(soft_K, theta) * K;
      Value        v;
      v.stress = s0 + k * power;
      v.slope  = eps > 0 ? k * n * power / eps : n < 1 ? std::numeric_limits<double>::infinity() : k;
      v.temperature_derivative = scale_derivative(soft_sigma0, dtheta) * sigma0 +
                                 scale_derivative(soft_K, dtheta) * K * power;
      return v;
    }

    // The slope n K ε̄ⁿ⁻¹ has the sign of θ K (for a softened K).
    bool is_nondecreasing(const double T) const override
    {
      return scale(soft_K, thermal->factor(T)) * K >= 0;
    }

  private:
    double sigma0 = 0, K = 0, n = 0.5;
    bool   soft_sigma0 = true, soft_K = true;
  };

  // One line registers it: from now on `set Model = ludwik` is valid in every
  // `subsection Hardening` this program reads, `--help` would list it with
  // this documentation, and an unknown name lists it beside the built-in
  // ones. Registration runs before main(), when the program's static objects
  // are initialised.
  ANVIL_REGISTER_HARDENING_LAW(Step2::LudwikHardening, "ludwik",
                               "s0 + K eps^n (Ludwik 1909; Initial yield stress s0, Ludwik "
                               "coefficient K, Ludwik exponent n)")

  // @sect3{The output: the largest plastic strain}
  //
  // A postprocessor is a class template over dim derived from
  // anvil::Postprocessor<dim>. Every registered output is created for every
  // run and says whether it applies to the scene (here: when there is a
  // mechanical field). It opens its file in start() (appending after a
  // restart), writes a row for every accepted step (and t = 0), and returns
  // named results, which the Simulator prints at the end of the run and hands
  // back through quantities_of_interest().
  //
  // The equivalent plastic strain comes from the mechanics' cell averages
  // (MechanicalProblem::cell_fields(), one value per active cell, filled on
  // the cells this process owns). Where: the centre of that cell in the
  // reference configuration. With several processes every process finds its
  // own largest value; the overall largest and its place come from the
  // process that holds it.
  template <int dim>
  class LargestPlasticStrain : public anvil::Postprocessor<dim>
  {
  public:
    bool applies(const anvil::SceneContents<dim> &contents) const override
    {
      return contents.mechanics;
    }

    void start(const anvil::SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step", "time", "largest_plastic_strain", "x", "y"};
      if (dim == 3)
        columns.push_back("z");
      csv.open(s.output_directory + "/largest_plastic_strain.csv", columns, s.is_root(), append);
    }

    void accepted(const anvil::SimulationState<dim> &s,
                  const anvil::StepReport<dim> * /*report*/) override
    {
      const auto   fields = s.physics.mechanics()->cell_fields();
      const auto   column = std::find(fields.names.begin(), fields.names.end(),
                                    "equivalent_plastic_strain") - fields.names.begin();
      const auto  &eps    = fields.values[column];
      double       local  = -1;
      Point<dim>   where;
      for (const auto &cell : s.triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && eps[cell->active_cell_index()] > local)
          {
            local = eps[cell->active_cell_index()];
            where = cell->center();
          }
      // The process with the largest value (the lowest rank on a tie) sends its place.
      const auto   max   = Utilities::MPI::min_max_avg(local, s.communicator);
      largest            = max.max;
      double place[dim];
      for (unsigned int d = 0; d < dim; ++d)
        place[d] = where[d];
      MPI_Bcast(place, dim, MPI_DOUBLE, max.max_index, s.communicator);

      std::vector<double> row = {double(s.step), s.time, largest};
      row.insert(row.end(), place, place + dim);
      csv.add_row(row);
    }

    std::vector<std::pair<std::string, double>> results() const override
    {
      return {{"largest_plastic_strain", largest}};
    }

  private:
    anvil::CsvHistory csv;
    double            largest = 0;
  };

  // The macro instantiates the class for dim = 2 and 3 and registers both.
  ANVIL_REGISTER_POSTPROCESSOR(LargestPlasticStrain, "largest plastic strain",
                               "largest_plastic_strain.csv: the largest equivalent plastic strain "
                               "(cell average) of every step and the centre of its cell.")

  // @sect3{Checking the derivatives}
  //
  // anvil's Newton iterations converge quadratically only if ∂σᵥ/∂ε̄ is
  // exact, and the coupled schemes need ∂σᵥ/∂T. Central differences check
  // both, at three plastic strains and three temperatures. The law is built
  // the way a scene builds it: a J2 material from the text of a `subsection
  // Material`, whose hardening law the J2 model holds.
  bool check_derivatives()
  {
    const auto model = anvil::MaterialFactory::create_from_text(
      "set Model = J2\n"
      "subsection Elasticity\n set Young's modulus = 200000\nend\n"
      "subsection Hardening\n"
      " set Model = ludwik\n set Initial yield stress = 300\n"
      " set Ludwik coefficient = 500\n set Ludwik exponent = 0.3\n"
      " subsection Thermal softening\n  set Model = johnson-cook\n"
      "  set Melting temperature = 1700\n  set Exponent = 1.2\n end\n"
      "end\n");
    const auto &law = *dynamic_cast<const anvil::J2Model &>(*model).hardening;

    double worst_slope = 0, worst_temperature = 0;
    for (const double eps : {0.01, 0.1, 0.5})
      for (const double T : {350., 600., 900.})
        {
          const double he = 1e-6 * eps, hT = 1e-3;
          const auto   v  = law.evaluate(eps, T);
          const double slope_fd =
            (law.evaluate(eps + he, T).stress - law.evaluate(eps - he, T).stress) / (2 * he);
          const double dT_fd =
            (law.evaluate(eps, T + hT).stress - law.evaluate(eps, T - hT).stress) / (2 * hT);
          worst_slope = std::max(worst_slope, std::abs(v.slope - slope_fd) / std::abs(v.slope));
          worst_temperature = std::max(worst_temperature, std::abs(v.temperature_derivative - dT_fd) /
                                                            std::abs(v.temperature_derivative));
        }
    std::cout << "step-2: ludwik derivatives against central differences (9 points):\n"
              << "  d(sigma_v)/d(eps): largest relative difference " << worst_slope << "\n"
              << "  d(sigma_v)/dT:     largest relative difference " << worst_temperature
              << std::endl;
    return worst_slope < 1e-7 && worst_temperature < 1e-7;
  }

  // @sect3{The closed form: uniaxial stress}
  //
  // In uniaxial stress σ the von Mises stress is σ itself, and the plastic
  // strain rate has the axial component ε̄̇ (the lateral ones −ε̄̇/2). A
  // rate-independent J2 bar loaded monotonically therefore sits on the yield
  // surface, σ = σᵥ(ε̄, T), and its axial strain splits into σ/E and ε̄:
  //
  //   σ = θ(T) (σ₀ + K (ε − σ/E)ⁿ)     once ε > θσ₀/E,   σ = E ε before.
  //
  // The left side grows with σ and the right side falls, so there is one
  // root, bracketed by [θσ₀, Eε]; bisection finds it to round-off. The
  // material point driver integrates the small-strain increments exactly
  // (radial return), so it must reproduce this curve to round-off; the block
  // at finite strain does with ε the logarithmic strain, up to the time
  // integration error of the Hughes–Winget increments (order Δt²).
  double uniaxial_stress(const double strain, const double E, const double theta,
                         const double sigma0, const double K, const double n)
  {
    if (E * strain <= theta * sigma0)
      return E * strain;
    double lo = theta * sigma0, hi = E * strain;
    for (unsigned int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
      {
        const double s = 0.5 * (lo + hi);
        (s - theta * (sigma0 + K * std::pow(strain - s / E, n)) > 0 ? hi : lo) = s;
      }
    return 0.5 * (lo + hi);
  }

  // @sect3{Part 1: one material point}
  //
  // The driver file step-2-point.prm is read like a scene (strictly: every
  // entry declared, every value checked), the driver writes its CSV, and we
  // read the axial strain and stress of every step back from it. The CSV has
  // 12 significant digits, so the point must follow the closed form to
  // 1e-10 relative.
  bool check_material_point(const std::string &file)
  {
    // Relative output names belong to the driver file's directory (here the
    // source tree): write the CSV and its summary to the working directory.
    const std::string out = (std::filesystem::current_path() / "step-2-point.csv").string();
    anvil::Scene      scene(file, {{"Output/File", out}});
    scene.read([](ParameterHandler &prm, const anvil::Scene &) {
      anvil::MaterialPointDriver::declare_parameters(prm);
    });
    anvil::MaterialPointDriver driver(scene);
    driver.run(true, nullptr);

    std::ifstream            csv(driver.output_file());
    std::string              line;
    std::getline(csv, line);
    const auto names = Utilities::split_string_list(line);
    // Headers carry units ("sxx [MPa]"): match the name before " [".
    const auto col = [&](const std::string &name) {
      const auto at = std::find_if(names.begin(), names.end(), [&](const std::string &n) {
        return n.substr(0, n.find(" [")) == name;
      });
      if (at == names.end())
        throw std::runtime_error("step-2: no column '" + name + "' in " + driver.output_file());
      return std::size_t(at - names.begin());
    };
    const auto exx = col("exx"), sxx = col("sxx");

    const double theta = 1 - 1e-3 * (393 - 293); // the file's softening at 393 K
    double       worst = 0;
    std::cout << "step-2: material point in uniaxial stress at 393 K (ludwik, theta = " << theta
              << ")\n"
              << "      strain   stress (MPa)   closed form (MPa)   relative difference\n";
    unsigned int rows = 0;
    for (unsigned int step = 0; std::getline(csv, line); ++step, ++rows)
      {
        const auto   v        = Utilities::string_to_double(Utilities::split_string_list(line));
        const double expected = uniaxial_stress(v[exx], 200000, theta, 300, 500, 0.3);
        const double error    = std::abs(v[sxx] - expected) / std::max(std::abs(expected), 1.);
        worst                 = std::max(worst, error);
        if (step % 20 == 0 || step == 3)
          std::cout << std::setw(12) << v[exx] << std::setw(15) << v[sxx] << std::setw(20)
                    << expected << std::setw(22) << error << "\n";
      }
    std::cout << "  largest relative difference over every step: " << worst << std::endl;
    return worst < 1e-10 && rows > 10; // a CSV without rows must not pass
  }

  // @sect3{Part 2: a block with the new law and the new output}
  //
  // The scene is read and run like step-1's. Our postprocessor was created
  // with the others and wrote largest_plastic_strain.csv; its result is one
  // of the run's quantities of interest, beside the scene's own reaction
  // `pull`. The block's deformation is homogeneous, so the closed form gives
  // both: with ε = ln 1.1, σ from the curve above (θ = 1 at 293 K),
  // ε̄ = ε − σ/E, and the pull σ times the current section
  // exp(2 ε_lateral) = exp(−2νσ/E − ε̄).
  bool check_block(const std::string &file)
  {
    anvil::Scene scene(file, {});
    scene.read_shape();
    scene.read([](ParameterHandler &prm, const anvil::Scene &scene) {
      anvil::Simulator<3>::declare_parameters(prm, scene.body_names(), scene.contact_pair_names(),
                                              scene.contact_tool_names());
    });
    anvil::Simulator<3> simulator(scene, MPI_COMM_WORLD);
    if (!simulator.run())
      return false;

    double largest = 0, pull = 0;
    for (const auto &[name, value] : simulator.quantities_of_interest())
      {
        if (name == "largest_plastic_strain")
          largest = value;
        if (name == "pull")
          pull = value;
      }
    const double E = 200000, nu = 0.3, strain = std::log(1.1);
    const double sigma    = uniaxial_stress(strain, E, 1., 300, 500, 0.3);
    const double eps_p    = strain - sigma / E;
    const double force    = sigma * std::exp(-2 * nu * sigma / E - eps_p);
    const double error_p  = std::abs(largest - eps_p) / eps_p;
    const double error_f  = std::abs(pull - force) / force;
    std::cout << "step-2: block stretched by 10 % (ludwik, 20 steps)\n"
              << "  largest plastic strain " << largest << ", closed form " << eps_p
              << ", relative difference " << error_p << "\n"
              << "  pull " << pull << " N, closed form " << force << " N, relative difference "
              << error_f << std::endl;
    return error_p < 1e-3 && error_f < 1e-3;
  }
} // namespace Step2

// @sect3{The main function}
//
// The scene file is the first argument; the material-point file sits beside
// it. Every check prints what it compared; the exit status is 0 only if all
// of them pass, 1 on a mismatch, 2 on bad input (as anvil's own).
int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      const std::string scene_file = argc > 1 ? argv[1] : "step-2.prm";
      const auto        slash      = scene_file.find_last_of('/');
      const std::string directory =
        slash == std::string::npos ? std::string("") : scene_file.substr(0, slash + 1);

      const bool derivatives = Step2::check_derivatives();
      const bool point       = Step2::check_material_point(directory + "step-2-point.prm");
      const bool block       = Step2::check_block(scene_file);
      const bool ok          = derivatives && point && block;
      std::cout << "step-2: " << (ok ? "all checks passed" : "a check FAILED") << std::endl;
      return ok ? 0 : 1;
    }
  catch (const anvil::InputError &e)
    {
      std::cerr << "step-2: error: " << e.what() << std::endl;
      return 2;
    }
}
