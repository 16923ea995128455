// How the ARKode adapter (source/thermal/arkode_integrator.cc) starts each
// call of a sequence, as the heat half-step calls it once per mechanical
// step: from the previous call's proposal, the span cut into equal steps.
// On M ẏ = −K y with diagonal M and K (exact: yᵢ = yᵢ(0) exp(−kᵢ t / mᵢ)):
// - where the error test allows a step of the whole span, every call after
//   the first takes one internal step, none rejected (before: the carried
//   step h < span and the remainder span − h, two steps);
// - where it does not, several steps, none rejected;
// - the answer stays within the integrator's tolerance of the closed form,
//   and the step count does not depend on the process count (np 1 = np 2).
#include "check.h"
#include "diagonal_heat_system.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include "../source/thermal/arkode_integrator.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

using namespace dealii;
using namespace anvil;

namespace
{
  anvil::testing::Checks check;
  bool                   root = true;

  /// @p calls calls of length @p span from y = 1, each starting from the last
  /// one's proposal; checks as in the file's head.
  void run(const double rate, const double span, const unsigned int calls, const bool one_step)
  {
    // ARKode's own path (not offered to the linear DIRK loop), unforced.
    anvil::testing::DiagonalHeatSystem system(rate, 0., /*exact*/ false);
    thermal::Vector y;
    system.reinit_vector(y);
    for (const auto i : system.owned)
      y(i) = 1.;
    y.compress(VectorOperation::insert);

    thermal::IntegratorSettings settings;
    settings.order             = 3;
    settings.linear            = true;
    settings.jacobian_constant = true;
    bool          no_rejections = true, one_each = true, ok = true;
    unsigned long later_steps   = 0; // after the first call
    unsigned long steps       = 0;
    for (unsigned int c = 0; c < calls; ++c)
      {
        const auto s = thermal::integrate(system, y, c * span, (c + 1) * span, settings);
        ok           = ok && s.success;
        steps += s.steps;
        settings.initial_step_size = s.next_step;
        if (c >= 2)
          no_rejections = no_rejections && s.attempts == s.steps;
        if (c >= 1)
          later_steps += s.steps;
        if (c >= calls / 2)
          {
            one_each    = one_each && s.steps == 1;
          }
      }
    double error = 0;
    for (const auto i : system.owned)
      {
        const double exact = std::exp(-system.k[i] / system.m[i] * calls * span);
        error              = std::max(error, std::abs(y(i) - exact));
      }
    error                            = Utilities::MPI::max(error, MPI_COMM_WORLD);
    const double relative_tolerance  = settings.relative_tolerance;
    std::ostringstream label;
    label << "rate " << rate << " /s, span " << span << " s: ";
    if (root)
      std::cout << label.str() << calls << " calls, " << steps << " internal steps, max |y - exact| = "
                << std::scientific << std::setprecision(2) << error << std::defaultfloat << std::endl;
    check(ok, label.str() + "every call reaches its end time");
    // Global error of a 3rd-order method at local tolerance 1e-6 over the
    // run: a few times the tolerance (the values are ≤ 1).
    check(error < 20 * relative_tolerance, label.str() + "|y − exp(−kt/m)| < 20 rtol");
    check(no_rejections, label.str() + "after the start, no rejected step");
    if (one_step)
      check(one_each, label.str() + "after the start, one internal step per call");
    else
      check(later_steps > 2 * (calls - 1), label.str() + "the error test asks for more than 2 steps per call");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  check.print_on_this_process(root);
  try
    {
      run(20., 1e-3, 40, true);  // slow decay: one step of the span passes
      run(20., 5e-2, 20, false); // fifty times the span: several steps
    }
  catch (const std::exception &e)
    {
      std::cerr << "exception: " << e.what() << std::endl;
      return 2;
    }
  return check.finish();
}
