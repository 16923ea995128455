// The linear heat problem's own DIRK loop (source/thermal/dirk_linear.cc) on
// M ẏ = −K y + g(t), M and K diagonal, g(t) = M ω cos ωt + K sin ωt: the
// closed form is y(t) = exp(−kt/m) + sin ωt (ẏ = −λ e^{−λt} + ω cos ωt).
// - fixed steps, ARKode's tables of order 1 to 5: the error at t = 1 falls
//   by 2^q when h halves (observed order within 0.25 of q), and the order-q
//   error is below a bound of the method's size;
// - adaptive, order 3, one call per "mechanical step" from the last call's
//   proposal: within 20 rtol of the closed form, as ARKode's own Newton path
//   on the same problem; one factorisation per call where one step passes,
//   no more than ARKode's where several are needed;
// - np 1 and np 2 (heat_dirk_linear_mpi2): the same counts, errors to round-off.
#include "check.h"
#include "diagonal_heat_system.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include "../source/thermal/dirk_linear.h"

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
  bool                   root  = true;
  constexpr double       omega = 2.;

  using Forced = anvil::testing::DiagonalHeatSystem;

  Forced make_system(const double rate)
  {
    return Forced(rate, omega, /*exact*/ true);
  }

  /// max |y(t_end) − closed form| after @p calls calls of @p span each from
  /// y(0) = 1; @p stats sums the calls' counters.
  double run(Forced &system, thermal::IntegratorSettings settings, const double span,
             const unsigned int calls, thermal::IntegratorStatistics &stats, bool &ok)
  {
    thermal::Vector y;
    system.reinit_vector(y);
    for (const auto i : system.owned)
      y(i) = 1.;
    y.compress(VectorOperation::insert);
    ok = true;
    for (unsigned int c = 0; c < calls; ++c)
      {
        const auto s = thermal::integrate(system, y, c * span, (c + 1) * span, settings);
        ok           = ok && s.success;
        settings.initial_step_size = s.next_step;
        stats.steps += s.steps;
        stats.attempts += s.attempts;
        stats.linear_setups += s.linear_setups;
        stats.linear_solves += s.linear_solves;
        stats.rhs_evaluations += s.rhs_evaluations;
      }
    const double t     = calls * span;
    double       error = 0;
    for (const auto i : system.owned)
      {
        const double exact = std::exp(-system.k[i] / system.m[i] * t) + std::sin(omega * t);
        error              = std::max(error, std::abs(y(i) - exact));
      }
    return Utilities::MPI::max(error, MPI_COMM_WORLD);
  }

  void fixed_step_order(const unsigned int order)
  {
    auto                        system = make_system(1.);
    thermal::IntegratorSettings settings;
    settings.order             = order;
    settings.linear            = true;
    settings.jacobian_constant = true;
    double       errors[2];
    const double h[2] = {0.1, 0.05};
    bool         ok   = true;
    for (unsigned int r = 0; r < 2; ++r)
      {
        settings.fixed_step_size = h[r];
        thermal::IntegratorStatistics stats;
        bool                          run_ok = false;
        errors[r] = run(system, settings, 1., 1, stats, run_ok);
        ok        = ok && run_ok && stats.linear_setups == 1 &&
             stats.steps == static_cast<unsigned long>(std::lround(1. / h[r]));
      }
    const double observed = std::log2(errors[0] / errors[1]);
    std::ostringstream label;
    label << "order " << order << ", fixed steps: ";
    if (root)
      std::cout << label.str() << "error " << std::scientific << std::setprecision(3) << errors[0] << " (h 0.1), "
                << errors[1] << " (h 0.05), observed order " << std::fixed << std::setprecision(3) << observed
                << std::defaultfloat << std::endl;
    check(ok, label.str() + "every step taken, one factorisation for the run");
    check(std::abs(observed - order) < 0.25, label.str() + "observed order within 0.25 of the method's");
    // |error| ≤ C h^q with C = 1 (measured 0.3–0.9 for orders 1–3, less above).
    check(errors[1] < std::pow(0.05, order), label.str() + "error at h = 0.05 below h^q");
  }

  void adaptive(const double span, const unsigned int calls, const bool one_step_per_call)
  {
    auto                        system = make_system(20.);
    thermal::IntegratorSettings settings;
    settings.order             = 3;
    settings.linear            = true;
    settings.jacobian_constant = true;
    thermal::IntegratorStatistics own, arkode;
    bool                          own_ok = false, arkode_ok = false;
    const double                  own_error = run(system, settings, span, calls, own, own_ok);
    settings.linear_stages                  = false;
    const double arkode_error               = run(system, settings, span, calls, arkode, arkode_ok);
    std::ostringstream label;
    label << "adaptive, span " << span << " s: ";
    if (root)
      std::cout << label.str() << "own loop " << own.steps << " steps (" << own.attempts << " attempts), "
                << own.linear_setups << " setups, " << own.linear_solves << " solves, " << own.rhs_evaluations
                << " rhs, error " << std::scientific << std::setprecision(2) << own_error << "; ARKode "
                << arkode.steps << " steps (" << arkode.attempts << "), " << arkode.linear_setups << " setups, "
                << arkode.linear_solves << " solves, " << arkode.rhs_evaluations << " rhs, error " << arkode_error
                << std::defaultfloat << std::endl;
    check(own_ok && arkode_ok, label.str() + "every call reaches its end time");
    check(own_error < 20 * settings.relative_tolerance, label.str() + "own loop within 20 rtol of the closed form");
    check(arkode_error < 20 * settings.relative_tolerance, label.str() + "ARKode within 20 rtol of the closed form");
    if (one_step_per_call)
      check(own.linear_setups <= calls + (own.attempts - own.steps),
            label.str() + "at most one factorisation per call (and per rejected step)");
    else
      check(own.linear_setups <= arkode.linear_setups, label.str() + "no more factorisations than ARKode");
    check(own.linear_solves == 3 * own.attempts, label.str() + "one linear solve per implicit stage");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  check.print_on_this_process(root);
  try
    {
      for (unsigned int order = 1; order <= 5; ++order)
        fixed_step_order(order);
      adaptive(1e-3, 40, true);  // one step per call
      adaptive(5e-2, 20, false); // several steps per call
    }
  catch (const std::exception &e)
    {
      std::cerr << "exception: " << e.what() << std::endl;
      return 2;
    }
  return check.finish();
}
