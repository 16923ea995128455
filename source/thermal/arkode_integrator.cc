// The ARKode adapter: the only file of anvil that includes SUNDIALS. deal.II
// 9.4's SUNDIALS::ARKode callbacks return int (0 ok, > 0 recoverable, < 0
// fatal); from 9.5 they return void and throw. Keep it that way: one adapter.
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/sundials/arkode.h>

#include <arkode/arkode_arkstep.h>

#include "arkode_integrator.h"
#include "dirk_linear.h"
#include "integrator_guard.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

namespace anvil
{
  namespace thermal
  {
    using namespace dealii;

    namespace
    {
      /// Thrown from output_step (C++ context, outside SUNDIALS) when ARKStepEvolve
      /// returned before the end time: deal.II 9.4 does not check the status in release mode.
      struct EvolveFailed : std::runtime_error
      {
        using std::runtime_error::runtime_error;
      };

      /// (M − γJ)⁻¹ of the system as a deal.II preconditioner.
      struct NewtonPreconditioner
      {
        ImplicitSystem &system;
        unsigned long  &inner_iterations;
        void            vmult(Vector &x, const Vector &b) const
        {
          const int n = system.solve_newton_matrix(x, b);
          if (n < 0)
            throw SolverControl::NoConvergence(0, 0);
          inner_iterations += n;
        }
      };
      /// The integration in progress on this thread (ARKode's step hook has
      /// no data of ours: deal.II owns its user data).
      struct StepRecord
      {
        double time         = 0; // end of the last accepted step
        double largest_step = 0;
      };
      thread_local StepRecord *current_record = nullptr;

      /// After every accepted internal step (at its end time t): remember the
      /// largest. ARKode calls it before it updates its own last-step record.
      int record_step(realtype t, N_Vector, void *)
      {
        if (current_record)
          {
            current_record->largest_step = std::max(current_record->largest_step,
                                                    double(t) - current_record->time);
            current_record->time = t;
          }
        return 0;
      }

      /// ARKode's settings beyond deal.II's AdditionalData (called once it
      /// made its memory): the scheme, silence, limits, the first step.
      void configure(void *mem, const IntegratorSettings &settings, const double span,
                     const double t1)
      {
        if (settings.order == 1)
          {
            // Backward Euler: one stage, A = b = c = 1 (fixed steps: no embedding).
            ARKodeButcherTable table = ARKodeButcherTable_Alloc(1, SUNFALSE);
            table->q       = 1;
            table->p       = 0;
            table->A[0][0] = 1;
            table->b[0]    = 1;
            table->c[0]    = 1;
            ARKStepSetTables(mem, 1, 0, table, nullptr);
            ARKodeButcherTable_Free(table);
          }
        // ARKode's own messages (step size below round-off, mxstep reached)
        // would precede anvil's one line on a failed heat step, which names
        // the cause (a NaN boundary value, the step it cut back): silenced.
        ARKStepSetErrFile(mem, nullptr);
        ARKStepSetPostprocessStepFn(mem, record_step);
        ARKStepSetMaxNumSteps(mem, settings.max_internal_steps);
        ARKStepSetInterpolantType(mem, ARK_INTERP_LAGRANGE);
        ARKStepSetStopTime(mem, t1);
        // ARKode keeps the step while its controller would grow it by less
        // than 1.5 (fixed-step bounds 1, 1.5): the proposal then says h, not
        // the larger step the error allows, and the next call, started from
        // it, would keep cutting its span in as many steps. Bounds 1, 1 let
        // the proposal grow (source/thermal/arkode_integrator.h, next_step).
        ARKStepSetFixedStepBounds(mem, 1., 1.);
        if (settings.fixed_step_size > 0)
          {
            // Whole number of steps: h = span / ceil(span / h_fixed).
            const double n = std::max(1., std::ceil(span / settings.fixed_step_size - 1e-9));
            ARKStepSetFixedStep(mem, span / n);
          }
        else
          ARKStepSetInitStep(mem, first_step(span, settings.initial_step_size));
      }

      /// The run's counters and last/next step sizes into @p stats.
      void read_counters(void *mem, IntegratorStatistics &stats)
      {
        long  n   = 0, nfe = 0, nfi = 0;
        ARKStepGetNumSteps(mem, &n), stats.steps = n;
        ARKStepGetNumStepAttempts(mem, &n), stats.attempts = n;
        ARKStepGetNumErrTestFails(mem, &n), stats.error_test_failures = n;
        ARKStepGetNumNonlinSolvIters(mem, &n), stats.nonlinear_iterations = n;
        ARKStepGetNumNonlinSolvConvFails(mem, &n), stats.nonlinear_failures = n;
        ARKStepGetNumRhsEvals(mem, &nfe, &nfi), stats.rhs_evaluations = nfi;
        ARKStepGetLastStep(mem, &stats.last_step);
        realtype proposal = 0;
        ARKStepGetCurrentStep(mem, &proposal);
        stats.next_step = std::max(double(proposal), stats.largest_step);
      }
    } // namespace

    ButcherTable dirk_table(const unsigned int order)
    {
      ButcherTable table;
      if (order <= 1)
        {
          table.q = 1; // backward Euler, as configure() gives ARKode
          table.A = {{1.}};
          table.b = table.c = {1.};
          return table;
        }
      static const int ids[] = {ARKSTEP_DEFAULT_DIRK_2, ARKSTEP_DEFAULT_DIRK_3, ARKSTEP_DEFAULT_DIRK_4,
                                ARKSTEP_DEFAULT_DIRK_5};
      ARKodeButcherTable t =
        ARKodeButcherTable_LoadDIRK(static_cast<ARKODE_DIRKTableID>(ids[std::min(order, 5u) - 2]));
      const unsigned int s = t->stages;
      table.q              = t->q;
      table.p              = t->p;
      table.A.assign(s, std::vector<double>(s, 0.));
      for (unsigned int i = 0; i < s; ++i)
        {
          for (unsigned int j = 0; j < s; ++j)
            table.A[i][j] = t->A[i][j];
          table.b.push_back(t->b[i]);
          table.c.push_back(t->c[i]);
          if (t->d)
            table.d.push_back(t->d[i]);
        }
      ARKodeButcherTable_Free(t);
      return table;
    }

    IntegratorStatistics integrate(ImplicitSystem &system, Vector &y, const double t0,
                                   const double t1, const IntegratorSettings &settings)
    {
      if (settings.linear_stages && settings.linear && settings.jacobian_constant &&
          system.can_solve_exactly() && (settings.fixed_step_size > 0 || settings.order >= 2))
        return integrate_linear_dirk(system, y, t0, t1, settings, dirk_table(settings.order));
      IntegratorStatistics stats;
      const double         span = t1 - t0;

      SUNDIALS::ARKode<Vector>::AdditionalData data(t0, t1, span, span,
                                                    /*minimum_step_size*/ 1e-14 * span,
                                                    std::max(2u, settings.order),
                                                    settings.max_nonlinear_iterations,
                                                    /*implicit_function_is_linear*/ settings.linear,
                                                    /*implicit_function_is_time_independent*/
                                                    settings.linear && settings.jacobian_constant,
                                                    /*mass_is_time_independent*/ true,
                                                    /*anderson_acceleration_subspace*/ 3,
                                                    settings.absolute_tolerance,
                                                    settings.relative_tolerance);
      SUNDIALS::ARKode<Vector> ode(data, y.get_mpi_communicator());
      std::string              message;

      ode.reinit_vector = [&](Vector &v) { system.reinit_vector(v); };
      ode.implicit_function = [&](const double t, const Vector &u, Vector &f) {
        return guarded(message, [&] { return system.rhs(t, u, f); });
      };
      ode.jacobian_times_setup = [&](const double t, const Vector &u, const Vector &) {
        return guarded(message, [&] { return system.setup_jacobian(t, u); });
      };
      ode.jacobian_times_vector = [&](const Vector &v, Vector &Jv, double, const Vector &,
                                      const Vector &) {
        return guarded(message, [&] { return system.jacobian_vmult(v, Jv); });
      };
      // γ reaches only the preconditioner setup: build M − γJ there.
      // γ of the last setup: ARKode's current one (it sets up whenever γ
      // changes in a linear problem, at every stage otherwise).
      double setup_gamma = -1;
      ode.jacobian_preconditioner_setup = [&](double t, const Vector &u, const Vector &, int jok,
                                              int &jcur, double gamma) {
        return guarded(message, [&] {
          jcur = 0;
          if (!jok)
            {
              const int e = system.setup_jacobian(t, u);
              if (e != 0)
                return e;
              jcur = 1;
            }
          ++stats.linear_setups;
          setup_gamma = gamma;
          return system.setup_newton_matrix(gamma);
        });
      };
      ode.jacobian_preconditioner_solve = [&](double, const Vector &, const Vector &,
                                              const Vector &r, Vector &z, double, double, int) {
        return guarded(message, [&] { return system.solve_newton_matrix(z, r) < 0 ? 1 : 0; });
      };
      // Newton systems: right-preconditioned GMRES on ARKode's exact M − γJ
      // (op knows the current γ), preconditioned by our factorisation of M − γ'J
      // (γ' from the last setup): one iteration while γ is unchanged. tol is
      // ARKode's absolute bound on |b − Ax|₂.
      ode.solve_linearized_system = [&](SUNDIALS::SundialsOperator<Vector> &op,
                                        SUNDIALS::SundialsPreconditioner<Vector> &,
                                        Vector &x, const Vector &b, double tol) {
        return guarded(message, [&] {
          ++stats.linear_solves;
          if (settings.linear && system.newton_matrix_is_exact(setup_gamma))
            {
              // The factorisation is of ARKode's own matrix: one solve is the
              // answer GMRES would reach in one iteration (and one more solve).
              const int n = system.solve_newton_matrix(x, b);
              if (n < 0)
                return 1;
              stats.linear_iterations += n;
              return 0;
            }
          x = 0;
          SolverControl control(200, std::max(tol, 1e-15 * b.l2_norm()));
          SolverGMRES<Vector> gmres(control, SolverGMRES<Vector>::AdditionalData(30, true));
          NewtonPreconditioner preconditioner{system, stats.linear_iterations};
          gmres.solve(op, x, b, preconditioner);
          return 0;
        });
      };
      ode.mass_times_setup  = [](const double) { return 0; };
      ode.mass_times_vector = [&](const double, const Vector &v, Vector &Mv) {
        return guarded(message, [&] { return system.mass_vmult(v, Mv); });
      };
      ode.solve_mass = [&](SUNDIALS::SundialsOperator<Vector> &, SUNDIALS::SundialsPreconditioner<Vector> &,
                           Vector &x, const Vector &b, double tol) {
        return guarded(message, [&] {
          // An explicit first stage (ESDIRK) asks for M⁻¹ 0 at every step.
          if (b.linfty_norm() == 0)
            {
              x = 0;
              return 0;
            }
          ++stats.mass_solves;
          return system.solve_mass(x, b, tol);
        });
      };
      StepRecord record;
      record.time = t0;
      ode.custom_setup = [&](void *mem) { configure(mem, settings, span, t1); };
      ode.output_step = [&](const double t, const Vector &, const unsigned int step) {
        if (step > 0 && std::abs(t - t1) > 1e-12 * std::max(std::abs(t1), span))
          throw EvolveFailed("ARKode stopped at t = " + std::to_string(t));
      };

      current_record = &record;
      try
        {
          ode.solve_ode(y);
          stats.success = true;
        }
      catch (const std::exception &e)
        {
          stats.success = false;
          stats.failure = message.empty() ? std::string(e.what()) :
                                            std::string(e.what()) + ": " + message;
        }

      current_record = nullptr;
      stats.largest_step = record.largest_step;

      read_counters(ode.get_arkode_memory(), stats);
      return stats;
    }
  } // namespace thermal
} // namespace anvil
