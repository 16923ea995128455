// ---------------------------------------------------------------------
// step-1: using anvil as a library
//
// This program shows the smallest useful thing you can do with anvil from
// your own code: read a scene, run it, and look at its results with your own
// post-processing. Here the scene is plane-strain tension of a block, and the
// post-processing compares the reaction force with its closed form.
// ---------------------------------------------------------------------

// @sect3{Include files}
//
// anvil's headers live under <anvil/...>, one folder per concern. The
// Simulator is the time loop of a scene; Scene reads a .prm file.
#include <deal.II/base/mpi.h>

#include <anvil/core/input_error.h>
#include <anvil/simulator/simulator.h>

#include <cmath>
#include <iostream>

// @sect3{The closed form}
//
// A hypoelastic body stretched without rotation follows
// σ = λ tr(e) I + 2G e with e the logarithmic strain. In plane strain with
// the lateral face free, e_zz = 0 and σ_yy = 0 give
// e_yy = −λ e_xx / (λ + 2G), and the reaction on the pulled face is σ_xx
// times the current height h·exp(e_yy) (unit depth).
double closed_form_reaction(const double E, const double nu, const double stretch,
                            const double height)
{
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double G      = E / (2 * (1 + nu));
  const double e_xx   = std::log(stretch);
  const double e_yy   = -lambda * e_xx / (lambda + 2 * G);
  const double s_xx   = lambda * (e_xx + e_yy) + 2 * G * e_xx;
  return s_xx * height * std::exp(e_yy);
}

// @sect3{The main function}
//
// The scene file is the first argument. Scene::read_shape() reads the
// dimension and body names; Scene::read() declares every parameter of a
// two-dimensional scene and parses the file strictly. The Simulator then
// checks the scene against its mesh and runs it.
int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      const std::string file = argc > 1 ? argv[1] : "step-1.prm";
      anvil::Scene      scene(file, {});
      scene.read_shape();
      scene.read([](dealii::ParameterHandler &prm, const anvil::Scene &scene) {
        anvil::Simulator<2>::declare_parameters(prm, scene.body_names(),
                                                scene.contact_pair_names(),
                                                scene.contact_tool_names());
      });

      anvil::Simulator<2> simulator(scene, MPI_COMM_WORLD);
      // false: the run stopped on a step it could not complete (its last
      // converged state is written); its quantities would not be results.
      if (!simulator.run())
        {
          std::cerr << "step-1: simulation stopped: " << simulator.failure() << std::endl;
          return 3;
        }

      // The reaction force is one of the scene's quantities of interest.
      double pull = 0;
      for (const auto &[name, value] : simulator.quantities_of_interest())
        if (name == "pull")
          pull = value;
      const double expected = closed_form_reaction(70000, 0.3, 1.2, 2.0);
      const double error    = std::abs(pull - expected) / expected;
      std::cout << "step-1: reaction " << pull << " N, closed form " << expected
                << " N, relative error " << error << std::endl;
      return error < 1e-3 ? 0 : 1;
    }
  catch (const anvil::InputError &e)
    {
      std::cerr << "step-1: error: " << e.what() << std::endl;
      return 2;
    }
}
