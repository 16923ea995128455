// The linear heat problem's own DIRK loop (see dirk_linear.h): what ARKode's
// Newton machinery did around one KLU solve per stage (a residual with a
// mass product per stage, N_Vector copies and norms, two mass solves and a
// full right-hand side per step, the setup at every γ) is left out.
#include <deal.II/base/mpi.h>

#include "dirk_linear.h"
#include "integrator_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace anvil
{
  namespace thermal
  {
    using namespace dealii;

    namespace
    {
      // ARKode's defaults (ARKStep, SUNDIALS 6): the PID controller's gains on
      // the errors of this step and the two before, its safety factor and
      // error bias, the growth limits (first step, later), and the cuts after
      // an error test failure (bounds; from the second in a row at most 0.3)
      // and after a failed solve.
      constexpr double k1 = 0.58, k2 = 0.21, k3 = 0.1, safety = 0.96, bias = 1.5;
      constexpr double first_growth = 1e4, growth = 20, eta_min_fail = 0.1, eta_max_fail = 0.3,
                       eta_solve_fail = 0.25;

      /// ARKode's weighted RMS norm of @p e with weights 1/(rtol |yᵢ| + atol)
      /// from the step's start, over the global vector.
      double wrms_norm(const Vector &e, const Vector &y, const double rtol, const double atol)
      {
        double sum = 0;
        auto   ei  = e.begin();
        for (auto yi = y.begin(); yi != y.end(); ++yi, ++ei)
          {
            const double w = *ei / (rtol * std::abs(*yi) + atol);
            sum += w * w;
          }
        return std::sqrt(Utilities::MPI::sum(sum, y.get_mpi_communicator()) / y.size());
      }

      /// x = M⁻¹ b, x = 0 for b = 0 without a solve.
      int solve_mass(ImplicitSystem &system, Vector &x, const Vector &b, IntegratorStatistics &stats)
      {
        if (b.linfty_norm() == 0)
          {
            x = 0;
            return 0;
          }
        ++stats.mass_solves;
        return system.solve_mass(x, b, std::numeric_limits<double>::max());
      }

      bool stiffly_accurate(const ButcherTable &table)
      {
        const unsigned int s  = table.stages();
        bool               sa = table.c[s - 1] == 1. && table.A[s - 1][s - 1] != 0.;
        for (unsigned int j = 0; j < s; ++j)
          sa = sa && table.b[j] == table.A[s - 1][j];
        return sa;
      }

      /// The error controller's step factor after an accepted step with
      /// errors @p e (this step's first), bounded by @p max_growth.
      double accepted_factor(const double (&e)[3], const unsigned int p, const double max_growth)
      {
        const double eta = safety * std::pow(e[0], -k1 / p) * std::pow(e[1], k2 / p) * std::pow(e[2], -k3 / p);
        return std::min(eta, max_growth);
      }
      /// The stages of one step, each one solve with M − γJ (J constant in
      /// the step: the problem is linear), zᵢ = y + (M − γJ)⁻¹ (γ f(tᵢ, y) +
      /// h Σⱼ<ᵢ aᵢⱼ fⱼ), then fᵢ = f(tᵢ, zᵢ) evaluated, not deduced, so that
      /// the heat balance closes to round-off.
      struct StageSolver
      {
        ImplicitSystem       &system;
        const ButcherTable   &table;
        IntegratorStatistics &stats;
        std::string          &message;
        std::vector<Vector>  &f;
        Vector               &z, &b;
        const bool            explicit_first;
        double                setup_gamma = -1; // γ of the factorisation
        bool                  have_f0     = false;
        // f(t, y) of this attempt where f does not depend on t: every stage's
        // γ f(tᵢ, y) from it (the same evaluation, the same bits), one
        // evaluation per step instead of one per stage.
        const bool            time_independent = system.rhs_independent_of_time();
        Vector                f_y;

        /// 0: done; > 0: recoverable (a shorter step); < 0: not.
        int solve(const Vector &y, const double t, const double t_new, const double h)
        {
          bool have_fy = false;
          for (unsigned int i = 0; i < table.stages(); ++i)
            {
              int          status = 0;
              const double t_i    = table.c[i] == 1. ? t_new : t + table.c[i] * h;
              if (i == 0 && explicit_first)
                {
                  if (!have_f0)
                    {
                      ++stats.rhs_evaluations;
                      status  = guarded(message, [&] { return system.rhs(t, y, f[0]); });
                      have_f0 = status == 0;
                    }
                  if (status != 0)
                    return status;
                  continue;
                }
              const double gamma = h * table.A[i][i];
              if (gamma != setup_gamma)
                {
                  ++stats.linear_setups;
                  status = guarded(message, [&] { return system.setup_exact_newton_matrix(gamma); });
                  if (status != 0)
                    return status;
                  setup_gamma = gamma;
                }
              const Vector *known = !time_independent ? nullptr : explicit_first ? &f[0] : have_fy ? &f_y : nullptr;
              if (known)
                b = *known;
              else
                {
                  ++stats.rhs_evaluations;
                  status = guarded(message, [&] { return system.rhs(t_i, y, b); });
                  if (status != 0)
                    return status;
                  if (time_independent)
                    {
                      f_y     = b;
                      have_fy = true;
                    }
                }
              b *= gamma;
              for (unsigned int j = 0; j < i; ++j)
                if (table.A[i][j] != 0.)
                  b.add(h * table.A[i][j], f[j]);
              ++stats.linear_solves;
              ++stats.nonlinear_iterations;
              status = guarded(message, [&] {
                const int n = system.solve_newton_matrix(z, b);
                if (n < 0)
                  return 1;
                stats.linear_iterations += n;
                return 0;
              });
              if (status != 0)
                return status;
              z += y;
              ++stats.rhs_evaluations;
              status = guarded(message, [&] { return system.rhs(t_i, z, f[i]); });
              if (status != 0)
                return status;
            }
          return 0;
        }
      };
    } // namespace

    IntegratorStatistics integrate_linear_dirk(ImplicitSystem &system, Vector &y, const double t0,
                                               const double t1, const IntegratorSettings &settings,
                                               const ButcherTable &table)
    {
      IntegratorStatistics stats;
      std::string          message;
      const unsigned int   s        = table.stages();
      const double         span     = t1 - t0;
      const bool           adaptive = !(settings.fixed_step_size > 0);
      const bool           sa       = stiffly_accurate(table);
      // An explicit first stage at c = 0 (ESDIRK): f(t, y), after an accepted
      // step of a stiffly accurate table the last stage's f.
      const bool explicit_first = table.A[0][0] == 0. && table.c[0] == 0.;
      auto       fail           = [&](const std::string &why) {
        stats.success = false;
        stats.failure = message.empty() ? why : why + ": " + message;
        return stats;
      };
      if (adaptive && table.d.empty())
        return fail("an adaptive step needs an embedded method (order ≥ 2)");
      for (unsigned int i = 1; i < s; ++i)
        if (table.A[i][i] == 0.)
          return fail("only the first stage of the table may be explicit");

      // y's layout (its map shared, not built anew from the index set).
      std::vector<Vector> f(s);
      Vector              z, b, y_new, error;
      for (auto *v : {&z, &b, &y_new, &error})
        v->reinit(y);
      for (auto &v : f)
        v.reinit(y);

      StageSolver stages{system, table, stats, message, f, z, b, explicit_first};
      if (guarded(message, [&] { return system.setup_jacobian(t0, y); }) != 0)
        return fail("the heat Jacobian could not be set up");

      double h = span;
      if (!adaptive)
        h = span / std::max(1., std::ceil(span / settings.fixed_step_size - 1e-9));
      else if (settings.initial_step_size > 0)
        h = first_step(span, settings.initial_step_size);
      const double h_min       = 1e-14 * span;
      double       t           = t0;
      double       proposal    = 0;
      double       errors[3]   = {1, 1, 1}; // ARKode's history starts at 1
      unsigned int failures_in_row = 0;
      while (t1 - t > 1e-12 * span)
        {
          if (stats.attempts >= settings.max_internal_steps)
            return fail("more than " + std::to_string(settings.max_internal_steps) + " internal steps");
          const double remaining = t1 - t;
          if (h > remaining * (1 + 1e-10))
            h = remaining;
          // A step within round-off of the remainder ends at t1 itself and
          // keeps h (and with it γ and the factorisation).
          const bool   last  = h >= remaining * (1 - 1e-10);
          const double t_new = last ? t1 : t + h;
          ++stats.attempts;

          const int status = stages.solve(y, t, t_new, h);
          if (status < 0)
            return fail("a heat stage failed");
          if (status > 0)
            {
              // Recoverable (a linear solver, a boundary value): a shorter step.
              ++stats.nonlinear_failures;
              h *= eta_solve_fail;
              if (h < h_min)
                return fail("the step fell below 1e-14 of the span after failed stages");
              continue;
            }

          if (sa)
            y_new.swap(z);
          else
            {
              b = 0;
              for (unsigned int j = 0; j < s; ++j)
                b.add(h * table.b[j], f[j]);
              if (guarded(message, [&] { return solve_mass(system, y_new, b, stats); }) != 0)
                return fail("a mass solve failed");
              y_new += y;
            }
          double dsm = 0;
          if (adaptive)
            {
              b = 0;
              for (unsigned int j = 0; j < s; ++j)
                if (table.b[j] != table.d[j])
                  b.add(h * (table.b[j] - table.d[j]), f[j]);
              if (guarded(message, [&] { return solve_mass(system, error, b, stats); }) != 0)
                return fail("a mass solve failed");
              dsm = wrms_norm(error, y, settings.relative_tolerance, settings.absolute_tolerance);
              if (!(dsm <= 1.))
                {
                  ++stats.error_test_failures;
                  ++failures_in_row;
                  double eta = std::max(eta_min_fail, safety * std::pow(bias * dsm, -1. / table.p));
                  if (failures_in_row >= 2 || !std::isfinite(dsm))
                    eta = std::min(eta, eta_max_fail);
                  h *= std::isfinite(eta) ? std::min(eta, 1.) : eta_min_fail;
                  if (h < h_min)
                    return fail("the step fell below 1e-14 of the span at the error test");
                  continue;
                }
            }

          // Accepted.
          failures_in_row = 0;
          ++stats.steps;
          stats.last_step    = t_new - t;
          stats.largest_step = std::max(stats.largest_step, stats.last_step);
          y.swap(y_new);
          stages.have_f0 = sa && explicit_first;
          if (stages.have_f0)
            f[0].swap(f[s - 1]); // f(t_new, z_s) = f(t_new, y)
          t = t_new;
          if (!adaptive)
            continue;
          errors[2] = errors[1];
          errors[1] = errors[0];
          errors[0] = std::max(bias * dsm, 1e-10);
          proposal  = h * accepted_factor(errors, table.p, stats.steps == 1 ? first_growth : growth);
          if (!last)
            {
              // The rest in equal steps near the proposal; the same h (γ) where it is one.
              const double next = first_step(t1 - t, proposal);
              if (std::abs(next / h - 1) > 1e-10)
                h = next;
            }
        }
      stats.success   = true;
      stats.next_step = std::max(proposal, stats.largest_step);
      return stats;
    }
  } // namespace thermal
} // namespace anvil
